#include "app/interrupt.hpp"

#include <atomic>
#include <stdexcept>

namespace lpsim {

namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

// The one piece of process-wide state in LPSim: a signal handler can reach nothing else. It holds the
// first signal received while a guard is installed (0: none, -1: no guard installed). A lock-free atomic,
// so that the handler may set it whichever thread the signal lands on.
std::atomic<int> g_received{-1};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void record_interrupt(int signal) {
  int none = 0;
  g_received.compare_exchange_strong(none, signal);
  // Any further signal acts as if no handler had been installed (sigaction is async-signal-safe).
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  for (int s : kSignals) sigaction(s, &fallback, nullptr);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  int none = -1;
  if (!g_received.compare_exchange_strong(none, 0))
    throw std::logic_error("InterruptGuard: a guard is installed already");
  struct sigaction action {};
  action.sa_handler = record_interrupt;
  sigemptyset(&action.sa_mask);
  // Interrupted system calls (an output's write) resume rather than fail with EINTR.
  action.sa_flags = SA_RESTART;
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &action, &previous_[k]);
}

InterruptGuard::~InterruptGuard() {
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &previous_[k], nullptr);
  g_received.store(-1);
}

int InterruptGuard::received() const { return g_received.load(); }

int pending_interrupt() {
  const int s = g_received.load();
  return s > 0 ? s : 0;
}

bool interrupted_status(int code) {
  for (int s : kSignals)
    if (code == 128 + s) return true;
  return false;
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

}  // namespace lpsim

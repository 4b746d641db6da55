#pragma once
// Ending `lpsim run` cleanly on SIGINT, SIGTERM and SIGHUP: while an InterruptGuard lives, the first of these
// signals is only recorded, so that the run can stop at the end of its current step and close its outputs
// well-formed; any further one has its default effect again (a second Ctrl-C kills, as usual).
#include <csignal>

namespace lpsim {

class InterruptGuard {
 public:
  /// Installs the handlers (the process must hold at most one guard at a time: std::logic_error otherwise).
  InterruptGuard();
  /// Puts back the handlers that were there before.
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// The signal received since the guard was installed, or 0.
  int received() const;

 private:
  struct sigaction previous_[3];
};

/// "SIGINT", "SIGTERM" or "SIGHUP" (the signals a guard records), else "a signal".
const char* signal_name(int signal);

/// The signal a guard installed anywhere in the process has recorded, or 0 (also without a guard): for waits
/// deep in a command (a SUMO starting) that must give up at once on a signal.
int pending_interrupt();

/// Whether exit status `code` is that of a run stopped by one of those signals (128 + the signal).
bool interrupted_status(int code);

}  // namespace lpsim

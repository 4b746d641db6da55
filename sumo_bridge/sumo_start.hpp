#pragma once
// Starting SUMO for a SumoLink: the binary found, a `sumo` process on a free local port watched while it
// starts, and the two client libraries' ways in (libsumo_link.cpp, traci_link.cpp).
#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "sumo_bridge/sumo_link.hpp"

namespace lpsim {

/// `name` itself when it contains a '/', else the first executable `name` on PATH; a SumoError when none.
std::string find_sumo_binary(const std::string& name);

/// A SUMO process serving TraCI on 127.0.0.1:port, with a watchdog: a call to it that does not return within
/// the answer timeout has the process killed, so that the client's blocked socket read fails instead of
/// waiting for ever.
class SumoProcess {
 public:
  /// Starts `binary` with `args` and --remote-port on a free port.
  SumoProcess(const std::string& binary, const std::vector<std::string>& args, double answer_timeout_s);
  ~SumoProcess();  // kills it if it still runs
  SumoProcess(const SumoProcess&) = delete;
  SumoProcess& operator=(const SumoProcess&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  double answer_timeout() const { return answer_timeout_s_; }
  /// Whether it has ended; then its exit status (or 128 + the signal that ended it) in *status.
  bool ended(int* status);
  /// Waits up to timeout_s for it to end (after the client closed it), then kills it.
  void finish(double timeout_s);

  /// While a Call lives, the watchdog kills the process once `seconds` have passed.
  class Call {
   public:
    Call(SumoProcess& p, double seconds);
    ~Call();
    Call(const Call&) = delete;
    Call& operator=(const Call&) = delete;

   private:
    SumoProcess& p_;
  };
  /// Whether the watchdog killed it.
  bool timed_out() const { return timed_out_; }

 private:
  void watch();

  pid_t pid_ = -1;
  int port_ = 0;
  double answer_timeout_s_ = 0;
  bool ended_ = false;
  int status_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  std::atomic<bool> timed_out_{false};
  std::thread watchdog_;
};

std::unique_ptr<SumoLink> start_libsumo(const std::vector<std::string>& args);
std::unique_ptr<SumoLink> start_traci(const std::string& binary, const std::vector<std::string>& args,
                                      double answer_timeout_s);

}  // namespace lpsim

#pragma once
// Starting SUMO for a SumoLink: the binary found, a `sumo` process on a free local port watched while it
// starts, and the two client libraries' ways in (libsumo_link.cpp, traci_link.cpp).
#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "sumo_bridge/sumo_link.hpp"

namespace lpsim {

/// `name` itself when it contains a '/', else the first executable `name` on PATH; a SumoError when none.
std::string find_sumo_binary(const std::string& name);

/// A SUMO process serving TraCI on 127.0.0.1:port.
class SumoProcess {
 public:
  /// Starts `binary` with `args` and --remote-port on a free port.
  SumoProcess(const std::string& binary, const std::vector<std::string>& args);
  ~SumoProcess();  // kills it if it still runs
  SumoProcess(const SumoProcess&) = delete;
  SumoProcess& operator=(const SumoProcess&) = delete;

  int port() const { return port_; }
  /// Whether it has ended; then its exit status (or 128 + the signal that ended it) in *status.
  bool ended(int* status);
  /// Waits up to timeout_s for it to end (after the client closed it), then kills it.
  void finish(double timeout_s);

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  bool ended_ = false;
  int status_ = 0;
};

std::unique_ptr<SumoLink> start_libsumo(const std::vector<std::string>& args);
std::unique_ptr<SumoLink> start_traci(const std::string& binary, const std::vector<std::string>& args);

}  // namespace lpsim

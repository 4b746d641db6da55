// SumoLink over a TraCI socket to a sumo/sumo-gui process: Debian's libtracicpp.
#include <libsumo/libtraci.h>

#include <chrono>
#include <thread>

#include "app/interrupt.hpp"
#include "sumo_bridge/api_link.hpp"

namespace lpsim {

namespace {

struct TraciApi {
  using Simulation = libtraci::Simulation;
  using Vehicle = libtraci::Vehicle;
  using Route = libtraci::Route;
  static constexpr SumoMode kMode = SumoMode::Traci;
  // Over a socket every call is a round trip: one subscription read per step serves every vehicle.
  static constexpr bool kReadsDirectly = false;
};

// How long SUMO may take to load its network and open its port (a region's network takes seconds).
constexpr double kStartSeconds = 300;

}  // namespace

std::unique_ptr<SumoLink> start_traci(const std::string& binary, const std::vector<std::string>& args,
                                      double answer_timeout_s) {
  auto process = std::make_unique<SumoProcess>(binary, args, answer_timeout_s);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(kStartSeconds);
  for (;;) {
    int status = 0;
    if (process->ended(&status))
      throw SumoError("SUMO (" + binary + ") ended with status " + std::to_string(status) +
                      " while starting (SUMO's messages above)");
    // A signal while SUMO loads its network (a region's takes minutes) ends the wait at once.
    if (const int signal = pending_interrupt(); signal != 0)
      throw SumoStartInterrupted("SUMO (" + binary + ") was still starting when " + signal_name(signal) +
                                 " came");
    try {
      // One attempt each time: between them, whether SUMO is still starting or has failed is checked here.
      libtraci::Simulation::init(process->port(), 0, "127.0.0.1");
      break;
    } catch (const std::exception&) {
      if (std::chrono::steady_clock::now() > until)
        throw SumoError("SUMO (" + binary + ") did not accept a TraCI connection within " +
                        std::to_string(static_cast<int>(kStartSeconds)) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  return std::make_unique<ApiLink<TraciApi>>(std::move(process));
}

}  // namespace lpsim

// SumoLink in this process: Debian's libsumocpp.
#include <libsumo/libsumo.h>

#include "sumo_bridge/api_link.hpp"

namespace lpsim {

namespace {
struct LibsumoApi {
  using Simulation = libsumo::Simulation;
  using Vehicle = libsumo::Vehicle;
  using Route = libsumo::Route;
  static constexpr SumoMode kMode = SumoMode::Libsumo;
  // In process a getter is a function call: reading the watched vehicles one by one is cheaper than the
  // result maps a subscription builds for each of them every step.
  static constexpr bool kReadsDirectly = true;
};
}  // namespace

std::unique_ptr<SumoLink> start_libsumo(const std::vector<std::string>& args) {
  if (libsumo::Simulation::isLoaded())
    throw SumoError("libsumo runs one simulation per process, and one is running");
  try {
    libsumo::Simulation::load(args);
  } catch (const std::exception& e) {
    throw SumoError(std::string("SUMO (libsumo) could not start: ") + e.what() + " (SUMO's messages above)");
  }
  return std::make_unique<ApiLink<LibsumoApi>>(nullptr);
}

}  // namespace lpsim

#include "app/simulation_options.hpp"

#include <cstdint>

namespace lpsim {

SimulationOptions simulation_options(const ConfigSpec& config) {
  SimulationOptions options;
  options.begin = config.begin;
  options.step_length = config.step_length;
  options.seed = static_cast<uint64_t>(config.seed);
  options.threads = config.threads > 0 ? config.threads : 1;
  options.time_to_teleport = config.time_to_teleport;
  return options;
}

}  // namespace lpsim

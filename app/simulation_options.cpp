#include "app/simulation_options.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.hpp"

namespace lpsim {

SimulationOptions simulation_options(const ConfigSpec& config) {
  SimulationOptions options;
  options.begin = config.begin;
  // The engine keeps the step in whole milliseconds: a step length that is not one is refused here.
  options.step_ms = std::llround(config.step_length * 1000.0);
  if (options.step_ms <= 0 ||
      std::fabs(static_cast<double>(options.step_ms) - config.step_length * 1000.0) > 1e-6)
    throw InputError(
        SourceLoc{config.config_file.empty() ? "command line" : config.config_file, 0},
        "step length " + std::to_string(config.step_length) + " s is not a whole number of milliseconds");
  options.seed = static_cast<uint64_t>(config.seed);
  options.threads = config.threads > 0 ? config.threads : 1;
  options.time_to_teleport = config.time_to_teleport;
  options.time_to_teleport_highways = config.time_to_teleport_highways;
  options.highway_min_speed = config.time_to_teleport_highways_min_speed;
  options.time_to_impatience = config.time_to_impatience;
  options.max_depart_delay = config.max_depart_delay;
  options.ignore_junction_blocker = config.ignore_junction_blocker;
  options.volumetric_fuel = config.volumetric_fuel;
  return options;
}

}  // namespace lpsim

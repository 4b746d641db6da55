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
  const ReroutingSpec& r = config.rerouting;
  auto ms = [](double s) { return std::llround(s * 1000.0); };
  options.rerouting.adaptation_interval_ms = ms(r.adaptation_interval);
  // As SUMO: a moving average over adaptation-steps samples, unless only the weight is given.
  options.rerouting.adaptation_steps =
      r.adaptation_weight == 0 || r.adaptation_steps_given ? r.adaptation_steps : 0;
  options.rerouting.adaptation_weight = r.adaptation_weight;
  options.rerouting.period_ms = ms(r.period);
  options.rerouting.pre_period_ms = ms(r.pre_period);
  options.rerouting.synchronize = r.synchronize;
  options.rerouting.minor_penalty = config.minor_penalty;
  options.rerouting.random_factor = config.weights_random_factor;
  options.rerouting.contraction_hierarchy =
      config.routing_algorithm == "CH" || config.routing_algorithm == "CHWrapper";
  return options;
}

}  // namespace lpsim

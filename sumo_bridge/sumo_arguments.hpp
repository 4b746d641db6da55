#pragma once
// What the co-simulation tells SUMO: its command line for a scenario (the scenario's own files and options,
// SUMO's side of each output beside LPSim's), and a departing trip's depart attributes as SUMO's text.
#include <cstdint>
#include <string>
#include <vector>

#include "app/output_paths.hpp"
#include "core/config_spec.hpp"
#include "demand/demand.hpp"

namespace lpsim {

/// A number exactly as SUMO parses it back (no rounding to six digits, no locale).
std::string sumo_number(double x);

/// SUMO's options for a co-simulation of the scenario `config` describes: its network, its route files for
/// their vTypes only (at --scale 0 SUMO keeps none of their vehicles), its additional files and
/// `extra_additional`, begin, step length, seed, teleport and impatience times, the default car-following
/// model, and outputs written as sumo_side_path() of LPSim's (tripinfo to `tripinfo`); then `user_args`,
/// whose options replace those of the same name (an InputError for the ones the co-simulation depends on).
/// The files SUMO will write for the output options in `user_args` (--<x>-output, the logs), under the
/// co-simulation's prefix (sumo_side_path), so that they are checked as every output is.
std::vector<ExtraOutput> sumo_args_outputs(const std::vector<std::string>& user_args);

/// InputError for a SUMO option in `user_args` that makes SUMO wait for TraCI clients (--remote-port,
/// --num-clients: the co-simulation is SUMO's only client, so the run would hang), or that asks for the
/// unfinished trips in the tripinfo (the co-simulation merges finished trips only).
void refuse_unsupported_sumo_args(const std::vector<std::string>& user_args);

std::vector<std::string> cosim_sumo_arguments(const ConfigSpec& config, const std::string& tripinfo,
                                              const std::string& extra_additional,
                                              const std::vector<std::string>& user_args);

/// Trip v's departLane, departPos and departSpeed as SUMO's attribute values.
struct SumoDepart {
  std::string lane, pos, speed;
};
SumoDepart sumo_depart(const Demand& demand, uint32_t v);

}  // namespace lpsim

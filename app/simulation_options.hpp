#pragma once
// The one mapping from a run's configuration to the engine's options, shared by `lpsim run`, other drivers
// and the tests, so that a new option reaches all of them at once.
#include "core/config_spec.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

/// The engine options `config` asks for: begin, step length, seed, threads (0, the default, steps on one
/// thread, as `lpsim run` always has), time-to-teleport and volumetric fuel. What the config does not decide
/// alone is left at the engine's defaults: the backend (`gpu`: resolving --device probes the machine, so the
/// driver does it, see app/device_select.hpp), `lane_counters` and `emission_sums` (they follow the outputs
/// requested, which Run knows) and `slot_sort_interval`.
SimulationOptions simulation_options(const ConfigSpec& config);

}  // namespace lpsim

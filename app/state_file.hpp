#pragma once
// An LPSim state file (--save-state.*, --load-state): a header (magic, format version, the layout of the
// values it holds, the digest of the scenario and options that made it, the payload's lengths and CRC-32)
// and the payload deflated (zlib), the run's state as Run and Simulation list it. A file that is truncated,
// corrupted, of another format or layout, or of another scenario is refused with one InputError naming it.
#include <cstdint>
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

/// What a state depends on: the network, the demand as loaded, and the options that change the results
/// (step length, seed, begin, teleport and junction rules, rerouting, what the lanes count).
uint64_t scenario_digest(const Scenario& scenario, const SimulationOptions& options);

/// Writes the file whole (to a temporary name first, then renamed, so that a run killed while writing
/// leaves the previous state, if any, intact). InputError when it cannot be written.
void write_state_file(const std::string& path, uint64_t digest, const std::vector<uint8_t>& payload);
/// The payload of a state file of this scenario (`digest`), checked; InputError naming the file otherwise.
std::vector<uint8_t> read_state_file(const std::string& path, uint64_t digest);

}  // namespace lpsim

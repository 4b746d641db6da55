#pragma once
// The vehicles that entered each edge during a run, from a SUMO edgeData output (LPSim's or SUMO's): an
// edge's `entered` summed over the file's intervals (entries from upstream, not departures).
#include <cstdint>
#include <string>
#include <unordered_map>

namespace lpsim {

/// Edge id -> vehicles that entered it; an unreadable or malformed file is an InputError with file:line.
std::unordered_map<std::string, int64_t> read_edge_entries(const std::string& path);

}  // namespace lpsim

#pragma once
// Edge travel times per interval from a SUMO edgeData output (duaIterate's dump, LPSim's or SUMO's), as
// duarouter reads --weight-files: each edge entry's `traveltime` in its interval.
#include <string>
#include <unordered_map>
#include <vector>

#include "net/router.hpp"

namespace lpsim {

/// The intervals of `path` (equally long, consecutive, from the first's begin) with the traveltime of each
/// edge `edge_index` knows; edges without an entry in an interval (or without traveltime) stay NaN (free
/// flow). An InputError naming file:line for an unreadable file, intervals of unequal length or gaps.
IntervalTravelTimes read_edge_weights(const std::string& path,
                                      const std::unordered_map<std::string, uint32_t>& edge_index,
                                      uint32_t num_edges);

}  // namespace lpsim

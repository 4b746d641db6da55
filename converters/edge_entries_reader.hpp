#pragma once
// What a run measured on each edge, from a SUMO edgeData output (LPSim's or SUMO's), summed over the file's
// intervals: the vehicles that entered it (`entered`: from upstream, not departures) and the seconds
// vehicles spent on it (`sampledSeconds`), with the time the intervals cover.
#include <cstdint>
#include <string>
#include <unordered_map>

namespace lpsim {

struct EdgeTotals {
  int64_t entered = 0;
  double sampled_seconds = 0;
};

struct EdgeDataTotals {
  std::unordered_map<std::string, EdgeTotals> edges;  // by edge id
  double seconds = 0;                                 // the intervals' lengths, summed
};

/// The totals of `path`; an unreadable or malformed file is an InputError with file:line.
EdgeDataTotals read_edge_totals(const std::string& path);

}  // namespace lpsim

#pragma once
// One edgeData/laneData output from two simulators' (a co-simulation): LPSim's file, in which the entries of
// the corridor's edges are replaced by those SUMO measured there (its file of the same definition, same
// intervals). SUMO leaves out edges nothing passed; so does the merged file for the corridor's edges.
#include <string>
#include <unordered_set>
#include <vector>

namespace lpsim {

/// An interval the two files end at different times (the last one, when the end lies between SUMO's steps):
/// its corridor entries cover SUMO's span, the rest LPSim's.
struct MeanDataSpanDiff {
  double begin, lpsim_end, sumo_end;
};

/// Rewrites `lpsim_file` (as LPSim's MeanDataWriter writes it: one element per line) with the entries of
/// `corridor_edges` taken from `sumo_file` (its interval of the same begin time). Plain or .gz alike.
/// Returns the intervals whose ends differ. InputError naming the file and line when either cannot be read or
/// an interval of LPSim's is not in SUMO's.
std::vector<MeanDataSpanDiff> merge_meandata(const std::string& lpsim_file, const std::string& sumo_file,
                                             const std::unordered_set<std::string>& corridor_edges);

}  // namespace lpsim

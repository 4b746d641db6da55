#pragma once
// One edgeData/laneData output from two simulators' (a co-simulation): LPSim's file, in which the entries of
// the corridor's edges are replaced by those SUMO measured there (its file of the same definition, same
// intervals). SUMO leaves out edges nothing passed; so does the merged file for the corridor's edges.
#include <string>
#include <unordered_set>

namespace lpsim {

/// Rewrites `lpsim_file` (as LPSim's MeanDataWriter writes it: one element per line) with the entries of
/// `corridor_edges` taken from `sumo_file` (its interval of the same begin time). Plain or .gz alike.
/// InputError naming the file and line when either cannot be read or an interval of LPSim's is not in SUMO's.
void merge_meandata(const std::string& lpsim_file, const std::string& sumo_file,
                    const std::unordered_set<std::string>& corridor_edges);

}  // namespace lpsim

#include "app/partition_resolution.hpp"

#include <string>

#include "converters/edge_entries_reader.hpp"
#include "core/error.hpp"

namespace lpsim {

std::vector<int32_t> resolve_partition(const PartitionSpec& spec, const Network& net,
                                       int32_t expected_parts) {
  if (expected_parts > 0 && spec.parts != expected_parts)
    throw InputError(spec.loc, "the partition file has " + std::to_string(spec.parts) +
                                   " parts, the run asks for " + std::to_string(expected_parts));
  uint32_t junctions = 0;  // SUMO's internal junctions own no road: a part needs a real one
  for (const JunctionType t : net.junction_type) junctions += t != JunctionType::Internal ? 1 : 0;
  if (static_cast<uint32_t>(spec.parts) > junctions)
    throw InputError(spec.loc, std::to_string(spec.parts) +
                                   " parts need at least as many junctions; the network has " +
                                   std::to_string(junctions) + " (SUMO's internal junctions not counted)");
  std::vector<int32_t> edge_part(net.num_edges(), kNone);
  std::vector<int> edge_line(net.num_edges(), 0);
  for (size_t i = 0; i < spec.edge_id.size(); ++i) {
    const SourceLoc where{spec.loc.file, spec.line[i]};
    const auto it = net.edge_index.find(spec.edge_id[i]);
    if (it == net.edge_index.end() || net.edge_is_internal[it->second])
      throw InputError(where, "edge '" + spec.edge_id[i] + "' is not a normal edge of the network");
    const uint32_t e = it->second;
    if (edge_part[e] != kNone)
      throw InputError(where, "edge '" + spec.edge_id[i] + "' listed twice (first at line " +
                                  std::to_string(edge_line[e]) + ")");
    if (spec.part[i] < 0 || spec.part[i] >= spec.parts)
      throw InputError(where, "part " + std::to_string(spec.part[i]) + " of edge '" + spec.edge_id[i] +
                                  "' is outside 0.." + std::to_string(spec.parts - 1));
    edge_part[e] = spec.part[i];
    edge_line[e] = spec.line[i];
  }
  uint32_t missing = 0;
  std::string first_missing;
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (!net.edge_is_internal[e] && edge_part[e] == kNone && missing++ == 0) first_missing = net.edge_id[e];
  if (missing > 0)
    throw InputError(spec.loc, std::to_string(missing) +
                                   " normal edges of the network have no part (the first: '" + first_missing +
                                   "')");
  std::vector<int32_t> junction_part(net.num_junctions(), kNone);
  std::vector<uint32_t> junction_edge(net.num_junctions(), 0);
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    const int32_t to = net.edge_to_junction[e];
    if (net.edge_is_internal[e] || to < 0) continue;
    const uint32_t j = static_cast<uint32_t>(to);
    if (junction_part[j] == kNone) {
      junction_part[j] = edge_part[e];
      junction_edge[j] = e;
    } else if (junction_part[j] != edge_part[e]) {
      throw InputError(SourceLoc{spec.loc.file, edge_line[e]},
                       "edges '" + net.edge_id[junction_edge[j]] + "' (part " +
                           std::to_string(junction_part[j]) + ") and '" + net.edge_id[e] + "' (part " +
                           std::to_string(edge_part[e]) + ") lead to junction '" + net.junction_id[j] +
                           "': the roads into a junction must share its part");
    }
  }
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    const int32_t from = net.edge_from_junction[e];
    if (!net.edge_is_internal[e] && from >= 0 && junction_part[static_cast<uint32_t>(from)] == kNone)
      junction_part[static_cast<uint32_t>(from)] = edge_part[e];
  }
  for (int32_t& p : junction_part)
    if (p == kNone) p = 0;  // a junction no normal edge touches owns nothing
  return junction_part;
}

MeasuredLoad read_measured_load(const std::string& path, const Network& net, double* seconds) {
  const EdgeDataTotals totals = read_edge_totals(path);
  MeasuredLoad load{std::vector<double>(net.num_edges(), 0), std::vector<int64_t>(net.num_edges(), 0)};
  for (const auto& [id, t] : totals.edges) {
    const auto it = net.edge_index.find(id);
    if (it == net.edge_index.end())
      throw InputError(SourceLoc{path, 0},
                       "edge '" + id + "' is not in the network: an edgeData output of another scenario?");
    load.vehicle_seconds[it->second] = t.sampled_seconds;
    load.entered[it->second] = t.entered;
  }
  *seconds = totals.seconds;
  return load;
}

}  // namespace lpsim

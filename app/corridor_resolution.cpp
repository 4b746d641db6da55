#include "app/corridor_resolution.hpp"

#include <algorithm>

namespace lpsim {

std::vector<uint32_t> resolve_corridor(const CorridorSpec& spec, const Network& net) {
  std::vector<uint32_t> edges;
  for (const CorridorSpec::Item& item : spec.items) {
    const SourceLoc at{spec.file, item.line};
    uint32_t e = 0;
    if (item.lane) {
      const auto it = net.lane_index_by_id.find(item.id);
      if (it == net.lane_index_by_id.end())
        throw InputError(at, "lane '" + item.id + "' is not a vehicle lane of the network");
      e = net.lane_edge[it->second];
    } else {
      const auto it = net.edge_index.find(item.id);
      if (it == net.edge_index.end()) throw InputError(at, "edge '" + item.id + "' is not in the network");
      e = it->second;
    }
    if (net.edge_is_internal[e])
      throw InputError(at, "'" + item.id + "' is inside a junction: a corridor is made of roads (edge:ID)");
    if (net.edge_num_lanes[e] == 0)
      throw InputError(at, "edge '" + item.id +
                               "' has no lane a road vehicle may use (a footpath, a track): SUMO would have "
                               "nothing of LPSim's to drive on it");
    edges.push_back(e);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<uint32_t> close_corridor(const std::vector<uint32_t>& edges, const Network& net) {
  std::vector<uint8_t> junction(net.num_junctions(), 0);
  for (const uint32_t e : edges)
    if (net.edge_to_junction[e] >= 0) junction[static_cast<uint32_t>(net.edge_to_junction[e])] = 1;
  std::vector<uint32_t> closed = edges;
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (!net.edge_is_internal[e] && net.edge_to_junction[e] >= 0 &&
        junction[static_cast<uint32_t>(net.edge_to_junction[e])])
      closed.push_back(e);
  std::sort(closed.begin(), closed.end());
  closed.erase(std::unique(closed.begin(), closed.end()), closed.end());
  return closed;
}

}  // namespace lpsim

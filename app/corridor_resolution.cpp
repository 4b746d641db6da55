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
    edges.push_back(e);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace lpsim

#include "partition/junction_graph.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace lpsim {

int64_t free_flow_steps(const Network& net, uint32_t e, double dt) {
  const double speed = std::max<double>(net.edge_speed[e], 0.1);
  return std::max<int64_t>(1, static_cast<int64_t>(std::ceil(net.edge_length[e] / speed / dt)));
}

EdgeRouteUses count_route_uses(const Demand& demand, uint32_t num_edges) {
  EdgeRouteUses u{std::vector<int64_t>(num_edges, 0), std::vector<int64_t>(num_edges, 0)};
  for (uint32_t v = 0; v < demand.size(); ++v)
    for (uint32_t i = 0; i < demand.route_length[v]; ++i) {
      const uint32_t e = demand.route_edges[demand.route_begin[v] + i];
      ++u.uses[e];
      if (i > 0) ++u.entries[e];
    }
  return u;
}

namespace {

// The graph with each normal edge's load (vehicle-steps) added to the junction it leads to and its crossings
// to the link between its two junctions (both directions summed).
JunctionGraph build_graph(const Network& net, const std::vector<int64_t>& load,
                          const std::vector<int64_t>& crossings) {
  const uint32_t nj = net.num_junctions(), ne = net.num_edges();
  JunctionGraph g;
  g.num_junctions = nj;
  std::vector<int32_t> vertex(nj, -1);
  for (uint32_t j = 0; j < nj; ++j) {
    if (j < net.junction_type.size() && net.junction_type[j] == JunctionType::Internal) continue;
    vertex[j] = static_cast<int32_t>(g.junction.size());
    g.junction.push_back(j);
    g.x.push_back(net.junction_x[j]);
    g.y.push_back(net.junction_y[j]);
  }
  const auto nv = static_cast<uint32_t>(g.junction.size());
  g.vertex_weight.assign(nv, 1);
  std::vector<std::vector<std::pair<int32_t, int64_t>>> links(nv);
  for (uint32_t e = 0; e < ne; ++e) {
    if (net.edge_is_internal[e]) continue;
    const int32_t from =
        net.edge_from_junction[e] >= 0 ? vertex[static_cast<uint32_t>(net.edge_from_junction[e])] : -1;
    const int32_t to =
        net.edge_to_junction[e] >= 0 ? vertex[static_cast<uint32_t>(net.edge_to_junction[e])] : -1;
    if (to >= 0) g.vertex_weight[static_cast<uint32_t>(to)] += load[e];
    if (from < 0 || to < 0 || from == to) continue;
    links[static_cast<uint32_t>(from)].emplace_back(to, crossings[e]);
    links[static_cast<uint32_t>(to)].emplace_back(from, crossings[e]);
  }
  g.adj_begin.assign(nv + 1, 0);
  for (uint32_t j = 0; j < nv; ++j) {
    auto& l = links[j];
    std::sort(l.begin(), l.end());
    for (size_t i = 0; i < l.size(); ++i) {
      if (i > 0 && l[i].first == l[i - 1].first) {
        g.adj_weight.back() += l[i].second;  // the other direction, or a parallel road
        continue;
      }
      g.adj.push_back(l[i].first);
      g.adj_weight.push_back(1 + l[i].second);
    }
    g.adj_begin[j + 1] = static_cast<int32_t>(g.adj.size());
  }
  return g;
}

}  // namespace

JunctionGraph build_junction_graph(const Network& net, const Demand& demand, double dt) {
  const uint32_t ne = net.num_edges();
  const std::vector<int64_t> uses = count_route_uses(demand, ne).uses;
  std::vector<int64_t> load(ne, 0);
  for (uint32_t e = 0; e < ne; ++e)
    if (!net.edge_is_internal[e]) load[e] = uses[e] * free_flow_steps(net, e, dt);
  return build_graph(net, load, uses);
}

JunctionGraph build_junction_graph(const Network& net, const MeasuredLoad& measured, double dt) {
  const uint32_t ne = net.num_edges();
  std::vector<int64_t> load(ne, 0);
  for (uint32_t e = 0; e < ne; ++e) load[e] = std::llround(measured.vehicle_seconds.at(e) / dt);
  return build_graph(net, load, measured.entered);
}

std::vector<int32_t> edge_parts_from_junctions(const Network& net,
                                               const std::vector<int32_t>& junction_part) {
  std::vector<int32_t> parts(net.num_edges(), kNone);
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    const int32_t to = net.edge_to_junction[e];
    if (!net.edge_is_internal[e] && to >= 0) parts[e] = junction_part[static_cast<uint32_t>(to)];
  }
  return parts;
}

}  // namespace lpsim

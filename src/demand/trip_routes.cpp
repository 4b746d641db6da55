#include "demand/trip_routes.hpp"

#include <stdexcept>
#include <string>

namespace lpsim {

RouteRequest trip_request(const Demand& d, const Network& net, uint32_t v) {
  const uint32_t* route = d.route_edges.data() + d.route_begin[v];
  RouteRequest q;
  if (d.route_length[v] == 0) return q;
  q.origins = {route[0]};
  q.destinations = {route[d.route_length[v] - 1]};
  q.vclass = d.types.vclass_mask[d.vehicle_type[v]];
  if (!d.via_begin.empty())
    q.via.assign(d.via_edges.begin() + d.via_begin[v], d.via_edges.begin() + d.via_begin[v + 1]);
  for (uint32_t k = d.stops.first(v); k < d.stops.last(v); ++k)
    q.via.push_back(net.lane_edge[d.stops.lane[k]]);
  return q;
}

std::vector<uint32_t> stop_positions(const Demand& d, const Network& net, uint32_t v,
                                     const std::vector<uint32_t>& route) {
  std::vector<uint32_t> at;
  uint32_t pos = 0;
  for (uint32_t k = d.stops.first(v); k < d.stops.last(v); ++k) {
    const uint32_t edge = net.lane_edge[d.stops.lane[k]];
    while (pos < route.size() && route[pos] != edge) ++pos;
    if (pos == route.size()) return {};
    at.push_back(pos);
  }
  return at;
}

void replace_routes(Demand& d, const Network& net, const std::vector<std::vector<uint32_t>>& routes) {
  if (routes.size() != d.size())
    throw std::invalid_argument("replace_routes: " + std::to_string(routes.size()) + " routes for " +
                                std::to_string(d.size()) + " vehicles");
  std::vector<uint32_t> edges;
  for (uint32_t v = 0; v < d.size(); ++v) {
    const std::vector<uint32_t>* route = &routes[v];
    if (!route->empty() && d.stops.first(v) != d.stops.last(v)) {
      const std::vector<uint32_t> at = stop_positions(d, net, v, *route);
      if (at.empty()) {
        route = nullptr;
      } else {
        for (uint32_t k = d.stops.first(v); k < d.stops.last(v); ++k)
          d.stops.route_pos[k] = at[k - d.stops.first(v)];
      }
    }
    const size_t begin = edges.size();
    if (route && !route->empty())
      edges.insert(edges.end(), route->begin(), route->end());
    else
      edges.insert(edges.end(), d.route_edges.begin() + d.route_begin[v],
                   d.route_edges.begin() + d.route_begin[v] + d.route_length[v]);
    d.route_begin[v] = static_cast<uint32_t>(begin);
    d.route_length[v] = static_cast<uint32_t>(edges.size() - begin);
  }
  d.route_edges = std::move(edges);
}

}  // namespace lpsim

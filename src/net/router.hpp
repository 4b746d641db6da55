#pragma once
#include <cstdint>
#include <vector>

#include "net/network.hpp"

namespace lpsim {

/// One routing request: from any of `origins` to any of `destinations` (edge indices; a trip has one of
/// each, an OD pair between junctions several), passing `via` edges in order.
struct RouteRequest {
  std::vector<uint32_t> origins, destinations, via;
};

/// Fastest paths on free-flow travel time (edge length / edge speed) over the edge graph that lane
/// connections induce. Deterministic: ties are broken by edge index.
class Router {
 public:
  explicit Router(const Network& net);
  /// Routes all requests on `threads` threads (0: all). An empty result means "no path".
  std::vector<std::vector<uint32_t>> route_all(const std::vector<RouteRequest>& requests, int threads) const;
  /// Free-flow cost of a path (seconds).
  double cost(const std::vector<uint32_t>& path) const;

 private:
  const Network& net_;
  std::vector<float> edge_cost_;
};

}  // namespace lpsim

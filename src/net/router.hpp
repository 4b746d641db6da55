#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "net/network.hpp"

namespace lpsim {

/// One routing request: from any of `origins` to any of `destinations` (edge indices; a trip has one of
/// each, an OD pair between junctions several), passing `via` edges in order, for a vehicle of class mask
/// `vclass` (core/vclass.hpp): only edges and moves some lane of which that class may use.
struct RouteRequest {
  std::vector<uint32_t> origins, destinations, via;
  uint32_t vclass = kAllVClasses;
  // Non-zero: the stream from which this request's random edge-cost factors are drawn (RandomWeights), e.g.
  // a hash of the vehicle id; such a request is routed on its own, never shared with another.
  uint64_t random_stream = 0;
};

/// std::out_of_range naming the first request that names an edge index at or above `num_edges`.
void check_request_edges(const std::vector<RouteRequest>& requests, uint32_t num_edges);

/// SUMO's --weights.random-factor F: each edge's cost is multiplied by a factor drawn uniformly in [1, F),
/// here one per (request, edge) from the counter-based RNG keyed by `seed` and the request's random_stream,
/// so that routes depend on the seed and the vehicle only (SUMO draws one per cost evaluation from its
/// global RNG, which no other simulator can reproduce draw for draw).
struct RandomWeights {
  double factor = 1;
  uint64_t seed = 0;
};

/// Edge travel times that change by time interval, as duarouter reads them from --weight-files (an edgeData
/// output's traveltime per interval) with --weights.expand: interval k covers [begin + k * period, begin +
/// (k + 1) * period); times before the first interval take the first's, times after the last the last's.
struct IntervalTravelTimes {
  double begin = 0;   // s
  double period = 1;  // s
  uint32_t num_edges = 0;
  // [k * num_edges + e]: edge e's travel time in interval k (s); NaN where it was not measured, which costs
  // the edge its free-flow time.
  std::vector<float> time;

  uint32_t intervals() const { return num_edges == 0 ? 0 : static_cast<uint32_t>(time.size() / num_edges); }
  /// Interval `intervals` of NaN (all edges free-flow) for `num_edges` edges.
  void resize(uint32_t edges, uint32_t intervals);
  /// The interval time t falls in, clamped to the first and the last (needs at least one).
  uint32_t interval_at(double t) const;
};

/// SUMO's default time penalty (--weights.minor-penalty) for crossing a junction on a link without
/// priority that no signal controls [s].
constexpr double kMinorLinkPenalty = 1.5;

/// Fastest paths on free-flow travel time over the edge graph that lane connections induce, costed as
/// SUMO's router costs them: each edge's length / speed, plus, from an edge into a successor, the
/// junction-internal lanes between them (those of the first connection onto the successor, in lane order)
/// at their length / speed, each with kMinorLinkPenalty when the link entering it has no priority and no
/// signal. Deterministic: ties are broken by edge index.
class Router {
 public:
  /// minor_penalty: SUMO's --weights.minor-penalty [s].
  explicit Router(const Network& net, double minor_penalty = kMinorLinkPenalty, RandomWeights random = {});
  /// Routes all requests on `threads` threads (0: all). An empty result means "no path".
  std::vector<std::vector<uint32_t>> route_all(const std::vector<RouteRequest>& requests, int threads) const;
  /// Free-flow cost of a path (seconds), its edges' and the junction crossings between them.
  double cost(const std::vector<uint32_t>& path) const;
  /// Cost of entering net.edge_succ[i] from its predecessor edge: the crossing plus the edge (seconds).
  double step_cost(uint32_t i) const { return step_cost_[i]; }
  /// Cost of edge e as a path's first edge (seconds; infinite at speed 0).
  double edge_cost(uint32_t e) const { return edge_cost_[e]; }
  /// Costs from now on on the travel times of the rerouting device (SUMO's MSRoutingEngine::getEffort):
  /// each edge, and each junction-internal lane by its internal edge, takes its length over `edge_speed`
  /// (per edge of the network, m/s), at least its free-flow time. std::invalid_argument on a wrong size.
  void set_speeds(const std::vector<double>& edge_speed);

  /// Costs from now on of interval k of `times`: each edge its travel time there (its free-flow time where
  /// that is NaN), the junction crossings at free flow; a metric to customize a contraction hierarchy with
  /// per interval, as SUMO's CH router takes the weights of each --weight-period. std::invalid_argument on
  /// times of another network or an interval it lacks.
  void set_interval_costs(const IntervalTravelTimes& times, uint32_t k);

  /// Time-dependent fastest paths, as duarouter's Dijkstra routes on interval weights: each request departs
  /// at depart[k]; an edge entered at time t costs its travel time in t's interval of `times` (its free-flow
  /// time where that is NaN), each junction crossing its cost on this Router (free flow unless set_speeds).
  /// Paths as route_all (empty: no path); `costs` (optional) receives each path's travel time in the same
  /// measure (infinite: no path). One search per request; the same paths on any number of threads.
  std::vector<std::vector<uint32_t>> route_timed(const std::vector<RouteRequest>& requests,
                                                 const std::vector<double>& depart,
                                                 const IntervalTravelTimes& times, int threads,
                                                 std::vector<double>* costs = nullptr) const;
  /// Edge e's travel time when entered at time t in route_timed's measure.
  double timed_edge_cost(uint32_t e, double t, const IntervalTravelTimes& times) const;
  /// Travel time of `path` departing at `depart` in route_timed's measure (infinite: not a path).
  double timed_cost(std::span<const uint32_t> path, double depart, const IntervalTravelTimes& times) const;

 private:
  void set_costs(const std::vector<double>* speeds);  // null: free flow

  const Network& net_;
  RandomWeights random_;
  double minor_penalty_;
  std::vector<float> edge_cost_;
  std::vector<double> step_cost_;      // parallel to net.edge_succ
  std::vector<double> crossing_cost_;  // parallel to net.edge_succ: the junction crossing alone
  std::vector<int32_t> crossing_;      // parallel to net.edge_succ: the connection crossed onto it (-1: none)
};

}  // namespace lpsim

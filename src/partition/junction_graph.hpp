#pragma once
// The graph a network is partitioned on, as the original LPSim did: a vertex per junction, an undirected
// edge per pair of junctions a road joins (both directions together), weighted by the demand. A road belongs
// to the part of the junction it leads to, so every approach to a junction, and the junction's signals and
// right of way, stay in one part; a vehicle changes part only where it leaves a junction onto a road of
// another part, so the vehicles using a road are what cutting it costs.
#include <stdint.h>

#include <vector>

#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

/// One vertex per junction of the road network; SUMO's internal junctions (waiting places inside an
/// intersection, type "internal") are none: no road leads to them, and a part of them alone would be empty.
struct JunctionGraph {
  std::vector<uint32_t> junction;  // the network junction of each vertex
  uint32_t num_junctions = 0;      // the network's, internal ones included
  // CSR adjacency (each undirected edge listed from both ends, neighbours ascending, no self-loops).
  std::vector<int32_t> adj_begin;  // size vertices + 1
  std::vector<int32_t> adj;        // neighbour vertices
  // 1 + vehicles whose route uses a road between the two junctions (or, measured, that entered one)
  std::vector<int64_t> adj_weight;
  // Per vertex: vehicle-steps on the roads leading to it, plus one so that empty junctions weigh something:
  // expected (each route's free-flow traversal of each road, in whole steps, at least one) or measured.
  std::vector<int64_t> vertex_weight;
  std::vector<float> x, y;  // junction positions (net coordinates)

  uint32_t num_vertices() const { return static_cast<uint32_t>(vertex_weight.size()); }
};

/// Per edge, the loaded routes that use it, and of them those that enter it from the edge before (a route's
/// first edge is where its vehicle departs, not entered).
struct EdgeRouteUses {
  std::vector<int64_t> uses, entries;
};
EdgeRouteUses count_route_uses(const Demand& demand, uint32_t num_edges);

/// Builds the junction graph of `net` weighted by the routes of `demand` (dt: the step length, s).
JunctionGraph build_junction_graph(const Network& net, const Demand& demand, double dt);

/// What a run of the scenario measured per edge (an edgeData output): the seconds vehicles spent on it and
/// the vehicles that entered it from upstream.
struct MeasuredLoad {
  std::vector<double> vehicle_seconds;
  std::vector<int64_t> entered;
};

/// The junction graph weighted by a run's measured load in place of the routes in free flow: a congested
/// junction weighs what its queues cost each step, and a road's cut what crossed it.
JunctionGraph build_junction_graph(const Network& net, const MeasuredLoad& measured, double dt);

/// Whole steps a vehicle takes to cross normal edge e at its free-flow speed (at least one).
int64_t free_flow_steps(const Network& net, uint32_t e, double dt);

/// The part each normal edge belongs to (that of the junction it leads to); kNone for internal edges and
/// edges without a junction.
std::vector<int32_t> edge_parts_from_junctions(const Network& net, const std::vector<int32_t>& junction_part);

}  // namespace lpsim

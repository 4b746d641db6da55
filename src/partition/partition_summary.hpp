#pragma once
// What a partition of a network gives each part: its share of the road and of the expected work, and what it
// must exchange with the others (the lanes its vehicles enter from other parts, its neighbours).
#include <stdint.h>

#include <vector>

#include "demand/demand.hpp"
#include "net/network.hpp"
#include "partition/junction_graph.hpp"

namespace lpsim {

struct PartSummary {
  uint32_t junctions = 0;
  uint32_t lanes = 0;  // lanes of its roads and of its junctions (internal lanes)
  double lane_km = 0;
  int64_t vehicle_steps = 0;   // expected: each route's free-flow traversal of its roads, in steps
  uint32_t cut_lanes_in = 0;   // its lanes whose road starts at a junction of another part
  uint32_t cut_lanes_out = 0;  // lanes of other parts whose road starts at one of its junctions
  int64_t vehicles_in = 0;  // expected vehicles entering it from another part (routes entering its cut roads)
  uint32_t ghost_lanes = 0;             // lanes of other parts it must see (partition_layout)
  uint64_t cells = 0, ghost_cells = 0;  // lane-map cells of its own lanes and of its ghosts
  std::vector<int32_t> neighbours;      // parts it shares a road with, ascending
};

// How far past a cut a vehicle looks (kernels' kMaxLookahead, 1,000 m): the ghost lanes of a part are those
// of other parts within this distance downstream of its lanes (partition_layout.hpp).
constexpr double kGhostLookAhead = 1000.0;

struct PartitionSummary {
  std::vector<PartSummary> parts;
  int64_t cut_roads = 0;     // normal edges whose two junctions lie in different parts
  int64_t cut_lanes = 0;     // their lanes
  uint64_t total_cells = 0;  // the whole network's lane-map cells
  double largest_share = 1;  // the most lane-map cells a part holds, ghosts included, over total_cells
  int64_t migrations = 0;    // expected vehicles crossing a cut (routes entering a cut road)
  int64_t measured_migrations = -1;  // vehicles that entered a cut road in a run (add_measured_migrations)
  double imbalance = 1;              // largest part's vehicle-steps over the mean part's (1: balanced)
};

/// The summary of junction_part (a part per junction of net) under the demand's routes.
PartitionSummary summarize_partition(const Network& net, const Demand& demand,
                                     const std::vector<int32_t>& junction_part, int32_t k, double dt);

/// Counts the vehicles of a run that crossed a cut: the entries (from upstream, as an edgeData output counts
/// them) of every road whose from-junction lies in another part than the road. Trajectories do not depend on
/// the partition, so one run of K = 1 gives the migrations of any partition.
void add_measured_migrations(PartitionSummary& s, const Network& net,
                             const std::vector<int32_t>& junction_part,
                             const std::vector<int64_t>& entered_per_edge);

/// For road e of edge_part (edge_parts_from_junctions), the part its vehicles come from when the road is
/// cut (its from-junction lies in another part), else kNone.
int32_t cut_source_part(const Network& net, const std::vector<int32_t>& junction_part,
                        const std::vector<int32_t>& edge_part, uint32_t e);

/// The part of every lane, normal and internal: a road's lanes are its to-junction's, a junction's internal
/// lanes are that junction's (the part of the road that leads into them). kNone where no part is known.
std::vector<int32_t> lane_parts(const Network& net, const std::vector<int32_t>& edge_part);

}  // namespace lpsim

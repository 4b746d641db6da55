#pragma once
// What one part of a partitioned run needs to know of the partition: who owns each lane, which lanes it holds
// (its own and its ghosts, whose lane-map cells it keeps), which of them other parts hold too (what its
// exchanges send and receive), and which signals it computes. Every part keeps the network's static columns
// whole; only the cells and the vehicles are split.
#include <stdint.h>

#include <vector>

#include "net/network.hpp"
#include "partition/part_cells.hpp"

namespace lpsim {

struct PartPlan {
  int32_t part = 0, parts = 1;
  std::vector<int32_t> lane_owner;  // per lane of the network
  std::vector<int32_t> edge_owner;  // per edge: the owner of its lanes (an edge without lanes: 0)
  std::vector<uint8_t> held;        // per lane: 1 where this part keeps the lane's cells (owned or ghost)
  PartCells cells;                  // this part's lane map: owned lanes' cells first, then its ghosts'
  // Every holder of each lane (its owner and the parts that keep it as a ghost), ascending: CSR over lanes.
  std::vector<uint32_t> holder_begin;
  std::vector<int32_t> holders;
  // Lanes this part holds that another part holds too, ascending: what its exchanges are about.
  std::vector<uint32_t> shared_lanes;
  // Per signal: the part that runs it (an actuated signal reads its loops on its owner's lanes and sends
  // its state to the others), or -1 where every part computes it itself (a fixed-time program).
  std::vector<int32_t> signal_owner;
};

/// The plan of every part of `edge_part` (a part per edge: edge_parts_from_junctions, or a partition file),
/// for a run whose longest vehicle is `longest_vehicle` metres. A part's ghosts are the lanes of other parts
/// its vehicles can read or write in a step:
/// - downstream, the lanes a vehicle looks into (kernels' 1,000 m look-ahead, and the room behind the last
///   junction it decides on: kRoomLookAheadLengths vehicle lengths, twice, plus the junctions' inside);
/// - at every junction one of its held lanes leads into, the foes' lanes and their internal lanes (right of
///   way reads their first vehicles and what is inside the junction), and the internal lanes of the links
///   that yield to its own;
/// - upstream, the lanes within the longest vehicle's length behind one of its lanes (its vehicles' tails);
/// - the induction loops of the actuated signals it runs;
/// each with the other lanes of its edge.
std::vector<PartPlan> part_plans(const Network& net, const std::vector<int32_t>& edge_part, int32_t parts,
                                 double longest_vehicle);

/// The plan of part `part` alone (what one rank of an MPI run keeps), as part_plans(...)[part].
PartPlan part_plan(const Network& net, const std::vector<int32_t>& edge_part, int32_t parts,
                   double longest_vehicle, int32_t part);

/// Metres downstream of a part's lanes that its ghosts reach, for a run whose longest vehicle is
/// `longest_vehicle` metres.
double ghost_look_ahead(double longest_vehicle);

}  // namespace lpsim

#pragma once
// The lanes each part of a partition holds: the lanes it owns, and the ghost lanes of other parts it must see
// to step its own vehicles as one part would (what the partitioned engine will copy across the cuts).
#include <stdint.h>

#include <vector>

#include "net/network.hpp"

namespace lpsim {

struct PartLayout {
  std::vector<uint32_t> owned;   // lanes of the part, ascending
  std::vector<uint32_t> ghosts;  // lanes of other parts it sees, ascending
  uint64_t owned_cells = 0, ghost_cells = 0;
};

/// For lane_part (a part per lane, lane_parts()): each part's owned lanes and its ghosts, the lanes of other
/// parts that lie within `look_ahead` metres downstream of the end of one of its lanes (its vehicles' path
/// ahead and the room behind a junction), and within `tail` metres upstream of the start of one (the lanes a
/// vehicle that just crossed into the part still covers with its body), each with the other lanes of its
/// edge.
std::vector<PartLayout> partition_layout(const Network& net, const std::vector<int32_t>& lane_part,
                                         int32_t parts, double look_ahead, double tail);

}  // namespace lpsim

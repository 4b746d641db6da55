#pragma once
// Where a foe's path through a junction crosses a connection's path, from the lane shapes. A vehicle on the
// foe's junction-internal lane blocks the connection only until its rear has passed that point (SUMO checks
// foes against crossing points too); without it the whole internal lane would block.
#include <cstdint>
#include <vector>

#include "net/network.hpp"

namespace lpsim {

// Clearance behind a crossing point that a foe's rear must pass, about half a lane width on either side [m].
constexpr double kCrossingClearance = 2.0;

/// For each entry k of the foe CSR (connection c yields to foe_list[k]): the cells of the foe's via lane,
/// counted from its start, within which a vehicle still blocks c: up to the last point where the foe's via
/// lane crosses c's internal lanes (its via lane and, past an internal junction, the lane after it), plus
/// kCrossingClearance, and at least 1. The whole via lane where the shapes do not cross (a merge) or are
/// missing; 0 where the foe has no via lane.
std::vector<uint16_t> foe_block_cells(const Network& net, const std::vector<uint32_t>& foe_begin,
                                      const std::vector<uint32_t>& foe_list);

}  // namespace lpsim

#pragma once
// The room behind a junction, read from the lane map, for SUMO's junction-blocking rule
// (MSVehicle::checkRewindLinkLanes): a vehicle enters a link that has foes only when the lanes after it
// hold the vehicle before the first vehicle at a standstill. The lane map shows bodies, not vehicles: a run
// of equal non-zero cells is taken as one vehicle, whose length is its cells less one (a body of L metres
// covers L + 1 cells unless its ends fall on cell boundaries).
#include <stdint.h>

#include "kernels/hd.hpp"
#include "kernels/lane_map.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

/// What the scan of one lane found.
struct LaneRoom {
  float space;       // metres the lane still offers (may be negative)
  bool standing;     // the scan ended at a vehicle at a standstill
  bool empty;        // no vehicle on the lane
  float last_speed;  // speed of the vehicle nearest the lane's start (when not empty)
};

/// SUMO's space till the last standing vehicle (MSVehicle::getSpaceTillLastStanding): walking the lane from
/// its start, the rear of the first vehicle at a standstill (shown as speed 0 in the map) less the room the
/// moving vehicles behind it take (length + `min_gap` each); without a standing vehicle, the lane's length
/// less the room all its vehicles take. With `count_standing` false every vehicle counts as moving (the
/// room taken on a junction's internal lanes, SUMO's brutto vehicle length sum, is length - space then).
LPSIM_HD_INLINED LaneRoom room_on_lane(const uint8_t* map, const NetView& net, int32_t lane, float min_gap,
                                       bool count_standing) {
  const int32_t cells = static_cast<int32_t>(lane_cells(net, lane));
  const uint8_t* c = map + net.lane_cell_begin[lane];
  LaneRoom room{net.lane_length[lane], false, true, 0.0f};
  int32_t k = 0;
  while (k < cells) {
    const int32_t hit = first_occupied(map, net, lane, k, cells - 1);
    if (hit < 0) break;
    const uint8_t v = c[hit];
    if (room.empty) room.last_speed = decode_cell_speed(v);
    room.empty = false;
    if (count_standing && v == 1) {
      room.space = static_cast<float>(hit) - (net.lane_length[lane] - room.space);
      room.standing = true;
      return room;
    }
    int32_t end = hit;
    while (end + 1 < cells && c[end + 1] == v) ++end;
    room.space -= static_cast<float>(end - hit) + min_gap;
    k = end + 1;
  }
  return room;
}

}  // namespace lpsim

#pragma once
// A trip's departure and arrival columns from SUMO's attributes, for the loaded demand and for trips added
// during a run alike.
#include <cstdint>

#include "core/demand_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

/// The rank of SUMO lane index `sumo_index` among the car lanes of `edge`, or -1 when it is none of them.
int car_lane_position(const Network& net, uint32_t edge, int sumo_index);

/// Sets trip v's depart lane, position, speed and arrival position from `ds` (departLane given as SUMO's
/// lane index becomes the rank among the car lanes of its first edge; a negative departPos or arrivalPos
/// counts from the end of the first or last edge). False, changing nothing of the lane, when a given
/// departLane is not a car lane of `first_edge`.
bool set_departure(Demand& d, uint32_t v, const DepartSpec& ds, const Network& net, uint32_t first_edge,
                   uint32_t last_edge);

}  // namespace lpsim

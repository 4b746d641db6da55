#include "demand/departure.hpp"

namespace lpsim {

int car_lane_position(const Network& net, uint32_t edge, int sumo_index) {
  const uint32_t first = net.edge_first_lane[edge];
  for (uint32_t k = 0; k < net.edge_num_lanes[edge]; ++k)
    if (net.lane_index[first + k] == sumo_index) return static_cast<int>(k);
  return -1;
}

bool set_departure(Demand& d, uint32_t v, const DepartSpec& ds, const Network& net, uint32_t first_edge,
                   uint32_t last_edge) {
  d.depart_lane_kind[v] = static_cast<uint8_t>(ds.lane);
  d.depart_lane[v] = 0;
  if (ds.lane == DepartLane::Given) {
    const int position = car_lane_position(net, first_edge, ds.lane_index);
    if (position < 0) return false;
    d.depart_lane[v] = static_cast<int8_t>(position);
  }
  d.depart_pos_kind[v] = static_cast<uint8_t>(ds.pos);
  d.depart_pos[v] = static_cast<float>(ds.pos == DepartPos::Given && ds.pos_value < 0
                                           ? ds.pos_value + net.edge_length[first_edge]
                                           : ds.pos_value);
  d.depart_speed_kind[v] = static_cast<uint8_t>(ds.speed);
  d.depart_speed[v] = static_cast<float>(ds.speed_value);
  d.arrival_pos_kind[v] = static_cast<uint8_t>(ds.arrival);
  d.arrival_pos[v] = static_cast<float>(ds.arrival == ArrivalPos::Given && ds.arrival_value < 0
                                            ? ds.arrival_value + net.edge_length[last_edge]
                                            : ds.arrival_value);
  return true;
}

}  // namespace lpsim

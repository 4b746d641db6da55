#include "engine/outside_link.hpp"

#include <algorithm>
#include <stdexcept>

#include "kernels/lane_map.hpp"

namespace lpsim {

OutsideLink::OutsideLink(const LinkScope& run, const std::vector<uint8_t>& outside_lanes, double step_length)
    : BoundaryLink(run), outside_(outside_lanes), step_length_(step_length) {
  if (outside_.size() != run_.net.num_lanes())
    throw std::invalid_argument("outside lanes: " + std::to_string(outside_.size()) + " flags for " +
                                std::to_string(run_.net.num_lanes()) + " lanes");
  all_lanes_.assign(run_.net.num_lanes(), 1);
  held_lanes_ = all_lanes_.data();
}

void OutsideLink::mirror_outside_vehicles(const std::vector<OutsideVehicle>& vehicles) {
  mirror_.clear();
  for (const OutsideVehicle& o : vehicles) {
    if (o.lane < 0 || static_cast<uint32_t>(o.lane) >= run_.net.num_lanes() ||
        !outside_[static_cast<uint32_t>(o.lane)])
      throw std::invalid_argument("mirrored vehicle on lane " + std::to_string(o.lane) +
                                  ", not one driven outside");
    mirror_.push_back(FootprintWrite{Footprint{o.lane, -1, -1, std::max(0.0f, o.pos)}, o.length,
                                     encode_cell_speed(o.speed)});
  }
}

// The other simulator's vehicles as they are at the end of this step are written before this step's
// insertions, which must not overlap them, and the next step's passes, which read them; this step's passes
// read the other map, with them as they were at its start.
void OutsideLink::before_writing(int map) {
  erase_foreign(map);
  write_foreign(map, mirror_);
}

// The running vehicles whose front is on an outside lane leave, in vehicle order after the departures and
// re-entries due outside.
void OutsideLink::after_end_of_step(int map) {
  hand_outs_.swap(departing_outside_);
  departing_outside_.clear();
  const size_t off_road = hand_outs_.size();
  TripLedger& ledger = run_.books.ledger;
  const std::vector<uint32_t> gone = hand_out(map, [&](const HostState& st, uint32_t k, const Footprint& fp,
                                                       float) {
    if (!outside_[static_cast<uint32_t>(fp.lane)]) return false;
    const uint32_t v = st.veh.vehicle[k];
    hand_outs_.push_back(HandOut{v, fp.lane, fp.pos, st.veh.speed[k], st.veh.route_pos[k]});
    ledger.handed_out(v, TripCounters{st.veh.route_length[k], st.veh.time_loss[k], st.veh.waiting_steps[k],
                                      st.veh.waiting_count[k], st.veh.next_stop[k], st.veh.stop_steps[k]});
    return true;
  });
  handed_out_ += gone.size();
  std::sort(hand_outs_.begin() + static_cast<std::ptrdiff_t>(off_road), hand_outs_.end(),
            [](const HandOut& a, const HandOut& b) { return a.vehicle < b.vehicle; });
}

bool OutsideLink::outside_edge(uint32_t edge) const {
  return run_.net.edge_num_lanes[edge] > 0 && outside_[run_.net.edge_first_lane[edge]];
}

// Its trip starts in the other simulator.
bool OutsideLink::takes_departure(uint32_t v, uint32_t edge) {
  if (!outside_edge(edge)) return false;
  TripCounters none;
  none.next_stop = run_.trips.demand().stops.first(v);
  run_.books.ledger.handed_out(v, none);
  departing_outside_.push_back(HandOut{v, -1, 0, 0, 0});
  ++handed_out_;
  return true;
}

// Its next edge is driven elsewhere: it re-enters there, in the other simulator.
bool OutsideLink::takes_reentry(const VehicleEnd& end, uint32_t rp, uint32_t edge) {
  if (!outside_edge(edge)) return false;
  run_.books.ledger.handed_out(end.vehicle, trip_counters(end));
  departing_outside_.push_back(HandOut{end.vehicle, -1, 0, 0, rp});
  ++handed_out_;
  return true;
}

void OutsideLink::take_back(uint32_t v, uint32_t route_pos, int32_t lane, float pos, float speed) {
  const Demand& d = run_.trips.demand();
  const Network& net = run_.net;
  TripLedger& ledger = run_.books.ledger;
  if (v >= d.size() || ledger.status(v) != kMigrated)
    throw std::invalid_argument("take_back: vehicle " + (v < d.size() ? d.vehicle_id[v] : std::to_string(v)) +
                                " was not handed out");
  if (route_pos >= d.route_length[v])
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] + " has no route edge " +
                                std::to_string(route_pos));
  const uint32_t edge = d.route_edges[d.route_begin[v] + route_pos];
  if (outside_edge(edge))
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] +
                                " re-enters on an edge driven outside");
  if (lane >= 0 && (static_cast<uint32_t>(lane) < net.edge_first_lane[edge] ||
                    static_cast<uint32_t>(lane) >= net.edge_first_lane[edge] + net.edge_num_lanes[edge]))
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] + " re-enters on lane " +
                                std::to_string(lane) + ", not one of edge " + net.edge_id[edge]);
  // The next step inserts it where it gets to in that step, as it would have driven on.
  const float lane_length =
      net.lane_length[lane >= 0 ? static_cast<uint32_t>(lane) : net.edge_first_lane[edge]];
  const float wanted = position_driven_on(pos, speed, static_cast<float>(step_length_), lane_length);
  ledger.handed_back(v, route_pos, lane, std::max(0.0f, pos), wanted, speed);
  run_.books.queues.push_back(edge, queue_entry(v, true));
}

bool OutsideLink::has_entry_room(uint32_t edge) const {
  return run_.books.queues.waiting_at(edge) < std::max<uint32_t>(1, run_.net.edge_num_lanes[edge]);
}

}  // namespace lpsim

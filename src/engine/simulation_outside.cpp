// The co-simulation's boundary in the Simulation: lanes another simulator drives. Its vehicles there are
// written into the lane map like another part's (the footprints a part receives), so that this simulation's
// vehicles queue behind them and enter only where there is room; a vehicle whose front reaches such a lane
// leaves at the end of that step, like a vehicle driving into another part, and is handed to the other side.
#include <algorithm>
#include <stdexcept>

#include "engine/simulation.hpp"
#include "kernels/lane_map.hpp"

namespace lpsim {

void Simulation::mirror_outside_vehicles(const std::vector<OutsideVehicle>& vehicles) {
  if (!opt_.outside_lanes) throw std::logic_error("mirror_outside_vehicles() without outside lanes");
  mirror_.clear();
  for (const OutsideVehicle& o : vehicles) {
    if (o.lane < 0 || static_cast<uint32_t>(o.lane) >= net_.num_lanes() ||
        !(*opt_.outside_lanes)[static_cast<uint32_t>(o.lane)])
      throw std::invalid_argument("mirrored vehicle on lane " + std::to_string(o.lane) +
                                  ", not one driven outside");
    mirror_.push_back(FootprintWrite{Footprint{o.lane, -1, -1, std::max(0.0f, o.pos)}, o.length,
                                     encode_cell_speed(o.speed)});
  }
}

// Before the step writes lane map `map`: what was written into it from outside is erased, and the other
// simulator's vehicles as they are at the end of this step are written (before this step's insertions,
// which must not overlap them, and the next step's passes, which read them); this step's passes read the
// other map, with them as they were at its start.
void Simulation::write_outside_footprints(int map) {
  std::vector<FootprintWrite>& kept = outside_footprints_[map];  // values 0: erasures
  if (!kept.empty()) stepper_->write_footprints(map, kept, all_lanes_.data());
  kept.clear();
  if (mirror_.empty()) return;
  stepper_->write_footprints(map, mirror_, all_lanes_.data());
  for (const FootprintWrite& w : mirror_) kept.push_back(FootprintWrite{w.fp, w.length, 0});
}

// After the end of step: the running vehicles whose front is on an outside lane leave, in vehicle order.
void Simulation::hand_out_vehicles() {
  hand_outs_.swap(departing_outside_);
  departing_outside_.clear();
  const size_t departures = hand_outs_.size();
  const std::vector<uint8_t>& outside = *opt_.outside_lanes;
  const HostState& st = stepper_->fetch(StateParts::Columns, slots_.size());
  const float* length = trips_.demand().types.length.data();
  std::vector<uint32_t> gone;
  for (uint32_t i = 0; i < st.num_active; ++i) {
    const uint32_t k = st.active[i];
    if (st.veh.status[k] != kRunning || !outside[static_cast<uint32_t>(st.veh.lane[k])]) continue;
    const uint32_t v = st.veh.vehicle[k];
    hand_outs_.push_back(HandOut{v, st.veh.lane[k], st.veh.pos[k], st.veh.speed[k], st.veh.route_pos[k]});
    // Its footprint in the map the step wrote is erased when that map is next written (its slot stops).
    const Footprint fp{st.veh.lane[k], st.veh.prev[k], st.veh.prev2[k], st.veh.pos[k]};
    outside_footprints_[1 - cur_].push_back(FootprintWrite{fp, length[st.veh.trip_type[k]], 0});
    ledger_.handed_out(v, TripCounters{st.veh.route_length[k], st.veh.time_loss[k], st.veh.waiting_steps[k],
                                       st.veh.waiting_count[k], st.veh.next_stop[k], st.veh.stop_steps[k]});
    gone.push_back(k);
  }
  if (gone.empty()) return;
  stepper_->mark_migrated(gone);
  for (const uint32_t k : gone) retiring_next_.push_back(k);
  handed_out_ += gone.size();
  handed_out_last_step_ = static_cast<uint32_t>(gone.size());
  std::sort(hand_outs_.begin() + static_cast<std::ptrdiff_t>(departures), hand_outs_.end(),
            [](const HandOut& a, const HandOut& b) { return a.vehicle < b.vehicle; });
}

bool Simulation::outside_edge(uint32_t edge) const {
  return opt_.outside_lanes && net_.edge_num_lanes[edge] > 0 &&
         (*opt_.outside_lanes)[net_.edge_first_lane[edge]];
}

void Simulation::take_back(uint32_t v, uint32_t route_pos, int32_t lane, float pos, float speed) {
  if (!opt_.outside_lanes) throw std::logic_error("take_back() without outside lanes");
  const Demand& d = trips_.demand();
  if (v >= d.size() || ledger_.status(v) != kMigrated)
    throw std::invalid_argument("take_back: vehicle " + (v < d.size() ? d.vehicle_id[v] : std::to_string(v)) +
                                " was not handed out");
  if (route_pos >= d.route_length[v])
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] + " has no route edge " +
                                std::to_string(route_pos));
  const uint32_t edge = d.route_edges[d.route_begin[v] + route_pos];
  if (outside_edge(edge))
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] +
                                " re-enters on an edge driven outside");
  if (lane >= 0 && (static_cast<uint32_t>(lane) < net_.edge_first_lane[edge] ||
                    static_cast<uint32_t>(lane) >= net_.edge_first_lane[edge] + net_.edge_num_lanes[edge]))
    throw std::invalid_argument("take_back: vehicle " + d.vehicle_id[v] + " re-enters on lane " +
                                std::to_string(lane) + ", not one of edge " + net_.edge_id[edge]);
  // The next step inserts it where it gets to in that step, as it would have driven on.
  const float lane_length =
      net_.lane_length[lane >= 0 ? static_cast<uint32_t>(lane) : net_.edge_first_lane[edge]];
  const float wanted = position_driven_on(pos, speed, static_cast<float>(step_length()), lane_length);
  ledger_.handed_back(v, route_pos, lane, std::max(0.0f, pos), wanted, speed);
  queues_.push_back(edge, queue_entry(v, true));
}

bool Simulation::has_entry_room(uint32_t edge) const {
  return queues_.waiting_at(edge) < std::max<uint32_t>(1, net_.edge_num_lanes[edge]);
}

}  // namespace lpsim

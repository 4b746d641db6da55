#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/time_range.hpp"
#include "engine/part_state.hpp"
#include "kernels/idm.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

namespace {

// The summary's speed sums count in units of 2^-24 m/s (and of 2^-24 of the desired speed).
constexpr double kSummaryUnits = 16777216.0;

// kernels/insert_vehicle.hpp reads the demand's depart kinds as plain bytes.
static_assert(kDepartLaneGiven == uint8_t(DepartLane::Given) &&
              kDepartLaneRandom == uint8_t(DepartLane::Random) &&
              kDepartLaneFree == uint8_t(DepartLane::Free) && kDepartLaneBest == uint8_t(DepartLane::Best));
static_assert(kDepartPosGiven == uint8_t(DepartPos::Given) &&
              kDepartPosRandom == uint8_t(DepartPos::Random) &&
              kDepartPosRandomFree == uint8_t(DepartPos::RandomFree) &&
              kDepartPosFree == uint8_t(DepartPos::Free) && kDepartPosLast == uint8_t(DepartPos::Last) &&
              kDepartPosStop == uint8_t(DepartPos::Stop));
static_assert(kDepartSpeedGiven == uint8_t(DepartSpeed::Given) &&
              kDepartSpeedZero == uint8_t(DepartSpeed::Zero) &&
              kDepartSpeedRandom == uint8_t(DepartSpeed::Random) &&
              kDepartSpeedMax == uint8_t(DepartSpeed::Max) &&
              kDepartSpeedDesired == uint8_t(DepartSpeed::Desired) &&
              kDepartSpeedLimit == uint8_t(DepartSpeed::SpeedLimit) &&
              kDepartSpeedLast == uint8_t(DepartSpeed::Last) && kDepartSpeedAvg == uint8_t(DepartSpeed::Avg));

// Steps a vehicle must stand to wait `seconds` (0: never, for a time of 0 or less). Beyond 2^32 - 1 steps it
// would never happen anyway (the stopped-steps counter is 32 bits): capped.
uint32_t stopped_steps_for(double seconds, double step_length) {
  return seconds > 0 ? static_cast<uint32_t>(std::min(std::ceil(seconds / step_length), 4294967295.0)) : 0;
}

// SUMO's teleport causes: "wrong lane", "yield" when the link the vehicle waits at has no priority (a minor
// link, a stop rule, or a red or yellow light, whose SUMO states are lower case too), else "jam".
TeleportCause teleport_cause(uint8_t limit_reason) {
  if (limit_reason == kWrongLane) return TeleportCause::WrongLane;
  if (limit_reason == kYield || limit_reason == kSignal || limit_reason == kHaltRule)
    return TeleportCause::Yield;
  return TeleportCause::Jam;
}

}  // namespace

Simulation::Simulation(const Network& net, Demand demand, const SimulationOptions& options)
    : net_(net), trips_(std::move(demand)), opt_(options), engine_net_(net, options.part), queues_(net) {
  if (opt_.step_ms <= 0) throw std::invalid_argument("step length must be a positive number of milliseconds");
  const Demand& d = trips_.demand();
  if (d.size() >= kMaxVehicles)
    throw std::invalid_argument("too many vehicles: " + std::to_string(d.size()) + " (at most " +
                                std::to_string(kMaxVehicles - 1) + ")");
  dt_ms_ = opt_.step_ms;
  time_ms_ = std::llround(opt_.begin * 1000.0);
  num_loaded_ = d.size();
  counts_.loaded = num_loaded_;
  ledger_.resize(num_loaded_);
  // kNumLaneCounters columns over every lane: kept only for edgeData/laneData (collect_lane_counters() sizes
  // them when asked without), the emission sums only for emissions outputs.
  if (opt_.lane_counters || opt_.emission_sums) lane_counters_.resize(net.num_lanes(), opt_.emission_sums);

  const VehicleTypes& t = d.types;
  for (uint32_t k = 0; k < t.size(); ++k) {
    max_accel_ = std::max(max_accel_, t.accel[k]);
    max_emergency_decel_ = std::max(max_emergency_decel_, t.emergency_decel[k]);
    min_decel_ = std::min(min_decel_, t.decel[k]);
  }
  // Vehicles that depart before the begin time are not simulated (as SUMO, which skips them).
  while (next_departure_ < num_loaded_ && seconds_to_ms(d.depart[next_departure_]) < time_ms_) {
    ledger_.set_status(next_departure_, kArrived);
    ++counts_.removed;
    ++next_departure_;
  }
  teleport_steps_ = stopped_steps_for(opt_.time_to_teleport, step_length());
  highway_teleport_steps_ = stopped_steps_for(opt_.time_to_teleport_highways, step_length());
  impatience_steps_ = stopped_steps_for(opt_.time_to_impatience, step_length());
  // 0 s ignores every vehicle on a junction lane, standing or not, as in SUMO.
  ignore_blocker_steps_ = stopped_steps_for(opt_.ignore_junction_blocker, step_length());
  stop_steps_from_times();

  if ((opt_.part == nullptr) != (opt_.transport == nullptr))
    throw std::invalid_argument("a part of a partitioned run needs both its plan and its transport");
  if (opt_.part != nullptr) init_parts();
  if (opt_.outside_lanes) {
    if (opt_.part) throw std::invalid_argument("lanes driven by another simulator need a run of one part");
    if (opt_.outside_lanes->size() != net.num_lanes())
      throw std::invalid_argument("outside lanes: " + std::to_string(opt_.outside_lanes->size()) +
                                  " flags for " + std::to_string(net.num_lanes()) + " lanes");
    all_lanes_.assign(net.num_lanes(), 1);
  }

  StepperSetup setup;
  setup.net = engine_net_.view(net_);
  setup.signals = engine_net_.signal_table(net_);
  setup.types = TypeView{t.length.data(),
                         t.min_gap.data(),
                         t.accel.data(),
                         t.decel.data(),
                         t.emergency_decel.data(),
                         t.max_speed.data(),
                         t.desired_max_speed.data(),
                         t.tau.data(),
                         t.delta.data(),
                         t.sigma.data(),
                         t.model.data(),
                         t.vclass_mask.data()};
  setup.num_types = t.size();
  setup.num_edges = net.num_edges();
  setup.num_connections = net.num_connections();
  setup.yielder_begin = engine_net_.yielder_begin.data();
  setup.yielder = engine_net_.yielder.data();
  setup.trips = trip_table_view();
  setup.lane_counters = opt_.lane_counters;
  setup.junction_stands = opt_.ignore_junction_blocker >= 0;
  setup.emission_sums = opt_.emission_sums;
  fuel_divisor_.resize(t.size());
  for (uint32_t k = 0; k < t.size(); ++k)
    fuel_divisor_[k] = opt_.volumetric_fuel ? kHbefaScale * t.fuel_density[k] : kHbefaScale;
  setup.emission_types = EmissionView{t.emission_model.data(),
                                      t.emission_coeff.data(),
                                      t.coast_incl.data(),
                                      t.coast_mass_term.data(),
                                      fuel_divisor_.data(),
                                      t.shut_off_stop.data(),
                                      nullptr,
                                      net.num_lanes()};
  setup.threads = opt_.threads;
  setup.device = opt_.gpu_device;
  stepper_ = opt_.backend(setup);

  init_rerouting();
  // The state at the begin time: its signals and its first insertions.
  stepper_->update_signals(time_ms_, time_ms_, cur_);
  if (parts_) share_signals();
  if (reroute_) reroute_vehicles(time_ms_);
  sync_trips();
  enqueue_due(time_ms_);
  insert_waiting(cur_);
  if (parts_) share_insertions(cur_);
  check_kept(0);
  start_inserted(0, 0);
  ++version_;  // the insertions changed the state (the rerouting device may have read it before them)
  if (reroute_) sample_routing_speeds();
  if (parts_) report_to_root();
}

// Part 0 of a partitioned run ends the other parts' serve_part().
Simulation::~Simulation() {
  if (!parts_ || parts_->plan.part != 0) return;
  try {
    request(kRequestStop);
  } catch (const std::exception&) {
    // A part that failed has ended its serve_part() already; its error was reported where it failed.
  }
}

bool Simulation::finished() const {
  const bool idle = parts_ ? parts_->all_idle : num_active_ == 0 && queues_.waiting() == 0;
  return idle && next_departure_ >= num_loaded_ && added_due_.empty();
}

// The stops' times as the step counts them: steps stood at least, and the step from which `until` lets a
// vehicle leave: the one that ends at `until` (counted from the begin time; 0: none, or already past).
void Simulation::stop_steps_from_times() {
  const StopTable& st = trips_.demand().stops;
  stop_duration_steps_.resize(st.size());
  stop_until_step_.resize(st.size());
  const double cap = static_cast<double>(std::numeric_limits<uint32_t>::max() / 2);
  for (uint32_t k = 0; k < st.size(); ++k) {
    const double duration = std::ceil(std::llround(st.duration[k] * 1000.0) / static_cast<double>(dt_ms_));
    stop_duration_steps_[k] = static_cast<uint32_t>(std::min(duration, cap));
    const double until = st.until[k] < 0
                             ? 0.0
                             : std::ceil(static_cast<double>(std::llround(st.until[k] * 1000.0) - time_ms_) /
                                         static_cast<double>(dt_ms_)) -
                                   1.0;
    stop_until_step_[k] = static_cast<uint32_t>(std::clamp(until, 0.0, cap));
  }
}

// Vehicle v's scheduled stops still to make when it enters the road at route position `rp`: from
// `next` (where a teleport left it, else its first) on, skipping those on edges it has already left.
void Simulation::set_stops(SlotInit& init, uint32_t next) const {
  const StopTable& st = trips_.demand().stops;
  init.stops_end = st.last(init.vehicle);
  while (next < init.stops_end && st.route_pos[next] < init.route_pos) ++next;
  init.next_stop = next;
}

TripTableView Simulation::trip_table_view() const {
  const Demand& d = trips_.demand();
  TripTableView v;
  const StopTable& st = d.stops;
  v.trips = TripView{d.vehicle_type.data(),  d.route_begin.data(),  d.route_length.data(),
                     d.route_edges.data(),   d.speed_factor.data(), d.arrival_pos_kind.data(),
                     d.arrival_pos.data(),   st.route_pos.data(),   st.lane.data(),
                     st.start_pos.data(),    st.end_pos.data(),     stop_duration_steps_.data(),
                     stop_until_step_.data()};
  v.num_stops = st.size();
  v.depart = DepartView{d.depart_lane_kind.data(), d.depart_lane.data(),       d.depart_pos_kind.data(),
                        d.depart_pos.data(),       d.depart_speed_kind.data(), d.depart_speed.data()};
  v.num_vehicles = d.size();
  v.num_route_edges = d.route_edges.size();
  return v;
}

// The backend reads the trip table through its own pointers (or its own copy, on a device): after the table
// grew or a route changed, it is handed the table as it lies now and what changed.
void Simulation::sync_trips() {
  if (!trips_.changed()) return;
  TripTable::Changes c = trips_.take_changes();
  TripChanges changes{c.first_new_vehicle, c.first_new_route_edge, std::move(c.new_routes), c.stops_moved};
  stepper_->update_trips(trip_table_view(), changes);
}

StepParams Simulation::step_params() const {
  const float dt = static_cast<float>(dt_ms_) / 1000.0f;
  return StepParams{step_,
                    time_ms_ + dt_ms_,
                    dt,
                    opt_.seed,
                    idm_default_substeps(dt),
                    max_accel_,
                    max_emergency_decel_,
                    teleport_steps_,
                    impatience_steps_,
                    ignore_blocker_steps_,
                    highway_teleport_steps_,
                    static_cast<float>(opt_.highway_min_speed)};
}

void Simulation::step() {
  const auto t0 = std::chrono::steady_clock::now();
  if (parts_ && parts_->plan.part == 0) request(kRequestStep);
  if (reroute_) reroute_vehicles(time_ms_ + dt_ms_);
  sync_trips();
  ++version_;
  Stepper& s = *stepper_;
  const StepParams params = step_params();
  s.update_signals(params.signal_time_ms, time_ms_, cur_);
  if (parts_) share_signals();
  s.start_step(params, cur_);
  s.clear_footprints();
  if (parts_) forget_remote_footprints(1 - cur_);
  if (opt_.outside_lanes) write_outside_footprints(1 - cur_);
  s.approach();
  if (parts_) share_approaches();
  s.plan();
  if (parts_) share_claims();
  s.commit();
  if (opt_.emission_sums) s.count_emissions();
  s.start_end_of_step(step_ + 1);
  // While a device runs the passes: the departures due by the end of the step join their queues. Nothing
  // there depends on the step's outcome, and the order does not matter: a vehicle teleported in the step
  // joins its queue at the head (handle_vehicle_ends), a departure at the tail.
  enqueue_due(time_ms_ + dt_ms_);
  StepOutcome& out = s.finish_end_of_step();
  check_kept(out.kept);
  // The vehicles the step moved: not the slots of those that left the road in the step before (they only
  // cleared their footprint), so a vehicle that drives into another part counts once.
  counts_.vehicle_updates += out.kept;

  time_ms_ += dt_ms_;
  ++step_;
  handle_vehicle_ends(out.ends);
  if (!moves_.empty()) s.apply_teleports(moves_, step_);
  if (parts_) exchange_vehicles();
  if (opt_.outside_lanes) hand_out_vehicles();
  insert_waiting(1 - cur_);
  if (parts_) share_insertions(1 - cur_);
  cur_ = 1 - cur_;
  start_inserted(out.kept, out.running);
  if (reroute_) sample_routing_speeds();
  if (parts_) {
    PartStats& st = parts_->stats;
    ++st.steps;
    st.vehicle_updates = counts_.vehicle_updates;
    st.step_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report_to_root();
  }
  if (opt_.slot_sort_interval > 0 && step_ % opt_.slot_sort_interval == 0) sort_slots();
  step_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Exactly the slots whose vehicles left the road in the previous step drop out of the active list
// (stays_active): anything else would free a slot still in use, or never free one.
void Simulation::check_kept(uint32_t kept) const {
  if (kept + retiring_.size() != num_active_)
    throw std::logic_error("step kept " + std::to_string(kept) + " of " + std::to_string(num_active_) +
                           " active slots, " + std::to_string(retiring_.size()) + " were to leave");
}

// Arrivals become trip records; teleporting vehicles re-enter at the next edge of their route (moves_ says
// which, for the backend to apply). Handled in vehicle order (the passes find them in slot order); their
// slots are free once the next step has cleared their footprint.
void Simulation::handle_vehicle_ends(std::vector<VehicleEnd>& ends) {
  std::sort(ends.begin(), ends.end(),
            [](const VehicleEnd& a, const VehicleEnd& b) { return a.vehicle < b.vehicle; });
  const Demand& d = trips_.demand();
  moves_.clear();
  teleport_events_.clear();
  for (const VehicleEnd& e : ends) {
    const uint32_t v = e.vehicle;
    retiring_next_.push_back(e.slot);
    if (e.kind == kEndArrived) {
      ++counts_.arrived;
      ledger_.ended(e, false, time(), d.depart[v], step_length(), d.speed_factor[v]);
      continue;
    }
    ++counts_.teleports;
    const TeleportCause cause = teleport_cause(e.limit_reason);
    // The wrong-lane rule of a fast road's lane clocks out first where its time is the shorter.
    const bool highway =
        cause == TeleportCause::WrongLane && highway_teleport_steps_ > 0 &&
        (teleport_steps_ == 0 || highway_teleport_steps_ < teleport_steps_) &&
        net_.lane_speed[static_cast<uint32_t>(e.lane)] > static_cast<float>(opt_.highway_min_speed);
    teleport_events_.push_back(TeleportEvent{v, static_cast<uint32_t>(e.lane), cause, highway});
    if (e.route_pos + 1 >= d.route_length[v]) {
      // Teleported past the end of its route: the trip ends here.
      moves_.push_back(TeleportMove{v, e.slot, 1});
      ++counts_.arrived;
      ledger_.ended(e, true, time(), d.depart[v], step_length(), d.speed_factor[v]);
      continue;
    }
    moves_.push_back(TeleportMove{v, e.slot, 0});
    const uint32_t edge = d.route_edges[d.route_begin[v] + e.route_pos + 1];
    if (outside_edge(edge)) {
      // Its next edge is driven elsewhere: it re-enters there, in the other simulator.
      ledger_.handed_out(v, trip_counters(e));
      departing_outside_.push_back(HandOut{v, -1, 0, 0, e.route_pos + 1});
      ++handed_out_;
      continue;
    }
    if (parts_) {  // the edge's owner queues it (exchange_vehicles)
      parts_->teleports.push_back(TeleportHandOver{e, e.route_pos + 1, edge, ledger_.departure(v)});
      continue;
    }
    ledger_.teleporting(e, e.route_pos + 1);
    queues_.push_front(edge, queue_entry(v, true));
  }
}

// Trips whose departure is due by `until_ms` join their first edge's queue, in the order of their depart
// times, ties by index: the loaded ones (sorted by depart) and those added during the run.
void Simulation::enqueue_due(int64_t until_ms) {
  const Demand& d = trips_.demand();
  for (;;) {
    const bool loaded_due =
        next_departure_ < num_loaded_ && seconds_to_ms(d.depart[next_departure_]) <= until_ms;
    const bool added_due = !added_due_.empty() && added_due_.back().first <= until_ms;
    if (!loaded_due && !added_due) break;
    // An added trip has a higher index than every loaded one: it goes first only when it departs earlier.
    if (added_due && (!loaded_due || added_due_.back().first < seconds_to_ms(d.depart[next_departure_]))) {
      enqueue(added_due_.back().second);
      added_due_.pop_back();
    } else {
      enqueue(next_departure_++);
    }
  }
}

void Simulation::enqueue(uint32_t v) {
  const Demand& d = trips_.demand();
  if (d.route_length[v] == 0 || !queues_.has_lanes(d.route_edges[d.route_begin[v]])) {
    ledger_.set_status(v, kArrived);
    ++counts_.removed;
    return;
  }
  const uint32_t edge = d.route_edges[d.route_begin[v]];
  if (parts_ && parts_->plan.edge_owner[edge] != parts_->plan.part) return;  // another part inserts it
  if (outside_edge(edge)) {
    TripCounters none;
    none.next_stop = d.stops.first(v);
    ledger_.handed_out(v, none);  // its trip starts in the other simulator
    departing_outside_.push_back(HandOut{v, -1, 0, 0, 0});
    ++handed_out_;
    return;
  }
  queues_.push_back(edge, queue_entry(v, false));
}

void Simulation::insert_waiting(int map_index) {
  const InsertBatch& batch = queues_.offer(ledger_.reentry_wants());
  // The step length as a float in the one way the insertion checks have always used it.
  const InsertParams params{static_cast<float>(step_length()),
                            opt_.seed,
                            static_cast<uint32_t>(step_),
                            max_emergency_decel_,
                            min_decel_,
                            nullptr,
                            nullptr};
  if (queues_.offered_entries() > 0) stepper_->insert(batch, queues_.offered_entries(), params, map_index);

  // Advance the queues past the inserted heads, give each inserted vehicle a slot and record the
  // departures, in the order of the batch.
  const Demand& d = trips_.demand();
  inits_.clear();
  // Each entry's edge, for a partitioned run's report of the departures in the order one part inserts.
  if (parts_) {
    entry_edge_.resize(queues_.offered_entries());
    for (uint32_t slot = 0; slot < batch.num_slots; ++slot)
      std::fill(entry_edge_.begin() + batch.begin[slot], entry_edge_.begin() + batch.begin[slot + 1],
                batch.edge[slot]);
  }
  queues_.take_inserted([&](uint32_t i) {
    const uint32_t v = batch.entry[i] & ~kInsertTeleported;
    SlotInit init{0,
                  v,
                  batch.route_pos[i],
                  batch.out_lane[i],
                  batch.out_pos[i],
                  batch.out_speed[i],
                  0.0f,
                  0.0f,
                  0,
                  0,
                  0,
                  0,
                  0};
    if (batch.entry[i] & kInsertTeleported) {
      set_stops(init, ledger_.reentering(init));
    } else {
      ++counts_.inserted;
      ledger_.departed(v, time(), d.depart[v], init);
      if (parts_)
        parts_->departures.push_back(DepartDelay{uint64_t{entry_edge_[i]} << 32 | i, time() - d.depart[v]});
      set_stops(init, d.stops.first(v));
    }
    init.slot = slots_.take();
    inits_.push_back(init);
  });
  if (opt_.max_depart_delay >= 0) drop_late_departures();
}

// SUMO's --max-depart-delay: a departure that could not be inserted in this step, which ends more than the
// delay after its depart time, is dropped (MSInsertionControl::tryInsert); queued vehicles behind a failed
// head were not tried and are dropped alike, as in SUMO.
void Simulation::drop_late_departures() {
  const Demand& d = trips_.demand();
  const int64_t max_delay_ms = std::llround(opt_.max_depart_delay * 1000.0);
  queues_.drop_departures([&](uint32_t v) {
    if (time_ms_ - seconds_to_ms(d.depart[v]) <= max_delay_ms) return false;
    ledger_.set_status(v, kArrived);
    ++counts_.discarded;
    return true;
  });
}

// The vehicles inserted in this step start in their slots and join the active list; the slots that left it
// in this step (their vehicles left the road in the previous one) are free.
void Simulation::start_inserted(uint32_t kept, uint32_t running) {
  added_.clear();
  for (const SlotInit& in : inits_) added_.push_back(in.slot);
  // In a partitioned run, also the vehicles that drove in from other parts; those that drove out ran.
  uint32_t adopted = 0, migrated = 0;
  if (parts_) {
    adopted = static_cast<uint32_t>(parts_->adopted.size());
    migrated = parts_->migrated;
    added_.insert(added_.end(), parts_->adopted.begin(), parts_->adopted.end());
    parts_->adopted.clear();
    parts_->migrated = 0;
  }
  std::sort(added_.begin(), added_.end());
  stepper_->start_vehicles(inits_, added_);
  num_active_ = kept + static_cast<uint32_t>(added_.size());
  // Running vehicles: those of the step's active list, and every one inserted.
  counts_.running = running + inits_.size() + adopted - migrated - handed_out_last_step_;
  handed_out_last_step_ = 0;
  counts_.waiting = queues_.waiting();
  inits_.clear();
  for (const uint32_t k : retiring_) slots_.release(k);
  retiring_.swap(retiring_next_);
  retiring_next_.clear();
}

// Renumbers the slots of the vehicles on the road densely from 0 in the order of their lanes (ties: the old
// slot), so that a pass meets the vehicles of one lane, and of neighbouring lanes, one after the other: their
// lane-map cells and lane columns are then read together instead of scattered over the network. Runs between
// steps, when the slots in use are exactly the active list. Nothing depends on a vehicle's slot number
// (claims break ties by vehicle, random draws are keyed by vehicle, ends are handled in vehicle order, a
// vehicle's slot is looked up in the active list), so results are unchanged. The host keeps only the slots
// due to leave (retiring_), which are renumbered with the rest.
void Simulation::sort_slots() {
  stepper_->sort_slots(retiring_);
  for (const uint32_t k : retiring_)
    if (k == kNotActive) throw std::logic_error("a slot due to leave was not in the active list");
  slots_.reset(num_active_);
}

uint32_t Simulation::add_trip(const NewTrip& trip) {
  const uint32_t v = trips_.add(trip, net_);
  ledger_.resize(trips_.size());
  ++counts_.loaded;
  // Soonest last; among trips due at once, the lowest index last.
  const std::pair<int64_t, uint32_t> due{seconds_to_ms(trip.depart), v};
  added_due_.insert(std::upper_bound(added_due_.begin(), added_due_.end(), due, std::greater<>()), due);
  return v;
}

void Simulation::set_route(uint32_t v, const std::vector<uint32_t>& edges) {
  const Demand& d = trips_.demand();
  if (v >= d.size()) throw std::invalid_argument("set_route: no vehicle " + std::to_string(v));
  auto refuse = [&](const std::string& why) {
    throw std::invalid_argument("vehicle '" + d.vehicle_id[v] + "': new route refused: " + why);
  };
  if (edges.empty()) refuse("it is empty");
  for (const uint32_t e : edges)
    if (e >= net_.num_edges() || net_.edge_is_internal[e]) refuse("no normal edge " + std::to_string(e));
  if (!TripTable::connected(net_, edges, d.types.vclass_mask[d.vehicle_type[v]]))
    refuse("it is not connected for the vehicle's vClass");
  const uint32_t* old = d.route_edges.data() + d.route_begin[v];
  auto must_start_at = [&](uint32_t rp, const char* where) {
    if (edges.front() != old[rp])
      refuse(std::string("it starts at edge '") + net_.edge_id[edges.front()] + "', the vehicle " + where +
             " '" + net_.edge_id[old[rp]] + "'");
  };

  const int32_t k = slot_of(v);
  const HostState& s = state(StateParts::Full);
  if (k >= 0 && s.veh.status[k] == kRunning) {
    const uint32_t rp = s.veh.route_pos[k];
    must_start_at(rp, "is on edge");
    // On a junction's internal lane it is already bound for the next edge of its route.
    if (net_.edge_is_internal[net_.lane_edge[static_cast<uint32_t>(s.veh.lane[k])]] &&
        (edges.size() < 2 || edges[1] != old[rp + 1]))
      refuse("the vehicle is crossing a junction into edge '" + net_.edge_id[old[rp + 1]] +
             "', which must come second");
    trips_.set_route(v, edges);
    sync_trips();
    const std::vector<SlotRoute> routes{
        SlotRoute{static_cast<uint32_t>(k), d.route_begin[v], d.route_length[v], 0}};
    stepper_->set_routes(routes);
    ++version_;
    return;
  }
  // Off the road: waiting to re-enter after a teleport (its old slot may wait one more step to be cleared),
  // or to depart (queued or not yet due). Its queue stays the one of the route's first edge.
  if (ledger_.status(v) == kTeleporting) {
    must_start_at(ledger_.resume_route_pos(v), "re-enters after its teleport at");
    ledger_.set_resume_route_pos(v, 0);
  } else if (ledger_.status(v) == kPending && k < 0) {
    must_start_at(0, "departs from");
  } else {
    refuse("its trip has ended");
  }
  trips_.set_route(v, edges);
}

const LaneCounters& Simulation::collect_lane_counters() {
  if (lane_counters_.sampled_steps.size() != net_.num_lanes())  // all zero: nothing counted
    lane_counters_.resize(net_.num_lanes(), opt_.emission_sums);
  if (parts_ && parts_->plan.part == 0) request(kRequestCounters);
  if (parts_ && parts_->plan.part != 0) {
    gather_counters();
    return lane_counters_;
  }
  if (opt_.lane_counters || opt_.emission_sums) {
    int64_t* columns[kNumLaneCounters];
    for (int k = 0; k < kNumLaneCounters; ++k) {
      std::vector<int64_t>& column = counter_column(lane_counters_, k);
      columns[k] = column.empty() ? nullptr : column.data();
    }
    stepper_->drain_counters(columns);
  }
  if (parts_) gather_counters();
  return lane_counters_;
}

// The counter columns the backend keeps (LaneCounter order): the traffic ones for edgeData/laneData, the
// emission sums for emissions outputs.
std::vector<int> Simulation::kept_counters() const {
  std::vector<int> kept;
  for (int k = 0; k < kNumLaneCounters; ++k)
    if (k < kCountEmissionFirst ? opt_.lane_counters : opt_.emission_sums) kept.push_back(k);
  return kept;
}

const std::vector<uint64_t>& Simulation::active_by_vehicle() const {
  const HostState& s = state(StateParts::Sample);
  // Sorted when an output lists vehicles, once per step that asks: the passes and the summary need no order.
  if (by_vehicle_version_ != version_) {
    by_vehicle_.clear();
    for (uint32_t i = 0; i < s.num_active; ++i) {
      const uint32_t k = s.active[i];
      by_vehicle_.push_back(uint64_t{s.veh.vehicle[k]} << 32 | k);
    }
    std::sort(by_vehicle_.begin(), by_vehicle_.end());
    by_vehicle_version_ = version_;
  }
  return by_vehicle_;
}

void Simulation::sample_fcd(FcdFrame& frame) const {
  frame.time = time();
  frame.vehicle.clear();
  frame.lane.clear();
  frame.pos.clear();
  frame.speed.clear();
  if (parts_) {
    gather_sample();
    for (const SampleEntry& e : parts_->sample) {
      frame.vehicle.push_back(e.vehicle);
      frame.lane.push_back(static_cast<uint32_t>(e.lane));
      frame.pos.push_back(e.pos);
      frame.speed.push_back(e.speed);
    }
    return;
  }
  const HostState& s = state(StateParts::Sample);
  for (const uint64_t key : active_by_vehicle()) {
    const uint32_t v = static_cast<uint32_t>(key >> 32), k = static_cast<uint32_t>(key);
    if (s.veh.status[k] != kRunning) continue;
    frame.vehicle.push_back(v);
    frame.lane.push_back(static_cast<uint32_t>(s.veh.lane[k]));
    frame.pos.push_back(s.veh.pos[k]);
    frame.speed.push_back(s.veh.speed[k]);
  }
}

// The slot of vehicle v while it holds one, else -1. A vehicle that re-entered the road right after a
// teleport holds its old slot for one more step (to clear its footprint) besides the new one; the new one is
// further along the route.
int32_t Simulation::slot_of(uint32_t v) const {
  const HostState& s = state(StateParts::Full);
  const std::vector<uint64_t>& keys = active_by_vehicle();
  int32_t slot = -1;
  for (auto it = std::lower_bound(keys.begin(), keys.end(), uint64_t{v} << 32);
       it != keys.end() && (*it >> 32) == v; ++it) {
    const uint32_t k = static_cast<uint32_t>(*it);
    if (slot < 0 || s.veh.route_pos[k] > s.veh.route_pos[static_cast<uint32_t>(slot)])
      slot = static_cast<int32_t>(k);
  }
  return slot;
}

uint8_t Simulation::status(uint32_t v) const { return on_road(&VehicleView::status, v, ledger_.status(v)); }
int32_t Simulation::lane(uint32_t v) const { return on_road(&VehicleView::lane, v, int32_t{-1}); }
float Simulation::pos(uint32_t v) const { return on_road(&VehicleView::pos, v, 0.0f); }
float Simulation::speed(uint32_t v) const { return on_road(&VehicleView::speed, v, 0.0f); }
uint32_t Simulation::route_pos(uint32_t v) const { return on_road(&VehicleView::route_pos, v, 0u); }
uint8_t Simulation::limit_reason(uint32_t v) const {
  return on_road(&VehicleView::limit_reason, v, uint8_t{0});
}

char Simulation::link_state(uint32_t conn) const {
  const int32_t sig = net_.conn_signal[conn];
  if (sig < 0 || net_.conn_link_index[conn] < 0) return net_.conn_state[conn];
  return state(StateParts::Full)
      .link_state[engine_net_.link_begin[static_cast<size_t>(sig)] +
                  static_cast<uint32_t>(net_.conn_link_index[conn])];
}

const std::vector<uint32_t>& Simulation::active() const {
  active_vehicles_.clear();
  for (const uint64_t key : active_by_vehicle()) active_vehicles_.push_back(static_cast<uint32_t>(key >> 32));
  // A vehicle that teleported and re-entered at once holds its old slot for one more step.
  active_vehicles_.erase(std::unique(active_vehicles_.begin(), active_vehicles_.end()),
                         active_vehicles_.end());
  return active_vehicles_;
}

// Summed in units of 2^-24 (integers: the sums do not depend on the order of the slots, which sort_slots
// changes, nor on how the vehicles are split among the parts of a partitioned run; each term is off by at
// most 3e-8).
SpeedSums Simulation::speed_sums() const {
  SpeedSums sums;
  const Demand& d = trips_.demand();
  const VehicleTypes& t = d.types;
  const HostState& s = state(StateParts::Sample);
  const NetView nv = engine_net_.view(net_);
  for (uint32_t i = 0; i < s.num_active; ++i) {
    const uint32_t k = s.active[i];
    if (s.veh.status[k] != kRunning) continue;
    const uint32_t v = s.veh.vehicle[k];
    const float speed = s.veh.speed[k];
    ++sums.running;
    sums.speed += std::llround(static_cast<double>(speed) * kSummaryUnits);
    const uint32_t type = d.vehicle_type[v];
    const float v0 =
        desired_speed(lane_speed_for(nv, static_cast<uint32_t>(s.veh.lane[k]), t.vclass_mask[type]),
                      d.speed_factor[v], t.max_speed[type], t.desired_max_speed[type]);
    if (v0 > 0) sums.relative += std::llround(static_cast<double>(speed / v0) * kSummaryUnits);
    if (speed < kHaltingSpeed) ++sums.halting;
    if (s.veh.stop_release[k] != 0) ++sums.stopped;  // standing at a scheduled stop
  }
  return sums;
}

std::vector<TripRecord> Simulation::own_unfinished_trips(double end, bool undeparted) const {
  const Demand& d = trips_.demand();
  std::vector<TripRecord> out;
  auto record = [&](uint32_t v, uint8_t kind) -> TripRecord& {
    TripRecord& r = out.emplace_back();
    r.vehicle = v;
    r.unfinished = kind;
    r.speed_factor = d.speed_factor[v];
    const DepartRecord dep = ledger_.departure(v);
    r.depart = kind == kTripRunning ? dep.time : -1.0;
    r.depart_delay = (kind == kTripRunning ? dep.time : end) - d.depart[v];
    r.depart_lane = static_cast<uint32_t>(dep.lane);
    r.depart_pos = dep.pos;
    r.depart_speed = dep.speed;
    r.arrival = end;  // the writer gives duration end - depart and arrival -1
    return r;
  };
  // On the road: its slot holds the counters so far (a vehicle teleported before carries them there).
  const HostState& s = state(StateParts::Columns);
  for (const uint64_t key : active_by_vehicle()) {
    const uint32_t v = static_cast<uint32_t>(key >> 32), k = static_cast<uint32_t>(key);
    if (s.veh.status[k] != kRunning) continue;
    TripRecord& r = record(v, kTripRunning);
    r.route_length = s.veh.route_length[k];
    r.time_loss = s.veh.time_loss[k];
    r.waiting_time = static_cast<double>(s.veh.waiting_steps[k]) * step_length();
    r.waiting_count = s.veh.waiting_count[k];
    r.stop_time = static_cast<double>(s.veh.stop_steps[k]) * step_length();
  }
  // Off the road between a teleport and its re-entry, or never departed.
  for (uint32_t v = 0; v < trips_.size(); ++v) {
    const uint8_t st = ledger_.status(v);
    if (st == kTeleporting) {
      const TripCounters* c = ledger_.carried(v);
      TripRecord& r = record(v, kTripRunning);
      if (c) {
        r.route_length = c->route_length;
        r.time_loss = c->time_loss;
        r.waiting_time = static_cast<double>(c->waiting_steps) * step_length();
        r.waiting_count = c->waiting_count;
        r.stop_time = static_cast<double>(c->stop_steps) * step_length();
      }
    } else if (st == kPending && undeparted && ledger_.departure(v).lane < 0 &&
               seconds_to_ms(d.depart[v]) <= seconds_to_ms(end) && d.route_length[v] > 0) {
      // In a partitioned run the part that owns its first edge reports it (the others never queue it).
      const uint32_t edge = d.route_edges[d.route_begin[v]];
      if (parts_ && parts_->plan.edge_owner[edge] != parts_->plan.part) continue;
      record(v, kTripUndeparted);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const TripRecord& a, const TripRecord& b) { return a.vehicle < b.vehicle; });
  return out;
}

SummaryRow Simulation::summary_row() const {
  SummaryRow r;
  const Counts& c = counts();
  r.time = time();
  r.loaded = c.loaded;
  r.inserted = c.inserted;
  r.running = c.running;
  r.waiting = c.waiting;
  r.arrived = c.arrived;
  r.ended = c.arrived + c.discarded;
  r.teleports = c.teleports;
  const SpeedSums sums = parts_ ? gather_speed_sums() : speed_sums();
  const uint64_t running = sums.running;
  const int64_t speed_sum = sums.speed, rel_sum = sums.relative;
  const uint64_t halting = sums.halting, stopped = sums.stopped;
  r.halting = halting;
  r.stopped = stopped;
  if (running > 0) {
    r.mean_speed = static_cast<double>(speed_sum) / kSummaryUnits / static_cast<double>(running);
    r.mean_speed_relative = static_cast<double>(rel_sum) / kSummaryUnits / static_cast<double>(running);
  }
  // As SUMO: meanWaitingTime is the mean insertion delay of the vehicles inserted so far, meanTravelTime
  // the mean trip duration of the vehicles that arrived so far.
  const double delay_sum = parts_ ? parts_->depart_delay_sum : ledger_.depart_delay_sum();
  const double travel_sum = parts_ ? parts_->travel_time_sum : ledger_.travel_time_sum();
  if (c.inserted > 0) r.mean_waiting_time = delay_sum / static_cast<double>(c.inserted);
  if (c.arrived > 0) r.mean_travel_time = travel_sum / static_cast<double>(c.arrived);
  return r;
}

std::string Simulation::check_lane_map() const {
  const HostState& s = state(StateParts::Full);
  const Demand& d = trips_.demand();
  std::vector<int64_t> owner(net_.num_cells(), -1);
  const NetView nv = engine_net_.view(net_);
  std::vector<uint8_t> expect(net_.num_cells(), 0);
  for (const uint64_t key : active_by_vehicle()) {
    const uint32_t v = static_cast<uint32_t>(key >> 32), k = static_cast<uint32_t>(key);
    if (s.veh.status[k] != kRunning) continue;
    const Footprint fp{s.veh.lane[k], s.veh.prev[k], s.veh.prev2[k], s.veh.pos[k]};
    std::vector<uint8_t> mark(net_.num_cells(), 0);
    apply_footprint(mark.data(), nv, fp, d.types.length[d.vehicle_type[v]], 1);
    for (uint64_t c = 0; c < mark.size(); ++c) {
      if (!mark[c]) continue;
      if (owner[c] >= 0)
        return "vehicles " + d.vehicle_id[static_cast<size_t>(owner[c])] + " and " + d.vehicle_id[v] +
               " share cell " + std::to_string(c) + " at t=" + std::to_string(time());
      owner[c] = v;
      expect[c] = 1;
    }
  }
  // Cells written from outside (a co-simulation's mirrored vehicles, handed-out vehicles' last footprints).
  for (const FootprintWrite& w : outside_footprints_[cur_])
    apply_footprint(expect.data(), nv, w.fp, w.length, 1);
  for (uint64_t c = 0; c < net_.num_cells(); ++c)
    if ((s.map[c] != 0) != (expect[c] != 0))
      return "lane map cell " + std::to_string(c) +
             (s.map[c] ? " marked but no vehicle there" : " unmarked under a vehicle") +
             " at t=" + std::to_string(time());
  return "";
}

}  // namespace lpsim

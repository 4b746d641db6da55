#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/time_range.hpp"
#include "demand/trip_routes.hpp"
#include "engine/outside_link.hpp"
#include "engine/part_link.hpp"
#include "engine/saved_state.hpp"
#include "engine/state_archive.hpp"
#include "engine/state_recut.hpp"
#include "kernels/idm.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/vehicle_step.hpp"
#include "transport/byte_buffer.hpp"

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

// The stops' times as the step counts them: steps stood at least, and the step from which `until` lets a
// vehicle leave: the one that ends at `until` (counted from the begin time; 0: none, or already past).
StopSteps stop_steps_from_times(const StopTable& st, int64_t step_ms, int64_t begin_ms) {
  StopSteps steps;
  steps.duration.resize(st.size());
  steps.until.resize(st.size());
  const double cap = static_cast<double>(std::numeric_limits<uint32_t>::max() / 2);
  for (uint32_t k = 0; k < st.size(); ++k) {
    const double duration = std::ceil(std::llround(st.duration[k] * 1000.0) / static_cast<double>(step_ms));
    steps.duration[k] = static_cast<uint32_t>(std::min(duration, cap));
    const double until = st.until[k] < 0
                             ? 0.0
                             : std::ceil(static_cast<double>(std::llround(st.until[k] * 1000.0) - begin_ms) /
                                         static_cast<double>(step_ms)) -
                                   1.0;
    steps.until[k] = static_cast<uint32_t>(std::clamp(until, 0.0, cap));
  }
  return steps;
}

// Named field by field: the views' columns are the demand's and the stop table's under other names.
TripTableView trip_table_view(const Demand& d, const StopSteps& stop_steps) {
  TripTableView v;
  const StopTable& st = d.stops;
  v.trips = TripView{.type = d.vehicle_type.data(),
                     .route_begin = d.route_begin.data(),
                     .route_length = d.route_length.data(),
                     .route_edges = d.route_edges.data(),
                     .speed_factor = d.speed_factor.data(),
                     .arrival_pos_kind = d.arrival_pos_kind.data(),
                     .arrival_pos = d.arrival_pos.data(),
                     .stop_route_pos = st.route_pos.data(),
                     .stop_lane = st.lane.data(),
                     .stop_start = st.start_pos.data(),
                     .stop_end = st.end_pos.data(),
                     .stop_duration_steps = stop_steps.duration.data(),
                     .stop_until_step = stop_steps.until.data()};
  v.num_stops = st.size();
  v.depart = DepartView{.lane_kind = d.depart_lane_kind.data(),
                        .lane = d.depart_lane.data(),
                        .pos_kind = d.depart_pos_kind.data(),
                        .pos = d.depart_pos.data(),
                        .speed_kind = d.depart_speed_kind.data(),
                        .speed = d.depart_speed.data()};
  v.num_vehicles = d.size();
  v.num_route_edges = d.route_edges.size();
  return v;
}

std::unique_ptr<BoundaryLink> make_link(const LinkScope& scope, const SimulationOptions& opt,
                                        double step_length) {
  if (opt.part) return std::make_unique<PartLink>(scope, *opt.part, *opt.transport, opt.pending_signal);
  if (opt.outside_lanes) return std::make_unique<OutsideLink>(scope, *opt.outside_lanes, step_length);
  return std::make_unique<BoundaryLink>(scope);
}

// Exactly the slots whose vehicles left the road in the previous step drop out of the active list
// (stays_active): anything else would free a slot still in use, or never free one.
void check_kept(const HostBooks& books, uint32_t kept) {
  if (kept + books.retiring.size() != books.num_active)
    throw std::logic_error("step kept " + std::to_string(kept) + " of " + std::to_string(books.num_active) +
                           " active slots, " + std::to_string(books.retiring.size()) + " were to leave");
}

// The counter columns the backend keeps (LaneCounter order): the traffic ones for edgeData/laneData, the
// emission sums for emissions outputs.
std::vector<int> kept_counters(const SimulationOptions& opt) {
  std::vector<int> kept;
  for (int k = 0; k < kNumLaneCounters; ++k)
    if (k < kCountEmissionFirst ? opt.lane_counters : opt.emission_sums) kept.push_back(k);
  return kept;
}

// The lane counters counted since the last request, from every part to part 0, which adds them to its own.
// Only the columns every part keeps travel (the parts run with the same options).
void gather_counters(BoundaryLink& link, Stepper& stepper, const std::vector<int>& kept, uint32_t num_lanes,
                     LaneCounters& counters) {
  std::vector<uint32_t> lanes;
  std::vector<int64_t> values;
  if (!link.leads() && !kept.empty()) {
    std::vector<int64_t> all(static_cast<size_t>(kNumLaneCounters) * num_lanes, 0);
    int64_t* columns[kNumLaneCounters];
    for (int k = 0; k < kNumLaneCounters; ++k) columns[k] = all.data() + static_cast<size_t>(k) * num_lanes;
    stepper.drain_counters(columns);
    for (uint32_t l = 0; l < num_lanes; ++l) {
      bool any = false;
      for (const int k : kept) any = any || columns[k][l] != 0;
      if (!any) continue;
      lanes.push_back(l);
      for (const int k : kept) values.push_back(columns[k][l]);
    }
  }
  Bytes b;
  ByteWriter w(b);
  w.put_array(lanes);
  w.put_array(values);
  const std::vector<Bytes> all = link.gather(b, "counters");
  for (size_t i = 1; i < all.size(); ++i) {
    ByteReader r(all[i]);
    const std::vector<uint32_t> l = r.get_array<uint32_t>();
    const std::vector<int64_t> v = r.get_array<int64_t>();
    for (size_t j = 0; j < l.size(); ++j)
      for (size_t c = 0; c < kept.size(); ++c)
        counter_column(counters, kept[c])[l[j]] += v[j * kept.size() + c];
  }
}

}  // namespace

Simulation::Simulation(const Network& net, Demand demand, const SimulationOptions& options)
    : net_(net), trips_(std::move(demand)), opt_(options), engine_net_(net, options.part), books_(net) {
  if (opt_.step_ms <= 0) throw std::invalid_argument("step length must be a positive number of milliseconds");
  const Demand& d = trips_.demand();
  if (d.size() >= kMaxVehicles)
    throw std::invalid_argument("too many vehicles: " + std::to_string(d.size()) + " (at most " +
                                std::to_string(kMaxVehicles - 1) + ")");
  time_ms_ = std::llround(opt_.begin * 1000.0);
  DepartureSchedule& due = books_.schedule;
  due.loaded = d.size();
  books_.counts.loaded = due.loaded;
  books_.ledger.resize(due.loaded);
  // kNumLaneCounters columns over every lane: kept only for edgeData/laneData (collect_lane_counters() sizes
  // them when asked without), the emission sums only for emissions outputs.
  if (opt_.lane_counters || opt_.emission_sums) lane_counters_.resize(net.num_lanes(), opt_.emission_sums);

  const VehicleTypes& t = d.types;
  const float dt = static_cast<float>(opt_.step_ms) / 1000.0f;
  params_.dt = dt;
  params_.seed = opt_.seed;
  params_.substeps = idm_default_substeps(dt);
  params_.max_accel = 2.6f;
  params_.max_emergency_decel = 9.0f;
  for (uint32_t k = 0; k < t.size(); ++k) {
    params_.max_accel = std::max(params_.max_accel, t.accel[k]);
    params_.max_emergency_decel = std::max(params_.max_emergency_decel, t.emergency_decel[k]);
  }
  // Vehicles that depart before the begin time are not simulated (as SUMO, which skips them).
  while (due.next < due.loaded && seconds_to_ms(d.depart[due.next]) < time_ms_) {
    books_.ledger.set_status(due.next, kArrived);
    ++books_.counts.removed;
    ++due.next;
  }
  params_.teleport_steps = stopped_steps_for(opt_.time_to_teleport, step_length());
  params_.highway_teleport_steps = stopped_steps_for(opt_.time_to_teleport_highways, step_length());
  params_.impatience_steps = stopped_steps_for(opt_.time_to_impatience, step_length());
  // 0 s ignores every vehicle on a junction lane, standing or not, as in SUMO.
  params_.ignore_blocker_steps = stopped_steps_for(opt_.ignore_junction_blocker, step_length());
  params_.highway_min_speed = static_cast<float>(opt_.highway_min_speed);
  stop_steps_ = stop_steps_from_times(d.stops, opt_.step_ms, time_ms_);

  if ((opt_.part == nullptr) != (opt_.transport == nullptr))
    throw std::invalid_argument("a part of a partitioned run needs both its plan and its transport");
  if (opt_.outside_lanes && opt_.part)
    throw std::invalid_argument("lanes driven by another simulator need a run of one part");

  StepperSetup setup;
  setup.net = engine_net_.view(net_);
  setup.signals = engine_net_.signal_table(net_);
  visit_type_columns([](auto*& view, const auto& column) { view = column.data(); }, setup.types, t);
  setup.num_types = t.size();
  setup.num_edges = net.num_edges();
  setup.num_connections = net.num_connections();
  setup.yielder_begin = engine_net_.yielder_begin.data();
  setup.yielder = engine_net_.yielder.data();
  setup.trips = trip_table_view(d, stop_steps_);
  setup.lane_counters = opt_.lane_counters;
  setup.junction_stands = opt_.ignore_junction_blocker >= 0;
  setup.emission_sums = opt_.emission_sums;
  fuel_divisor_.resize(t.size());
  for (uint32_t k = 0; k < t.size(); ++k)
    fuel_divisor_[k] = opt_.volumetric_fuel ? kHbefaScale * t.fuel_density[k] : kHbefaScale;
  setup.emission_types = EmissionView{.model = t.emission_model.data(),
                                      .coeff = t.emission_coeff.data(),
                                      .coast_incl = t.coast_incl.data(),
                                      .coast_mass_term = t.coast_mass_term.data(),
                                      .fuel_divisor = fuel_divisor_.data(),
                                      .shut_off_stop = t.shut_off_stop.data(),
                                      .sums = nullptr,
                                      .num_lanes = net.num_lanes()};
  setup.threads = opt_.threads;
  setup.device = opt_.gpu_device;
  stepper_ = opt_.backend(setup);
  const LinkScope scope{net_, engine_net_, trips_, *stepper_, books_};
  link_ = make_link(scope, opt_, step_length());
  InsertionRules rules;
  rules.seed = opt_.seed;
  rules.step_ms = opt_.step_ms;
  rules.max_depart_delay = opt_.max_depart_delay;
  rules.max_emergency_decel = params_.max_emergency_decel;
  for (uint32_t k = 0; k < t.size(); ++k) rules.min_decel = std::min(rules.min_decel, t.decel[k]);
  insertion_ = std::make_unique<InsertionControl>(scope, *link_, rules);

  if (!d.rerouting.empty())
    reroute_ = std::make_unique<ReroutingDevice>(net_, opt_.rerouting, opt_.seed, opt_.threads, time_ms_,
                                                 opt_.step_ms, d.size(), due.next);
  // The state at the begin time: its signals and its first insertions.
  const RerouteScope reroute_scope{net_, d, books_, *link_};
  stepper_->update_signals(time_ms_, time_ms_, cur_);
  link_->after_signals();
  if (reroute_) apply_new_routes(reroute_->reroute(time_ms_, reroute_scope, [this] { return query(); }));
  sync_trips();
  insertion_->enqueue_due(time_ms_);
  insertion_->insert(cur_, time_ms_, step_);
  link_->after_insertion(cur_);
  check_kept(books_, 0);
  insertion_->start(0, 0);
  ++version_;  // the insertions changed the state (the rerouting device may have read it before them)
  if (reroute_ && reroute_->sample_due(time_ms_))
    reroute_->sample_speeds(reroute_scope, state(StateParts::Columns));
  link_->report();
}

// Part 0 of a partitioned run ends the other parts' serve_part().
Simulation::~Simulation() {
  try {
    link_->request(kRequestStop);
  } catch (const std::exception&) {
    // A part that failed has ended its serve_part() already; its error was reported where it failed.
  }
}

OutsideLink& Simulation::outside_link() {
  auto* outside = dynamic_cast<OutsideLink*>(link_.get());
  if (!outside) throw std::logic_error("a run without lanes driven by another simulator has no outside link");
  return *outside;
}

// One part of a partitioned run other than part 0: it does what part 0 asks until part 0 ends the run.
void Simulation::serve_part() {
  for (;;) {
    switch (link_->next_request()) {
      case kRequestStep:
        step();
        break;
      case kRequestSample:
        link_->running_vehicles(version_);
        break;
      case kRequestCounters:
        collect_lane_counters();
        break;
      case kRequestSpeedSums:
        speed_sums();
        break;
      case kRequestUnfinished:
        unfinished_trips(0, false);  // the arguments come from part 0
        break;
      case kRequestSaveState:
        save_state();
        break;
      case kRequestCommands:
        apply_commands({});  // part 0's, handed over
        break;
      case kRequestLoadState:
        load_state({}, "part " + std::to_string(opt_.part->part) + "'s state");
        break;
      case kRequestStop:
        return;
    }
  }
}

bool Simulation::finished() const { return link_->idle() && books_.schedule.empty(); }

// The backend reads the trip table through its own pointers (or its own copy, on a device): after the table
// grew or a route changed, it is handed the table as it lies now and what changed.
void Simulation::sync_trips() {
  if (!trips_.changed()) return;
  TripTable::Changes c = trips_.take_changes();
  TripChanges changes{c.first_new_vehicle, c.first_new_route_edge, std::move(c.new_routes), c.stops_moved};
  stepper_->update_trips(trip_table_view(trips_.demand(), stop_steps_), changes);
}

void Simulation::step() {
  const auto t0 = std::chrono::steady_clock::now();
  link_->begin_step();
  const RerouteScope reroute_scope{net_, trips_.demand(), books_, *link_};
  if (reroute_)
    apply_new_routes(reroute_->reroute(time_ms_ + opt_.step_ms, reroute_scope, [this] { return query(); }));
  sync_trips();
  ++version_;
  Stepper& s = *stepper_;
  StepParams params = params_;
  params.step = step_;
  params.signal_time_ms = time_ms_ + opt_.step_ms;
  s.update_signals(params.signal_time_ms, time_ms_, cur_);
  link_->after_signals();
  s.start_step(params, cur_);
  s.clear_footprints();
  link_->before_writing(1 - cur_);
  s.approach();
  link_->after_approach(step_, cur_);
  s.plan();
  link_->after_plan(step_);
  s.commit();
  if (opt_.emission_sums) s.count_emissions();
  s.start_end_of_step(step_ + 1);
  // While a device runs the passes: the departures due by the end of the step join their queues. Nothing
  // there depends on the step's outcome, and the order does not matter: a vehicle teleported in the step
  // joins its queue at the head (handle_vehicle_ends), a departure at the tail.
  insertion_->enqueue_due(time_ms_ + opt_.step_ms);
  StepOutcome& out = s.finish_end_of_step();
  check_kept(books_, out.kept);
  // The vehicles the step moved: not the slots of those that left the road in the step before (they only
  // cleared their footprint), so a vehicle that drives into another part counts once.
  books_.counts.vehicle_updates += out.kept;

  time_ms_ += opt_.step_ms;
  ++step_;
  handle_vehicle_ends(out.ends);
  if (!moves_.empty()) s.apply_teleports(moves_, step_);
  link_->after_end_of_step(1 - cur_);
  insertion_->insert(1 - cur_, time_ms_, step_);
  link_->after_insertion(1 - cur_);
  cur_ = 1 - cur_;
  insertion_->start(out.kept, out.running);
  if (reroute_ && reroute_->sample_due(time_ms_))
    reroute_->sample_speeds(reroute_scope, state(StateParts::Columns));
  link_->count_step(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  link_->report();
  if (opt_.slot_sort_interval > 0 && step_ % opt_.slot_sort_interval == 0) sort_slots();
  step_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Arrivals become trip records; teleporting vehicles re-enter at the next edge of their route (moves_ says
// which, for the backend to apply). Handled in vehicle order (the passes find them in slot order); their
// slots are free once the next step has cleared their footprint.
void Simulation::handle_vehicle_ends(std::vector<VehicleEnd>& ends) {
  std::sort(ends.begin(), ends.end(),
            [](const VehicleEnd& a, const VehicleEnd& b) { return a.vehicle < b.vehicle; });
  const Demand& d = trips_.demand();
  TripLedger& ledger = books_.ledger;
  moves_.clear();
  books_.teleport_events.clear();
  for (const VehicleEnd& e : ends) {
    const uint32_t v = e.vehicle;
    books_.retiring_next.push_back(e.slot);
    if (e.kind == kEndArrived) {
      ++books_.counts.arrived;
      ledger.ended(e, false, time(), d.depart[v], step_length(), d.speed_factor[v]);
      continue;
    }
    ++books_.counts.teleports;
    const TeleportCause cause = teleport_cause(e.limit_reason);
    // The wrong-lane rule of a fast road's lane clocks out first where its time is the shorter.
    const bool highway =
        cause == TeleportCause::WrongLane && params_.highway_teleport_steps > 0 &&
        (params_.teleport_steps == 0 || params_.highway_teleport_steps < params_.teleport_steps) &&
        net_.lane_speed[static_cast<uint32_t>(e.lane)] > static_cast<float>(opt_.highway_min_speed);
    books_.teleport_events.push_back(TeleportEvent{v, static_cast<uint32_t>(e.lane), cause, highway});
    if (e.route_pos + 1 >= d.route_length[v]) {
      // Teleported past the end of its route: the trip ends here.
      moves_.push_back(TeleportMove{v, e.slot, 1});
      ++books_.counts.arrived;
      ledger.ended(e, true, time(), d.depart[v], step_length(), d.speed_factor[v]);
      continue;
    }
    moves_.push_back(TeleportMove{v, e.slot, 0});
    const uint32_t edge = d.route_edges[d.route_begin[v] + e.route_pos + 1];
    if (link_->takes_reentry(e, e.route_pos + 1, edge)) continue;
    ledger.teleporting(e, e.route_pos + 1);
    books_.queues.push_front(edge, queue_entry(v, true));
  }
}

// Renumbers the slots of the vehicles on the road densely from 0 in the order of their lanes (ties: the old
// slot), so that a pass meets the vehicles of one lane, and of neighbouring lanes, one after the other: their
// lane-map cells and lane columns are then read together instead of scattered over the network. Runs between
// steps, when the slots in use are exactly the active list. Nothing depends on a vehicle's slot number
// (claims break ties by vehicle, random draws are keyed by vehicle, ends are handled in vehicle order, a
// vehicle's slot is looked up in the active list), so results are unchanged. The host keeps only the slots
// due to leave (HostBooks::retiring), which are renumbered with the rest.
void Simulation::sort_slots() {
  stepper_->sort_slots(books_.retiring);
  for (const uint32_t k : books_.retiring)
    if (k == kNotActive) throw std::logic_error("a slot due to leave was not in the active list");
  books_.slots.reset(books_.num_active);
}

// Part 0 hands its commands to the other parts; each command is checked in every part, and applied once
// the parts' verdicts say it can act (vehicle_commands.hpp).
std::vector<CommandOutcome> Simulation::apply_commands(const std::vector<VehicleCommand>& given) {
  link_->request(kRequestCommands);
  const std::vector<VehicleCommand> commands =
      link_->parts() > 1 ? commands_from_bytes(link_->broadcast(command_bytes(given), "commands")) : given;
  const CommandScope scope{
      net_, trips_, books_, *stepper_, *link_, cur_, time(), step_length(), [this] { sync_trips(); }};
  // One fetch of the vehicles' state for the whole batch (the applier keeps what its commands change).
  const VehicleQuery now = query();
  CommandApplier applier(scope, now);
  std::vector<CommandOutcome> outcomes;
  for (const VehicleCommand& c : commands) {
    CommandOutcome o;
    if (c.kind == VehicleCommand::Kind::Add) {
      try {
        o.vehicle = trips_.add(c.trip, net_);
      } catch (const std::invalid_argument& e) {
        o.error = e.what();
      }
      if (o.done()) {
        books_.ledger.resize(trips_.size());
        ++books_.counts.loaded;
        // Soonest last; among trips due at once, the lowest index last.
        const std::pair<int64_t, uint32_t> due{seconds_to_ms(c.trip.depart), o.vehicle};
        std::vector<std::pair<int64_t, uint32_t>>& added = books_.schedule.added;
        added.insert(std::upper_bound(added.begin(), added.end(), due, std::greater<>()), due);
      }
      outcomes.push_back(std::move(o));
      continue;
    }
    const std::vector<Bytes> verdicts = link_->allgather(applier.verdict(c), "command verdicts");
    o = CommandApplier::combine_verdicts(c, verdicts, trips_.demand());
    if (o.done()) applier.apply(c, verdicts);
    outcomes.push_back(std::move(o));
  }
  ++version_;  // the state changed (the next query fetches it again)
  return outcomes;
}

void Simulation::apply_new_routes(const std::vector<NewRoute>& routes) {
  const Demand& d = trips_.demand();
  std::vector<std::pair<uint32_t, uint32_t>> running;  // (slot, vehicle)
  std::optional<VehicleQuery> on_road;                 // read once a route changes
  for (const NewRoute& n : routes) {
    if (n.edges.empty()) continue;
    if (d.stops.first(n.vehicle) != d.stops.last(n.vehicle)) {
      // Routed through its stops' edges, so each is on it; placed along it before it departs.
      const std::vector<uint32_t> at = stop_positions(d, net_, n.vehicle, n.edges);
      if (at.empty()) continue;
      trips_.set_stop_positions(n.vehicle, at);
    }
    trips_.set_route(n.vehicle, n.edges);
    if (!on_road) on_road.emplace(query());
    if (const int32_t k = on_road->slot(n.vehicle); k >= 0)
      running.emplace_back(static_cast<uint32_t>(k), n.vehicle);
  }
  if (running.empty()) return;
  sync_trips();
  std::vector<SlotRoute> slots;
  for (const auto& [k, v] : running) slots.push_back(SlotRoute{k, d.route_begin[v], d.route_length[v], 0});
  stepper_->set_routes(slots);
  ++version_;
}

const LaneCounters& Simulation::collect_lane_counters() {
  if (lane_counters_.sampled_steps.size() != net_.num_lanes())  // all zero: nothing counted
    lane_counters_.resize(net_.num_lanes(), opt_.emission_sums);
  link_->request(kRequestCounters);
  if (link_->leads() && (opt_.lane_counters || opt_.emission_sums)) {
    int64_t* columns[kNumLaneCounters];
    for (int k = 0; k < kNumLaneCounters; ++k) {
      std::vector<int64_t>& column = counter_column(lane_counters_, k);
      columns[k] = column.empty() ? nullptr : column.data();
    }
    stepper_->drain_counters(columns);
  }
  if (link_->parts() > 1)
    gather_counters(*link_, *stepper_, kept_counters(opt_), net_.num_lanes(), lane_counters_);
  return lane_counters_;
}

const std::vector<uint64_t>& Simulation::active_by_vehicle() const {
  const HostState& s = state(StateParts::Sample);
  // Sorted when an output lists vehicles, once per step that asks: the passes and the summary need no order.
  ActiveOrder& o = active_order_;
  if (o.version != version_) {
    o.keys.clear();
    for (uint32_t i = 0; i < s.num_active; ++i) {
      const uint32_t k = s.active[i];
      o.keys.push_back(uint64_t{s.veh.vehicle[k]} << 32 | k);
    }
    std::sort(o.keys.begin(), o.keys.end());
    o.version = version_;
  }
  return o.keys;
}

void Simulation::sample_fcd(FcdFrame& frame) {
  frame.time = time();
  frame.vehicle.clear();
  frame.lane.clear();
  frame.pos.clear();
  frame.speed.clear();
  if (link_->parts() > 1) {
    for (const SampleEntry& e : link_->running_vehicles(version_)) {
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

VehicleQuery Simulation::query(StateParts parts) const {
  const std::vector<uint64_t>& by_vehicle = active_by_vehicle();
  return VehicleQuery(state(parts), parts, by_vehicle, books_.ledger, net_, engine_net_);
}

const std::vector<uint32_t>& Simulation::active() const {
  std::vector<uint32_t>& vehicles = active_order_.vehicles;
  vehicles.clear();
  for (const uint64_t key : active_by_vehicle()) vehicles.push_back(static_cast<uint32_t>(key >> 32));
  // A vehicle that teleported and re-entered at once holds its old slot for one more step.
  vehicles.erase(std::unique(vehicles.begin(), vehicles.end()), vehicles.end());
  return vehicles;
}

// Summed in units of 2^-24 (integers: the sums do not depend on the order of the slots, which sort_slots
// changes, nor on how the vehicles are split among the parts of a partitioned run; each term is off by at
// most 3e-8). In a partitioned run part 0 adds every part's (integers: exact in any order).
SpeedSums Simulation::speed_sums() {
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
  if (link_->parts() == 1) return sums;
  link_->request(kRequestSpeedSums);
  Bytes b;
  ByteWriter(b).put(sums);
  SpeedSums total;
  for (const Bytes& x : link_->gather(b, "speed sums")) {
    const SpeedSums part = ByteReader(x).get<SpeedSums>();
    total.running += part.running;
    total.halting += part.halting;
    total.stopped += part.stopped;
    total.speed += part.speed;
    total.relative += part.relative;
  }
  return total;
}

std::vector<TripRecord> Simulation::own_unfinished_trips(double end, bool undeparted) const {
  const Demand& d = trips_.demand();
  std::vector<TripRecord> out;
  auto record = [&](uint32_t v, uint8_t kind) -> TripRecord& {
    TripRecord& r = out.emplace_back();
    r.vehicle = v;
    r.unfinished = kind;
    r.speed_factor = d.speed_factor[v];
    const DepartRecord dep = books_.ledger.departure(v);
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
    const uint8_t st = books_.ledger.status(v);
    if (st == kTeleporting) {
      const TripCounters* c = books_.ledger.carried(v);
      TripRecord& r = record(v, kTripRunning);
      if (c) {
        r.route_length = c->route_length;
        r.time_loss = c->time_loss;
        r.waiting_time = static_cast<double>(c->waiting_steps) * step_length();
        r.waiting_count = c->waiting_count;
        r.stop_time = static_cast<double>(c->stop_steps) * step_length();
      }
    } else if (st == kPending && undeparted && books_.ledger.departure(v).lane < 0 &&
               seconds_to_ms(d.depart[v]) <= seconds_to_ms(end) && d.route_length[v] > 0) {
      // In a partitioned run the part that owns its first edge reports it (the others never queue it).
      const uint32_t edge = d.route_edges[d.route_begin[v]];
      if (!link_->owns_edge(edge)) continue;
      record(v, kTripUndeparted);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const TripRecord& a, const TripRecord& b) { return a.vehicle < b.vehicle; });
  return out;
}

SummaryRow Simulation::summary_row() {
  SummaryRow r;
  const Counts& c = counts();
  r.time = time();
  r.loaded = c.loaded;
  r.inserted = c.inserted;
  r.running = c.running;
  r.waiting = c.waiting;
  r.arrived = c.arrived;
  r.ended = c.arrived + c.discarded + c.cancelled;
  r.teleports = c.teleports;
  const SpeedSums sums = speed_sums();
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
  const double delay_sum = link_->depart_delay_sum();
  const double travel_sum = link_->travel_time_sum();
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
    const Footprint fp = current_footprint(s.veh, k);
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
  for (const FootprintWrite& w : link_->foreign_footprints(cur_))
    apply_footprint(expect.data(), nv, w.fp, w.length, 1);
  for (uint64_t c = 0; c < net_.num_cells(); ++c)
    if ((s.map[c] != 0) != (expect[c] != 0))
      return "lane map cell " + std::to_string(c) +
             (s.map[c] ? " marked but no vehicle there" : " unmarked under a vehicle") +
             " at t=" + std::to_string(time());
  return "";
}

// Part 0 sends `end` and `undeparted` with the gather's request; every part answers with its own records.
std::vector<TripRecord> Simulation::unfinished_trips(double end, bool undeparted) {
  if (link_->parts() == 1) return own_unfinished_trips(end, undeparted);
  link_->request(kRequestUnfinished);
  Bytes args;
  ByteWriter w(args);
  w.put(end);
  w.put(static_cast<uint8_t>(undeparted ? 1 : 0));
  const Bytes root = link_->broadcast(args, "unfinished arguments");
  ByteReader r(root);
  end = r.get<double>();
  undeparted = r.get<uint8_t>() != 0;
  Bytes b;
  ByteWriter(b).put_array(own_unfinished_trips(end, undeparted));
  std::vector<TripRecord> all;
  for (const Bytes& x : link_->gather(b, "unfinished"))
    for (const TripRecord& t : ByteReader(x).get_array<TripRecord>()) all.push_back(t);
  std::sort(all.begin(), all.end(),
            [](const TripRecord& a, const TripRecord& b) { return a.vehicle < b.vehicle; });
  return all;
}

const Simulation::Counts& Simulation::counts() const { return link_->counts(); }

std::vector<TripRecord> Simulation::take_finished_trips() { return link_->take_finished(); }

const std::vector<TeleportEvent>& Simulation::teleport_events() const { return link_->teleport_events(); }

// What a step reads that an earlier one wrote: the clock, and as sections of their own (SavedPartState) the
// books, the routes as rerouting left them, the lane counters drained so far, the rerouting device, what the
// boundary link carries, and the backend's own state.
template <class A>
void Simulation::visit_state(A& a, std::vector<uint8_t>& backend) {
  if (opt_.outside_lanes) throw std::runtime_error("a co-simulation has no saved state yet");
  SavedPartState saved;
  if constexpr (A::kReads) {
    a(saved);
    time_ms_ = saved.time_ms;
    step_ = saved.step;
    cur_ = saved.map;
    if (cur_ != 0 && cur_ != 1) a.fail("no lane map " + std::to_string(cur_));
  } else {
    saved.time_ms = time_ms_;
    saved.step = step_;
    saved.map = cur_;
  }
  // f(archive) on section k: writing it, or reading it whole.
  auto section = [&](StateSection k, auto&& f) {
    std::vector<uint8_t>& bytes = saved.sections[k];
    if constexpr (A::kReads) {
      StateIn in(bytes.data(), bytes.size(), a.what());
      f(in);
      if (!in.done()) in.fail("bytes left after a section's last field");
    } else {
      StateOut out;
      f(out);
      bytes = std::move(out.bytes());
    }
  };
  section(kSectionBooks, [&](auto& s) { s(books_); });
  section(kSectionRoutes, [&](auto& s) { trips_.visit_routes(s); });
  section(kSectionLaneCounters, [&](auto& s) { s(lane_counters_); });
  section(kSectionRerouting, [&](auto& s) {
    uint8_t rerouting = reroute_ ? 1 : 0;
    s(rerouting);
    if (rerouting != (reroute_ ? 1 : 0)) s.fail("the state's rerouting device does not match this run's");
    if (reroute_) s(*reroute_);
  });
  section(kSectionLink, [&](auto& s) {
    if constexpr (A::kReads)
      link_->load_state(s, cur_);
    else
      link_->save_state(s, cur_);
  });
  if constexpr (A::kReads) {
    backend = std::move(saved.sections[kSectionBackend]);
  } else {
    saved.sections[kSectionBackend] = std::move(backend);
    a(saved);
  }
}

// The parts' partition, then every part's own state in part order (part 0 gathers them).
std::vector<uint8_t> Simulation::save_state() {
  link_->request(kRequestSaveState);
  std::vector<uint8_t> backend = stepper_->save_state(books_.slots.size());
  StateOut own;
  visit_state(own, backend);
  SavedState saved;
  saved.parts = link_->gather(own.bytes(), "state");
  if (saved.parts.empty()) return {};
  if (opt_.part != nullptr) saved.edge_part = opt_.part->edge_owner;
  StateOut a;
  a(saved);
  return std::move(a.bytes());
}

void Simulation::load_state(const std::vector<uint8_t>& state, const std::string& what) {
  std::vector<Bytes> each;
  if (link_->leads()) {
    StateIn a(state.data(), state.size(), what);
    SavedState saved;
    a(saved);
    if (!a.done()) a.fail("bytes left after the last part's state");
    // Saved in other parts, or in another partition: re-cut for these.
    const auto here = static_cast<int32_t>(link_->parts());
    const bool same_parts = saved.parts.size() == static_cast<size_t>(here) &&
                            (opt_.part ? saved.edge_part == opt_.part->edge_owner : saved.edge_part.empty());
    if (!same_parts) {
      const Demand& d = trips_.demand();
      double longest = 0;
      for (const float l : d.types.length) longest = std::max(longest, static_cast<double>(l));
      std::vector<PartPlan> plans;
      if (opt_.part) plans = part_plans(net_, opt_.part->edge_owner, here, longest);
      try {
        saved = recut_state(saved, RecutScope{net_, d, longest}, plans);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(
            "saved by a run of " + std::to_string(saved.parts.size()) + " part" +
            (saved.parts.size() == 1 ? "" : "s") +
            (saved.parts.size() == static_cast<size_t>(here) ? " in another partition" : "") +
            ", resumed in " + std::to_string(here) + ": " + e.what());
      }
    }
    each = std::move(saved.parts);
    link_->request(kRequestLoadState);
  }
  const Bytes mine = link_->scatter(each, "state");
  StateIn a(mine.data(), mine.size(), what);
  std::vector<uint8_t> backend;
  visit_state(a, backend);
  if (!a.done()) a.fail("bytes left after the state's last field");
  sync_trips();  // the routes as the state has them
  try {
    stepper_->load_state(backend, books_.slots.size());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  moves_.clear();
  ++version_;
}

}  // namespace lpsim

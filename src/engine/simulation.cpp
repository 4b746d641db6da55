#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/pass_prefetch.hpp"
#include "kernels/gpu_stepper.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

namespace {

template <class T>
T* ptr(std::vector<T>& v) {
  return v.data();
}

// The summary's speed sums count in units of 2^-24 m/s (and of 2^-24 of the desired speed).
constexpr double kSummaryUnits = 16777216.0;

// Fewer active vehicles than this run the passes on the calling thread.
constexpr int64_t kParallelMinVehicles = 2048;

// kernels/insert_vehicle.hpp reads the demand's depart kinds as plain bytes.
static_assert(kDepartLaneGiven == uint8_t(DepartLane::Given) &&
              kDepartLaneRandom == uint8_t(DepartLane::Random) &&
              kDepartLaneFree == uint8_t(DepartLane::Free) && kDepartLaneBest == uint8_t(DepartLane::Best));
static_assert(kDepartPosGiven == uint8_t(DepartPos::Given) &&
              kDepartPosRandom == uint8_t(DepartPos::Random) &&
              kDepartPosRandomFree == uint8_t(DepartPos::RandomFree));
static_assert(kDepartSpeedGiven == uint8_t(DepartSpeed::Given) &&
              kDepartSpeedZero == uint8_t(DepartSpeed::Zero) &&
              kDepartSpeedRandom == uint8_t(DepartSpeed::Random) &&
              kDepartSpeedMax == uint8_t(DepartSpeed::Max) &&
              kDepartSpeedDesired == uint8_t(DepartSpeed::Desired) &&
              kDepartSpeedLimit == uint8_t(DepartSpeed::SpeedLimit) &&
              kDepartSpeedLast == uint8_t(DepartSpeed::Last) && kDepartSpeedAvg == uint8_t(DepartSpeed::Avg));

// Queue entry flag (host only, taken off before an entry is offered): the vehicle is placed at its lane's
// start (inserts_at_lane_start). With kInsertTeleported the entry says all the batch building needs, so that
// it reads no per-vehicle column.
constexpr uint32_t kQueuedAtLaneStart = 0x40000000u;
constexpr uint32_t kMaxVehicles = kQueuedAtLaneStart;  // vehicle indices below both flags

// The queue entry of vehicle v (its departPos kind `pos_kind`), departing or re-entering after a teleport.
uint32_t queue_entry(uint32_t v, uint8_t pos_kind, bool teleported) {
  return v | (teleported ? kInsertTeleported : 0u) |
         (inserts_at_lane_start(pos_kind, teleported) ? kQueuedAtLaneStart : 0u);
}

// The LaneCounters columns in the order the GPU stepper keeps them.
std::vector<int64_t>* counter_columns(LaneCounters& c, int k) {
  std::vector<int64_t>* columns[kNumLaneCounters] = {&c.sampled_steps, &c.travelled_mm,      &c.waiting_steps,
                                                     &c.time_loss_ms,  &c.occupied_mm_steps, &c.entered,
                                                     &c.left,          &c.arrived,           &c.departed};
  return columns[k];
}

}  // namespace

Simulation::Simulation(const Network& net, const Demand& demand, const SimulationOptions& options)
    : net_(net), demand_(demand), opt_(options), engine_net_(net), pool_(std::max(1, options.threads)) {
  if (!(opt_.step_length > 0)) throw std::invalid_argument("step length must be positive");
  if (demand.size() >= kMaxVehicles)
    throw std::invalid_argument("too many vehicles: " + std::to_string(demand.size()) + " (at most " +
                                std::to_string(kMaxVehicles - 1) + ")");
  dt_ms_ = std::llround(opt_.step_length * 1000.0);
  if (dt_ms_ <= 0 || std::fabs(static_cast<double>(dt_ms_) - opt_.step_length * 1000.0) > 1e-6)
    throw std::invalid_argument("step length must be a whole number of milliseconds");
  time_ms_ = std::llround(opt_.begin * 1000.0);
  const uint32_t nv = demand.size(), nl = net.num_lanes();
  counts_.loaded = nv;

  for (int b = 0; b < 2; ++b) map_[b].assign(net.num_cells() + kLaneMapPadding, 0);
  link_state_.assign(engine_net_.link_begin.back(), 'r');
  signal_next_switch_ms_.assign(net.num_signals(), kSignalNeverSet);
  approach_.assign(nl, LaneApproach{0xFFFFFFFFu, -1, 0, 0, 0, 0, 0});
  claims_.assign(nl, 0);
  merge_requests_.assign(nl, 0);
  lane_counters_.resize(nl);

  trip_status_.assign(nv, kPending);
  resume_rp_.assign(nv, 0);
  depart_time_.assign(nv, 0);
  depart_pos_.assign(nv, 0);
  depart_speed_.assign(nv, 0);
  depart_lane_.assign(nv, -1);
  queue_.resize(net.num_edges());
  for (uint32_t e = 0; e < net.num_edges(); ++e) queue_[e].lanes = net.edge_num_lanes[e];

  const VehicleTypes& t = demand.types;
  for (uint32_t k = 0; k < t.size(); ++k) {
    max_accel_ = std::max(max_accel_, t.accel[k]);
    max_emergency_decel_ = std::max(max_emergency_decel_, t.emergency_decel[k]);
    min_decel_ = std::min(min_decel_, t.decel[k]);
  }

  // Vehicles that depart before the begin time are not simulated (as SUMO, which skips them).
  while (next_departure_ < nv && std::llround(demand.depart[next_departure_] * 1000.0) < time_ms_) {
    trip_status_[next_departure_] = kArrived;
    ++counts_.removed;
    ++next_departure_;
  }
  // A time-to-teleport beyond 2^32 - 1 steps never fires (the stopped-steps counter is 32 bits): capped.
  teleport_steps_ =
      opt_.time_to_teleport > 0
          ? static_cast<uint32_t>(std::min(std::ceil(opt_.time_to_teleport / opt_.step_length), 4294967295.0))
          : 0;
  update_signals(time_ms_);
  enqueue_due(time_ms_);
  insert_waiting(cur_);
  kept_.clear();
  rebuild_active(0);
}

bool Simulation::finished() const {
  return num_active_ == 0 && waiting_ == 0 && next_departure_ >= demand_.size();
}

DepartView Simulation::depart_view() const {
  return DepartView{demand_.depart_lane_kind.data(),  demand_.depart_lane.data(),
                    demand_.depart_pos_kind.data(),   demand_.depart_pos.data(),
                    demand_.depart_speed_kind.data(), demand_.depart_speed.data()};
}

TripView Simulation::trip_view() const {
  return TripView{demand_.vehicle_type.data(), demand_.route_begin.data(),  demand_.route_length.data(),
                  demand_.route_edges.data(),  demand_.speed_factor.data(), demand_.arrival_pos_kind.data(),
                  demand_.arrival_pos.data()};
}

void Simulation::update_signals(int64_t time_ms) {
  const SignalTable table = engine_net_.signal_table(net_);
  for (uint32_t s = 0; s < table.num_signals; ++s)
    update_signal(table, s, time_ms, link_state_.data(), signal_next_switch_ms_.data());
}

char Simulation::link_state(uint32_t conn) const {
  sync_host();
  const int32_t sig = net_.conn_signal[conn];
  if (sig < 0 || net_.conn_link_index[conn] < 0) return net_.conn_state[conn];
  return link_state_[engine_net_.link_begin[static_cast<size_t>(sig)] +
                     static_cast<uint32_t>(net_.conn_link_index[conn])];
}

void Simulation::PlanColumns::reserve_slots(size_t n) {
  if (new_speed.size() >= n) return;
  // Grows by half again so a slowly growing active list does not resize every step. Contents are scratch:
  // the plan pass writes every entry the commit pass reads.
  const size_t c = std::max(n, new_speed.size() + new_speed.size() / 2);
  for (auto* col : {&new_speed, &new_pos, &stop_pos, &lookahead}) col->resize(c);
  for (auto* col : {&new_lane, &new_prev, &new_prev2, &claim0, &claim1, &stop_lane}) col->resize(c);
  for (auto* col : {&arrives, &claim_prio}) col->resize(c);
  for (auto* col : {&new_rp, &first_rp}) col->resize(c);
}

PlanView Simulation::PlanColumns::view() {
  return PlanView{ptr(new_speed), ptr(new_lane), ptr(new_pos),    ptr(new_prev),  ptr(new_prev2),
                  ptr(claim0),    ptr(claim1),   ptr(stop_pos),   ptr(stop_lane), ptr(arrives),
                  ptr(new_rp),    ptr(first_rp), ptr(claim_prio), ptr(lookahead)};
}

VehicleView Simulation::vehicle_view() {
  return VehicleView{ptr(status_),
                     ptr(vehicle_),
                     ptr(route_pos_),
                     ptr(speed_),
                     ptr(lane_),
                     ptr(prev_),
                     ptr(prev2_),
                     ptr(pos_),
                     ptr(old_lane_),
                     ptr(old_prev_),
                     ptr(old_prev2_),
                     ptr(old_pos_),
                     ptr(stopped_steps_),
                     ptr(waiting_steps_),
                     ptr(waiting_count_),
                     ptr(time_loss_),
                     ptr(route_length_),
                     ptr(arrival_step_),
                     ptr(lane_change_dir_),
                     ptr(held_at_line_),
                     ptr(limit_reason_),
                     ptr(best_rp_),
                     ptr(best_mask_),
                     ptr(conn_lane_),
                     ptr(conn_rp_),
                     ptr(conn_),
                     ptr(trip_type_),
                     ptr(trip_speed_factor_),
                     ptr(trip_route_begin_),
                     ptr(trip_route_size_)};
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
                    teleport_steps_};
}

StepContext Simulation::context(const uint8_t* map_now, uint8_t* map_next) {
  StepContext ctx{};
  ctx.net = engine_net_.view(net_);
  const VehicleTypes& t = demand_.types;
  ctx.types = TypeView{t.length.data(),          t.min_gap.data(),   t.accel.data(), t.decel.data(),
                       t.emergency_decel.data(), t.max_speed.data(), t.tau.data(),   t.delta.data()};
  ctx.trips = trip_view();
  ctx.veh = vehicle_view();
  ctx.plan = plan_.view();
  ctx.params = step_params();
  ctx.map_now = map_now;
  ctx.map_next = map_next;
  ctx.link_state = link_state_.data();
  ctx.approach = approach_.data();
  ctx.claims = claims_.data();
  ctx.merge_requests = merge_requests_.data();
  ctx.yielder_begin = engine_net_.yielder_begin.data();
  ctx.yielder = engine_net_.yielder.data();
  // Left null (ctx is zeroed) when no output wants them: the passes then skip their atomics.
  if (opt_.lane_counters) {
    LaneCounters& lc = lane_counters_;
    ctx.cnt_sampled_steps = lc.sampled_steps.data();
    ctx.cnt_travelled_mm = lc.travelled_mm.data();
    ctx.cnt_waiting_steps = lc.waiting_steps.data();
    ctx.cnt_time_loss_ms = lc.time_loss_ms.data();
    ctx.cnt_occupied_mm_steps = lc.occupied_mm_steps.data();
    ctx.cnt_entered = lc.entered.data();
    ctx.cnt_left = lc.left.data();
    ctx.cnt_arrived = lc.arrived.data();
  }
  return ctx;
}

void Simulation::step() {
  if (opt_.gpu)
    step_gpu();
  else
    step_cpu();
}

void Simulation::step_cpu() {
  plan_.reserve_slots(active_.size());
  StepContext ctx = context(map_[cur_].data(), map_[1 - cur_].data());
  update_signals(ctx.params.signal_time_ms);
  // Each pass is one parallel loop over the active vehicles, finished before the next starts. Each names
  // where its vehicles are (the footprint it clears or writes, the front it plans from) for the prefetch.
  const int64_t n = static_cast<int64_t>(active_.size());
  const uint32_t* act = active_.data();
  auto pass = [&](auto where, const uint8_t* map, auto fetch_lane, auto vehicle_pass) {
    pool_.run(
        n,
        [&](int64_t b, int64_t e) {
          run_prefetched(b, e, ctx.net, map, where, fetch_lane,
                         [&](int64_t i) { vehicle_pass(ctx, static_cast<uint32_t>(i), act[i]); });
        },
        kParallelMinVehicles);
  };
  auto lane_columns = [&](int32_t l) { prefetch_lane_columns(ctx.net, l); };
  // The plan also reads the lane's neighbours (lane changes), kind and merge request.
  auto plan_lane_columns = [&](int32_t l) {
    prefetch_lane_columns(ctx.net, l);
    __builtin_prefetch(&ctx.merge_requests[l]);
    __builtin_prefetch(&ctx.net.lane_left[l]);
    __builtin_prefetch(&ctx.net.lane_right[l]);
    __builtin_prefetch(&ctx.net.lane_internal[l]);
    __builtin_prefetch(&ctx.net.lane_rank[l]);
  };
  auto old_front = [&](int64_t i) { return LaneAt{ctx.veh.old_lane[act[i]], ctx.veh.old_pos[act[i]]}; };
  // Only running vehicles have a front to plan from, and only their plans were written this step.
  auto front = [&](int64_t i) {
    const uint32_t k = act[i];
    return LaneAt{ctx.veh.status[k] == kRunning ? ctx.veh.lane[k] : -1, ctx.veh.pos[k]};
  };
  auto new_front = [&](int64_t i) {
    return LaneAt{ctx.veh.status[act[i]] == kRunning ? ctx.plan.new_lane[i] : -1, ctx.plan.new_pos[i]};
  };
  // Lambdas rather than function pointers, so that each pass's body is inlined into its loop.
  pass(old_front, ctx.map_next, lane_columns,
       [](StepContext& c, uint32_t i, uint32_t k) { clear_old_footprint(c, i, k); });
  // Approach reads the lane map only for vehicles within reach of their lane's end: no cells fetched for it.
  pass(front, nullptr, lane_columns,
       [](StepContext& c, uint32_t i, uint32_t k) { approach_vehicle(c, i, k); });
  pass(front, ctx.map_now, plan_lane_columns,
       [](StepContext& c, uint32_t i, uint32_t k) { plan_vehicle(c, i, k); });
  pass(new_front, ctx.map_next, lane_columns,
       [](StepContext& c, uint32_t i, uint32_t k) { commit_vehicle(c, i, k); });
  counts_.vehicle_updates += static_cast<uint64_t>(n);

  time_ms_ += dt_ms_;
  ++step_;
  // One walk over the active list: the vehicles whose trip or road time ended in this step, and the slots
  // that stay active (running, or left the road in this step: the next clear pass removes their footprint).
  // Neither handling the ends nor inserting changes which slots stay: ends and teleports set no vehicle
  // running, and insertion takes only free slots.
  ends_.clear();
  kept_.resize(active_.size());
  size_t kept = 0;
  uint64_t running = 0;
  for (uint32_t k : active_) {
    const uint32_t kind = step_end_kind(ctx.veh, k, step_, teleport_steps_);
    if (kind != kEndNone) ends_.push_back(vehicle_end(ctx.veh, k, kind));
    running += ctx.veh.status[k] == kRunning ? 1u : 0u;
    kept_[kept] = k;  // a branch on staying would be mispredicted
    kept += stays_active(ctx.veh, k) ? 1u : 0u;
  }
  kept_.resize(kept);
  handle_vehicle_ends(ends_);
  for (const TeleportMove& m : moves_) apply_teleport_move(ctx.veh, m, step_);
  enqueue_due(time_ms_);
  insert_waiting(1 - cur_);
  cur_ = 1 - cur_;
  rebuild_active(running);
  if (opt_.slot_sort_interval > 0 && step_ % opt_.slot_sort_interval == 0) sort_slots();
}

void Simulation::step_gpu() {
  if (!gpu_) {
    // The device takes over the state as the host left it (signals of the current time, first insertions).
    const StepContext ctx = context(map_[cur_].data(), map_[1 - cur_].data());
    gpu_ = make_cuda_stepper(
        ctx, engine_net_.signal_table(net_),
        GpuStepSizes{demand_.size(), slots_.size(), net_.num_edges(), net_.num_connections(),
                     demand_.types.size(), demand_.route_edges.size()},
        depart_view(), map_[1 - cur_].data(), cur_, active_, opt_.lane_counters);
  }
  gpu_->start_step(step_params(), cur_, step_ + 1);
  // While the device runs the passes: the departures due by the end of the step join their queues. Nothing
  // there depends on the step's outcome, and the order does not matter: a vehicle teleported in the step
  // joins its queue at the head (handle_vehicle_ends), a departure at the tail.
  enqueue_due(time_ms_ + dt_ms_);
  GpuStepOutcome out;
  out.ends.swap(ends_);
  gpu_->finish_step(out);
  counts_.vehicle_updates += num_active_;
  check_kept(out.kept);

  time_ms_ += dt_ms_;
  ++step_;
  handle_vehicle_ends(out.ends);
  if (!moves_.empty()) gpu_->apply_teleports(moves_, step_);
  insert_waiting(1 - cur_);
  cur_ = 1 - cur_;

  const std::vector<uint32_t>& added = added_slots();
  gpu_->rebuild_active(inits_, added);
  num_active_ = out.kept + static_cast<uint32_t>(added.size());
  counts_.running = out.running + static_cast<uint64_t>(inits_.size());
  counts_.waiting = waiting_;
  inits_.clear();
  release_retired_slots();
  ends_.swap(out.ends);
  if (opt_.slot_sort_interval > 0 && step_ % opt_.slot_sort_interval == 0) sort_slots();
}

void Simulation::record_trip(const VehicleEnd& e, bool teleported) {
  const uint32_t v = e.vehicle;
  ++counts_.arrived;
  TripRecord r;
  r.vehicle = v;
  r.depart = depart_time_[v];
  r.depart_delay = depart_time_[v] - demand_.depart[v];
  r.arrival = time();
  r.depart_lane = static_cast<uint32_t>(depart_lane_[v]);
  r.arrival_lane = static_cast<uint32_t>(e.lane);
  r.depart_pos = depart_pos_[v];
  r.depart_speed = depart_speed_[v];
  r.arrival_pos = e.pos;
  r.arrival_speed = teleported ? 0.0f : e.speed;
  r.route_length = e.route_length;
  r.waiting_time = static_cast<double>(e.waiting_steps) * opt_.step_length;
  r.waiting_count = e.waiting_count;
  r.time_loss = e.time_loss;
  r.speed_factor = demand_.speed_factor[v];
  r.teleported = teleported;
  travel_time_sum_ += r.arrival - r.depart;
  finished_.push_back(r);
}

// Arrivals become trip records; teleporting vehicles re-enter at the next edge of their route (moves_ says
// which, for the backend to apply). Handled in vehicle order (the passes find them in slot order); their
// slots are free once the next step has cleared their footprint.
void Simulation::handle_vehicle_ends(std::vector<VehicleEnd>& ends) {
  std::sort(ends.begin(), ends.end(),
            [](const VehicleEnd& a, const VehicleEnd& b) { return a.vehicle < b.vehicle; });
  moves_.clear();
  teleport_events_.clear();
  for (const VehicleEnd& e : ends) {
    const uint32_t v = e.vehicle;
    retiring_next_.push_back(e.slot);
    if (e.kind == kEndArrived) {
      trip_status_[v] = kArrived;
      record_trip(e, false);
      continue;
    }
    ++counts_.teleports;
    teleport_events_.push_back(TeleportEvent{v, static_cast<uint32_t>(e.lane),
                                             e.limit_reason == kYield       ? TeleportCause::Yield
                                             : e.limit_reason == kWrongLane ? TeleportCause::WrongLane
                                                                            : TeleportCause::Jam});
    if (e.route_pos + 1 >= demand_.route_length[v]) {
      // Teleported past the end of its route: the trip ends here.
      moves_.push_back(TeleportMove{v, e.slot, 1});
      trip_status_[v] = kArrived;
      record_trip(e, true);
      continue;
    }
    moves_.push_back(TeleportMove{v, e.slot, 0});
    trip_status_[v] = kTeleporting;
    resume_rp_[v] = e.route_pos + 1;
    carried_[v] = Carried{e.route_length, e.time_loss, e.waiting_steps, e.waiting_count};
    const uint32_t edge = demand_.route_edges[demand_.route_begin[v] + e.route_pos + 1];
    EdgeQueue& q = queue_[edge];
    // Teleported vehicles go first: they have been on the road already.
    q.entries.insert(q.entries.begin() + q.head, queue_entry(v, demand_.depart_pos_kind[v], true));
    if (q.head + 1 == q.entries.size())
      queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), edge), edge);
    ++waiting_;
  }
}

void Simulation::enqueue_due(int64_t until_ms) {
  const uint32_t nv = demand_.size();
  while (next_departure_ < nv && std::llround(demand_.depart[next_departure_] * 1000.0) <= until_ms) {
    const uint32_t v = next_departure_++;
    if (demand_.route_length[v] == 0) {
      trip_status_[v] = kArrived;
      ++counts_.removed;
      continue;
    }
    const uint32_t e = demand_.route_edges[demand_.route_begin[v]];
    EdgeQueue& q = queue_[e];
    if (q.lanes == 0) {
      trip_status_[v] = kArrived;
      ++counts_.removed;
      continue;
    }
    if (q.head == q.entries.size()) {
      q.entries.clear();
      q.head = 0;
      queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), e), e);
    }
    q.entries.push_back(queue_entry(v, demand_.depart_pos_kind[v], false));
    ++waiting_;
  }
}

void Simulation::insert_waiting(int map_index) {
  // The head of each queue (up to kMaxInsertPerEdge), edges ascending. Insertion stops at the first vehicle
  // that does not fit, and once each lane of the edge has taken a vehicle at its start the next one placed
  // there cannot fit (inserts_at_lane_start): the offer ends before it, with the same result (on a
  // congested day most queues are long, and the batch is a few entries per edge instead of 16).
  batch_edge_.clear();
  batch_begin_.assign(1, 0);
  batch_entry_.clear();
  batch_rp_.clear();
  for (uint32_t e : queued_edges_) {
    const EdgeQueue& q = queue_[e];
    const size_t end = std::min<size_t>(q.entries.size(), q.head + kMaxInsertPerEdge);
    uint32_t lane_starts_left = q.lanes;
    for (size_t i = q.head; i < end; ++i) {
      const uint32_t entry = q.entries[i];
      if (entry & kQueuedAtLaneStart) {
        if (lane_starts_left == 0) break;
        --lane_starts_left;
      }
      const uint32_t offered = entry & ~kQueuedAtLaneStart;  // the insertion knows only kInsertTeleported
      batch_entry_.push_back(offered);
      batch_rp_.push_back((offered & kInsertTeleported) ? resume_rp_[offered & ~kInsertTeleported] : 0u);
    }
    batch_edge_.push_back(e);
    batch_begin_.push_back(static_cast<uint32_t>(batch_entry_.size()));
  }
  const size_t entries = batch_entry_.size();
  batch_inserted_.assign(batch_edge_.size(), 0);
  batch_lane_.resize(entries);
  batch_pos_.resize(entries);
  batch_speed_.resize(entries);
  const InsertBatch batch{static_cast<uint32_t>(batch_edge_.size()),
                          batch_edge_.data(),
                          batch_begin_.data(),
                          batch_entry_.data(),
                          batch_rp_.data(),
                          batch_inserted_.data(),
                          batch_lane_.data(),
                          batch_pos_.data(),
                          batch_speed_.data()};
  // The config's step length as given (not the millisecond-rounded step): the insertion checks use it.
  const InsertParams params{static_cast<float>(opt_.step_length),
                            opt_.seed,
                            max_emergency_decel_,
                            min_decel_,
                            lane_counters_.departed.data(),
                            lane_counters_.entered.data()};
  if (entries > 0) {
    if (gpu_) {
      gpu_->insert(batch, static_cast<uint32_t>(entries), params, map_index);
    } else {
      uint8_t* map = map_[map_index].data();
      const StepContext ctx = context(map_[cur_].data(), map);
      const DepartView depart = depart_view();
      for (uint32_t slot = 0; slot < batch.num_slots; ++slot)
        insert_queue_head(ctx, depart, params, map, batch, slot);
    }
  }

  // Advance the queues past the inserted heads, give each inserted vehicle a slot and record the
  // departures, in the order of the batch.
  inits_.clear();
  std::vector<uint32_t>& still = scratch_;
  still.clear();
  for (uint32_t slot = 0; slot < batch.num_slots; ++slot) {
    const uint32_t e = batch_edge_[slot];
    if (batch_inserted_[slot] == 0) {  // as it was: still waiting (most queues, on a congested road)
      still.push_back(e);
      continue;
    }
    EdgeQueue& q = queue_[e];
    for (uint32_t i = batch_begin_[slot]; i < batch_begin_[slot] + batch_inserted_[slot]; ++i) {
      const uint32_t v = batch_entry_[i] & ~kInsertTeleported;
      SlotInit init{0, v, batch_rp_[i], batch_lane_[i], batch_pos_[i], batch_speed_[i], 0.0f, 0.0f, 0, 0};
      if (batch_entry_[i] & kInsertTeleported) {
        const auto c = carried_.find(v);
        if (c != carried_.end()) {
          init.route_length = c->second.route_length;
          init.time_loss = c->second.time_loss;
          init.waiting_steps = c->second.waiting_steps;
          init.waiting_count = c->second.waiting_count;
          carried_.erase(c);
        }
      } else {
        ++counts_.inserted;
        depart_delay_sum_ += time() - demand_.depart[v];
        depart_time_[v] = static_cast<float>(time());
        depart_lane_[v] = batch_lane_[i];
        depart_pos_[v] = batch_pos_[i];
        depart_speed_[v] = batch_speed_[i];
      }
      take_slot(init);
      ++q.head;
      --waiting_;
    }
    if (q.head < q.entries.size()) {
      still.push_back(e);
    } else {
      q.entries.clear();
      q.head = 0;
    }
  }
  queued_edges_.swap(still);
}

void Simulation::take_slot(SlotInit& init) {
  init.slot = slots_.take();
  const size_t n = slots_.size();
  if (status_.size() < n) {
    // Grows by half again; an entry's contents are set when its slot is taken (activate_slot).
    const size_t c = std::max(n, status_.size() + status_.size() / 2);
    for (auto* col : {&status_, &lane_change_dir_, &held_at_line_, &limit_reason_}) col->resize(c);
    for (auto* col : {&vehicle_, &route_pos_, &stopped_steps_, &waiting_steps_, &waiting_count_,
                      &arrival_step_, &conn_rp_, &trip_type_, &trip_route_begin_, &trip_route_size_})
      col->resize(c);
    for (auto* col : {&best_rp_, &best_mask_}) col->resize(c * kBestLaneEntries);
    for (auto* col : {&speed_, &pos_, &old_pos_, &time_loss_, &route_length_, &trip_speed_factor_})
      col->resize(c);
    for (auto* col : {&lane_, &prev_, &prev2_, &old_lane_, &old_prev_, &old_prev2_, &conn_lane_, &conn_})
      col->resize(c);
  }
  inits_.push_back(init);
  // On the CPU the slot starts now; the GPU backend starts this step's inits on the device.
  if (!gpu_) activate_slot(vehicle_view(), trip_view(), init);
}

// Exactly the slots whose vehicles left the road in the previous step drop out of the active list
// (stays_active): anything else would free a slot still in use, or never free one.
void Simulation::check_kept(size_t kept) const {
  if (kept + retiring_.size() != num_active_)
    throw std::logic_error("step kept " + std::to_string(kept) + " of " + std::to_string(num_active_) +
                           " active slots, " + std::to_string(retiring_.size()) + " were to leave");
}

// The slots this step's insertions took, ascending (they join the active list).
const std::vector<uint32_t>& Simulation::added_slots() {
  added_.clear();
  for (const SlotInit& in : inits_) added_.push_back(in.slot);
  std::sort(added_.begin(), added_.end());
  return added_;
}

// The slots that left the active list in this step (their vehicles left the road in the previous one) are
// free; this step's ends leave in the next.
void Simulation::release_retired_slots() {
  for (uint32_t k : retiring_) slots_.release(k);
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
  if (gpu_) {
    gpu_->sort_slots(retiring_);  // the device's columns, its active list and retiring_
  } else {
    const size_t n = active_.size();
    std::vector<uint64_t>& keys = slot_keys_;
    keys.resize(n);
    for (size_t i = 0; i < n; ++i)
      keys[i] = uint64_t{static_cast<uint32_t>(lane_[active_[i]])} << 32 | active_[i];
    std::sort(keys.begin(), keys.end());
    std::vector<uint32_t>& order = slot_order_;  // order[new slot] = old slot
    order.resize(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(keys[i]);
    VehicleView veh = vehicle_view();
    std::vector<uint8_t>& moved = slot_bytes_;
    for_each_vehicle_column(veh, veh, [&](auto* column, auto*, uint32_t per) {
      using T = std::remove_pointer_t<decltype(column)>;
      moved.resize(n * per * sizeof(T));
      T* to = reinterpret_cast<T*>(moved.data());
      for (size_t i = 0; i < n; ++i)
        for (uint32_t e = 0; e < per; ++e) to[i * per + e] = column[size_t{order[i]} * per + e];
      std::copy_n(to, n * per, column);
    });
    std::vector<uint32_t>& new_slot = slot_new_;
    new_slot.assign(slots_.size(), kNotActive);
    for (size_t i = 0; i < n; ++i) {
      new_slot[order[i]] = static_cast<uint32_t>(i);
      active_[i] = static_cast<uint32_t>(i);
    }
    for (uint32_t& k : retiring_) k = new_slot[k];
  }
  for (const uint32_t k : retiring_)
    if (k == kNotActive) throw std::logic_error("a slot due to leave was not in the active list");
  slots_.reset(num_active_);
  by_vehicle_step_ = 0xFFFFFFFFu;
}

void Simulation::rebuild_active(uint64_t running) {
  // The kept slots (kept_, ascending) and the newly inserted ones, ascending. Running vehicles: those of
  // the step's active list, and every one inserted (as the GPU backend counts).
  check_kept(kept_.size());
  const std::vector<uint32_t>& added = added_slots();
  running += added.size();
  active_.resize(kept_.size() + added.size());
  std::merge(kept_.begin(), kept_.end(), added.begin(), added.end(), active_.begin());
  inits_.clear();
  release_retired_slots();
  num_active_ = static_cast<uint32_t>(active_.size());
  counts_.running = running;
  counts_.waiting = waiting_;
}

// On the GPU backend the host arrays are a copy fetched on demand, at most once per step (const: they only
// mirror the device's state, which stays as it is).
void Simulation::sync_sample() const {
  if (!gpu_ || sampled_step_ == step_) return;
  auto* self = const_cast<Simulation*>(this);
  std::vector<uint32_t> vehicle;
  std::vector<uint8_t> status;
  std::vector<int32_t> lane;
  std::vector<float> pos, speed;
  self->gpu_->sample(self->active_, vehicle, status, lane, pos, speed);
  for (size_t i = 0; i < active_.size(); ++i) {
    const uint32_t k = active_[i];
    self->vehicle_[k] = vehicle[i];
    self->status_[k] = status[i];
    self->lane_[k] = lane[i];
    self->pos_[k] = pos[i];
    self->speed_[k] = speed[i];
  }
  sampled_step_ = step_;
}

void Simulation::sync_host() const {
  if (!gpu_ || synced_step_ == step_) return;
  sync_sample();  // the active list
  auto* self = const_cast<Simulation*>(this);
  self->gpu_->download_state(self->context(nullptr, self->map_[cur_].data()), slots_.size(), cur_,
                             self->link_state_.data());
  synced_step_ = step_;
}

const LaneCounters& Simulation::lane_counters() const {
  if (gpu_ && opt_.lane_counters) {
    auto* self = const_cast<Simulation*>(this);
    int64_t* columns[kNumLaneCounters];
    for (int k = 0; k < kNumLaneCounters; ++k) columns[k] = counter_columns(self->lane_counters_, k)->data();
    self->gpu_->drain_counters(columns);
  }
  return lane_counters_;
}

const std::vector<uint64_t>& Simulation::active_by_vehicle() const {
  sync_sample();
  // Sorted when an output lists vehicles, once per step that asks: the passes and the summary need no order.
  if (by_vehicle_step_ != step_) {
    by_vehicle_.clear();
    for (const uint32_t k : active_) by_vehicle_.push_back(uint64_t{vehicle_[k]} << 32 | k);
    std::sort(by_vehicle_.begin(), by_vehicle_.end());
    by_vehicle_step_ = step_;
  }
  return by_vehicle_;
}

void Simulation::sample_fcd(FcdFrame& frame) const {
  frame.time = time();
  frame.vehicle.clear();
  frame.lane.clear();
  frame.pos.clear();
  frame.speed.clear();
  for (const uint64_t key : active_by_vehicle()) {
    const uint32_t v = static_cast<uint32_t>(key >> 32), k = static_cast<uint32_t>(key);
    if (status_[k] != kRunning) continue;
    frame.vehicle.push_back(v);
    frame.lane.push_back(static_cast<uint32_t>(lane_[k]));
    frame.pos.push_back(pos_[k]);
    frame.speed.push_back(speed_[k]);
  }
}

// The slot of vehicle v while it holds one, else -1. A vehicle that re-entered the road right after a
// teleport holds its old slot for one more step (to clear its footprint) besides the new one; the new one is
// further along the route.
int32_t Simulation::slot_of(uint32_t v) const {
  sync_host();
  const std::vector<uint64_t>& keys = active_by_vehicle();
  int32_t slot = -1;
  for (auto it = std::lower_bound(keys.begin(), keys.end(), uint64_t{v} << 32);
       it != keys.end() && (*it >> 32) == v; ++it) {
    const uint32_t k = static_cast<uint32_t>(*it);
    if (slot < 0 || route_pos_[k] > route_pos_[static_cast<uint32_t>(slot)]) slot = static_cast<int32_t>(k);
  }
  return slot;
}

uint8_t Simulation::status(uint32_t v) const { return on_road(status_, v, trip_status_[v]); }
int32_t Simulation::lane(uint32_t v) const { return on_road(lane_, v, int32_t{-1}); }
float Simulation::pos(uint32_t v) const { return on_road(pos_, v, 0.0f); }
float Simulation::speed(uint32_t v) const { return on_road(speed_, v, 0.0f); }
uint8_t Simulation::limit_reason(uint32_t v) const { return on_road(limit_reason_, v, uint8_t{0}); }

const std::vector<uint32_t>& Simulation::active() const {
  sync_host();
  active_vehicles_.clear();
  for (const uint64_t key : active_by_vehicle()) active_vehicles_.push_back(static_cast<uint32_t>(key >> 32));
  // A vehicle that teleported and re-entered at once holds its old slot for one more step.
  active_vehicles_.erase(std::unique(active_vehicles_.begin(), active_vehicles_.end()),
                         active_vehicles_.end());
  return active_vehicles_;
}

std::vector<TripRecord> Simulation::take_finished_trips() {
  std::vector<TripRecord> out;
  out.swap(finished_);
  return out;
}

SummaryRow Simulation::summary_row() const {
  SummaryRow r;
  r.time = time();
  r.loaded = counts_.loaded;
  r.inserted = counts_.inserted;
  r.running = counts_.running;
  r.waiting = counts_.waiting;
  r.arrived = counts_.arrived;
  r.ended = counts_.arrived;
  r.teleports = counts_.teleports;
  // Summed in units of 2^-24 (integers: the sums do not depend on the order of the slots, which sort_slots
  // changes; each term is off by at most 3e-8).
  int64_t speed_sum = 0, rel_sum = 0;
  uint64_t running = 0, halting = 0;
  const VehicleTypes& t = demand_.types;
  sync_sample();
  for (const uint32_t k : active_) {
    if (status_[k] != kRunning) continue;
    const uint32_t v = vehicle_[k];
    ++running;
    speed_sum += std::llround(static_cast<double>(speed_[k]) * kSummaryUnits);
    const float v0 = desired_speed(net_.lane_speed[lane_[k]], demand_.speed_factor[v],
                                   t.max_speed[demand_.vehicle_type[v]]);
    if (v0 > 0) rel_sum += std::llround(static_cast<double>(speed_[k] / v0) * kSummaryUnits);
    if (speed_[k] < kHaltingSpeed) ++halting;
  }
  r.halting = halting;
  if (running > 0) {
    r.mean_speed = static_cast<double>(speed_sum) / kSummaryUnits / static_cast<double>(running);
    r.mean_speed_relative = static_cast<double>(rel_sum) / kSummaryUnits / static_cast<double>(running);
  }
  // As SUMO: meanWaitingTime is the mean insertion delay of the vehicles inserted so far, meanTravelTime
  // the mean trip duration of the vehicles that arrived so far.
  if (counts_.inserted > 0) r.mean_waiting_time = depart_delay_sum_ / static_cast<double>(counts_.inserted);
  if (counts_.arrived > 0) r.mean_travel_time = travel_time_sum_ / static_cast<double>(counts_.arrived);
  return r;
}

std::string Simulation::check_lane_map() const {
  sync_host();
  std::vector<int64_t> owner(net_.num_cells(), -1);
  const NetView nv = engine_net_.view(net_);
  std::vector<uint8_t> expect(net_.num_cells(), 0);
  for (const uint64_t key : active_by_vehicle()) {
    const uint32_t v = static_cast<uint32_t>(key >> 32), k = static_cast<uint32_t>(key);
    if (status_[k] != kRunning) continue;
    const Footprint fp{lane_[k], prev_[k], prev2_[k], pos_[k]};
    std::vector<uint8_t> mark(net_.num_cells(), 0);
    apply_footprint(mark.data(), nv, fp, demand_.types.length[demand_.vehicle_type[v]], 1);
    for (uint64_t c = 0; c < mark.size(); ++c) {
      if (!mark[c]) continue;
      if (owner[c] >= 0)
        return "vehicles " + demand_.vehicle_id[static_cast<size_t>(owner[c])] + " and " +
               demand_.vehicle_id[v] + " share cell " + std::to_string(c) + " at t=" + std::to_string(time());
      owner[c] = v;
      expect[c] = 1;
    }
  }
  const std::vector<uint8_t>& map = map_[cur_];
  for (uint64_t c = 0; c < net_.num_cells(); ++c)
    if ((map[c] != 0) != (expect[c] != 0))
      return "lane map cell " + std::to_string(c) +
             (map[c] ? " marked but no vehicle there" : " unmarked under a vehicle") +
             " at t=" + std::to_string(time());
  return "";
}

}  // namespace lpsim

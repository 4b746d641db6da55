#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/device_select.hpp"
#include "kernels/rng.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

namespace {

template <class T>
T* ptr(std::vector<T>& v) {
  return v.data();
}

// Fewer active vehicles than this run the passes on the calling thread.
constexpr int64_t kParallelMinVehicles = 2048;

// Salt for departure draws (random lane / position), apart from every other use of the RNG.
constexpr uint64_t kDepartRngSalt = 0x4445504152545F31ull;

}  // namespace

Simulation::Simulation(const Network& net, const Demand& demand, const SimulationOptions& options)
    : net_(net), demand_(demand), opt_(options), engine_net_(net), pool_(std::max(1, options.threads)) {
  if (!(opt_.step_length > 0)) throw std::invalid_argument("step length must be positive");
  dt_ms_ = std::llround(opt_.step_length * 1000.0);
  if (dt_ms_ <= 0 || std::fabs(static_cast<double>(dt_ms_) - opt_.step_length * 1000.0) > 1e-6)
    throw std::invalid_argument("step length must be a whole number of milliseconds");
  time_ms_ = std::llround(opt_.begin * 1000.0);
  const uint32_t nv = demand.size(), nl = net.num_lanes();
  counts_.loaded = nv;

  for (int b = 0; b < 2; ++b) map_[b].assign(net.num_cells(), 0);
  link_state_.assign(engine_net_.link_begin.back(), 'r');
  approach_.assign(nl, LaneApproach{0xFFFFFFFFu, -1, 0, 0, 0, 0, 0});
  claims_.assign(nl, 0);
  merge_requests_.assign(nl, 0);
  lane_counters_.resize(nl);

  status_.assign(nv, kPending);
  lane_change_dir_.assign(nv, 0);
  held_at_line_.assign(nv, 0);
  limit_reason_.assign(nv, 0);
  best_rp_.assign(nv, 0xFFFFFFFFu);
  best_mask_.assign(nv, 0);
  claim_prio_.assign(nv, 1);
  arrives_.assign(nv, 0);
  route_pos_.assign(nv, 0);
  new_rp_.assign(nv, 0);
  first_rp_.assign(nv, 0);
  stopped_steps_.assign(nv, 0);
  waiting_steps_.assign(nv, 0);
  waiting_count_.assign(nv, 0);
  arrival_step_.assign(nv, 0);
  speed_.assign(nv, 0);
  pos_.assign(nv, 0);
  old_pos_.assign(nv, 0);
  time_loss_.assign(nv, 0);
  route_length_.assign(nv, 0);
  lane_.assign(nv, -1);
  prev_.assign(nv, -1);
  prev2_.assign(nv, -1);
  old_lane_.assign(nv, -1);
  old_prev_.assign(nv, -1);
  old_prev2_.assign(nv, -1);
  new_speed_.assign(nv, 0);
  new_pos_.assign(nv, 0);
  stop_pos_.assign(nv, 0);
  new_lane_.assign(nv, -1);
  new_prev_.assign(nv, -1);
  new_prev2_.assign(nv, -1);
  claim0_.assign(nv, -1);
  claim1_.assign(nv, -1);
  stop_lane_.assign(nv, -1);
  teleport_pending_.assign(nv, 0);
  depart_time_.assign(nv, 0);
  depart_pos_.assign(nv, 0);
  depart_speed_.assign(nv, 0);
  depart_lane_.assign(nv, -1);
  queue_.resize(net.num_edges());
  queue_head_.assign(net.num_edges(), 0);

  const VehicleTypes& t = demand.types;
  for (uint32_t k = 0; k < t.size(); ++k) {
    max_accel_ = std::max(max_accel_, t.accel[k]);
    max_emergency_decel_ = std::max(max_emergency_decel_, t.emergency_decel[k]);
    min_decel_ = std::min(min_decel_, t.decel[k]);
  }

  // Vehicles that depart before the begin time are not simulated (as SUMO, which skips them).
  while (next_departure_ < nv && std::llround(demand.depart[next_departure_] * 1000.0) < time_ms_) {
    status_[next_departure_] = kArrived;
    ++counts_.removed;
    ++next_departure_;
  }
  update_signals();
  enqueue_due(time_ms_);
  insert_waiting(map_[cur_].data());
  rebuild_active();
}

bool Simulation::finished() const {
  return active_.empty() && waiting_ == 0 && next_departure_ >= demand_.size();
}


TripView Simulation::trip_view() const {
  return TripView{demand_.vehicle_type.data(), demand_.route_begin.data(), demand_.route_length.data(),
                  demand_.route_edges.data(), demand_.speed_factor.data(), demand_.arrival_pos_kind.data(),
                  demand_.arrival_pos.data()};
}

void Simulation::update_signals() {
  const SignalTable table = engine_net_.signal_table(net_);
  for (uint32_t s = 0; s < table.num_signals; ++s) update_signal(table, s, time_ms_, link_state_.data());
}

char Simulation::link_state(uint32_t conn) const {
  const int32_t sig = net_.conn_signal[conn];
  if (sig < 0 || net_.conn_link_index[conn] < 0) return net_.conn_state[conn];
  return link_state_[engine_net_.link_begin[static_cast<size_t>(sig)] + static_cast<uint32_t>(net_.conn_link_index[conn])];
}

void Simulation::step() {
  const uint8_t* map_now = map_[cur_].data();
  uint8_t* map_next = map_[1 - cur_].data();
  update_signals();

  StepContext ctx{};
  ctx.net = engine_net_.view(net_);
  const VehicleTypes& t = demand_.types;
  ctx.types = TypeView{t.length.data(), t.min_gap.data(), t.accel.data(), t.decel.data(), t.emergency_decel.data(),
                       t.max_speed.data(), t.tau.data(), t.delta.data()};
  ctx.trips = trip_view();
  ctx.veh = VehicleView{ptr(status_),        ptr(route_pos_),     ptr(speed_),          ptr(lane_),
                        ptr(prev_),          ptr(prev2_),         ptr(pos_),            ptr(old_lane_),
                        ptr(old_prev_),      ptr(old_prev2_),     ptr(old_pos_),        ptr(stopped_steps_),
                        ptr(waiting_steps_), ptr(waiting_count_), ptr(time_loss_),      ptr(route_length_),
                        ptr(arrival_step_),  ptr(lane_change_dir_), ptr(held_at_line_), ptr(limit_reason_),
                        ptr(best_rp_),       ptr(best_mask_)};
  ctx.plan = PlanView{ptr(new_speed_), ptr(new_lane_), ptr(new_pos_),  ptr(new_prev_),   ptr(new_prev2_),
                      ptr(claim0_),    ptr(claim1_),   ptr(stop_pos_), ptr(stop_lane_), ptr(arrives_),
                      ptr(new_rp_),    ptr(first_rp_), ptr(claim_prio_)};
  const float dt = static_cast<float>(dt_ms_) / 1000.0f;
  const uint32_t teleport_steps =
      opt_.time_to_teleport > 0 ? static_cast<uint32_t>(std::ceil(opt_.time_to_teleport / opt_.step_length)) : 0;
  ctx.params = StepParams{step_, time_ms_, dt, opt_.seed, idm_default_substeps(dt), max_accel_, max_emergency_decel_,
                          teleport_steps};
  ctx.map_now = map_now;
  ctx.map_next = map_next;
  ctx.link_state = link_state_.data();
  ctx.approach = approach_.data();
  ctx.claims = claims_.data();
  ctx.merge_requests = merge_requests_.data();
  ctx.yielder_begin = engine_net_.yielder_begin.data();
  ctx.yielder = engine_net_.yielder.data();
  // Left null (ctx is zeroed) when no output wants them: the passes then skip their atomics.
  if (opt_.lane_counters || opt_.gpu) {
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

  const int64_t n = static_cast<int64_t>(active_.size());
  if (opt_.gpu) {
    // GPU backend: the same passes on the device; it leaves in ctx's host arrays what the CPU loops would.
    if (!gpu_)
      gpu_ = make_gpu_stepper(ctx, engine_net_.signal_table(net_),
                              GpuStepSizes{demand_.size(), net_.num_edges(), net_.num_connections(), t.size(),
                                           demand_.route_edges.size()});
    gpu_->step(ctx, active_.data(), static_cast<uint32_t>(n));
  } else {
    // CPU backend: each pass is one parallel loop over the active vehicles, finished before the next starts.
    const uint32_t* act = active_.data();
    auto pass = [&](auto vehicle_pass) {
      pool_.run(n, [&](int64_t b, int64_t e) { for (int64_t i = b; i < e; ++i) vehicle_pass(ctx, act[i]); },
                kParallelMinVehicles);
    };
    pass(clear_old_footprint);
    pass(approach_vehicle);
    pass(plan_vehicle);
    pass(commit_vehicle);
  }
  counts_.vehicle_updates += static_cast<uint64_t>(n);

  time_ms_ += dt_ms_;
  ++step_;
  handle_departures_from_road();
  enqueue_due(time_ms_);
  insert_waiting(map_next);
  cur_ = 1 - cur_;
  rebuild_active();
}

void Simulation::record_trip(uint32_t v, bool teleported) {
  ++counts_.arrived;
  TripRecord r;
  r.vehicle = v;
  r.depart = depart_time_[v];
  r.depart_delay = depart_time_[v] - demand_.depart[v];
  r.arrival = time();
  r.depart_lane = static_cast<uint32_t>(depart_lane_[v]);
  r.arrival_lane = static_cast<uint32_t>(lane_[v]);
  r.depart_pos = depart_pos_[v];
  r.depart_speed = depart_speed_[v];
  r.arrival_pos = pos_[v];
  r.arrival_speed = teleported ? 0.0f : speed_[v];
  r.route_length = route_length_[v];
  r.waiting_time = static_cast<double>(waiting_steps_[v]) * opt_.step_length;
  r.waiting_count = waiting_count_[v];
  r.time_loss = time_loss_[v];
  r.speed_factor = demand_.speed_factor[v];
  r.teleported = teleported;
  travel_time_sum_ += r.arrival - r.depart;
  finished_.push_back(r);
}

// Arrivals become trip records; teleporting vehicles re-enter at the next edge of their route.
void Simulation::handle_departures_from_road() {
  for (uint32_t v : active_) {
    if (status_[v] == kArrived && arrival_step_[v] == step_ && !teleport_pending_[v]) {
      record_trip(v, false);
    } else if (status_[v] == kTeleporting && !teleport_pending_[v]) {
      ++counts_.teleports;
      const uint32_t rp = route_pos_[v];
      if (rp + 1 >= demand_.route_length[v]) {
        // Teleported past the end of its route: the trip ends here.
        status_[v] = kArrived;
        arrival_step_[v] = step_;
        record_trip(v, true);
        continue;
      }
      route_pos_[v] = rp + 1;
      stopped_steps_[v] = 0;
      teleport_pending_[v] = 1;
      const uint32_t e = demand_.route_edges[demand_.route_begin[v] + rp + 1];
      auto& q = queue_[e];
      // Teleported vehicles go first: they have been on the road already.
      q.insert(q.begin() + queue_head_[e], v);
      if (queue_head_[e] + 1 == q.size()) queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), e), e);
      ++waiting_;
    }
  }
}

void Simulation::enqueue_due(int64_t until_ms) {
  const uint32_t nv = demand_.size();
  while (next_departure_ < nv && std::llround(demand_.depart[next_departure_] * 1000.0) <= until_ms) {
    const uint32_t v = next_departure_++;
    if (demand_.route_length[v] == 0) {
      status_[v] = kArrived;
      ++counts_.removed;
      continue;
    }
    const uint32_t e = demand_.route_edges[demand_.route_begin[v]];
    if (net_.edge_num_lanes[e] == 0) {
      status_[v] = kArrived;
      ++counts_.removed;
      continue;
    }
    auto& q = queue_[e];
    if (queue_head_[e] == q.size()) {
      q.clear();
      queue_head_[e] = 0;
      queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), e), e);
    }
    q.push_back(v);
    ++waiting_;
  }
}

void Simulation::insert_waiting(uint8_t* map) {
  inserted_now_.clear();
  std::vector<uint32_t>& still = scratch_;
  still.clear();
  for (uint32_t e : queued_edges_) {
    auto& q = queue_[e];
    while (queue_head_[e] < q.size() && try_insert(q[queue_head_[e]], map)) {
      inserted_now_.push_back(q[queue_head_[e]]);
      ++queue_head_[e];
      --waiting_;
    }
    if (queue_head_[e] < q.size()) still.push_back(e);
    else {
      q.clear();
      queue_head_[e] = 0;
    }
  }
  queued_edges_.assign(still.begin(), still.end());
}

bool Simulation::try_insert(uint32_t v, uint8_t* map) {
  const bool teleported = teleport_pending_[v] != 0;
  const uint32_t rp = route_pos_[v];
  const uint32_t e = demand_.route_edges[demand_.route_begin[v] + rp];
  const uint32_t first = net_.edge_first_lane[e], nlanes = net_.edge_num_lanes[e];
  const uint32_t type = demand_.vehicle_type[v];
  const VehicleTypes& t = demand_.types;
  const float length = t.length[type], min_gap = t.min_gap[type];
  const float dt = static_cast<float>(opt_.step_length);
  const NetView nv = engine_net_.view(net_);
  const TripView trips = trip_view();
  const uint32_t best = best_lanes(nv, trips, v, rp).mask[0];
  auto leads_on = [&](uint32_t l) { return (lane_bit(nv, l) & best) != 0; };

  // Candidate lanes in the order they are tried.
  uint32_t candidates[64];
  uint32_t nc = 0;
  const auto kind = teleported ? DepartLane::Best : static_cast<DepartLane>(demand_.depart_lane_kind[v]);
  switch (kind) {
    case DepartLane::Given:  // the demand builder maps SUMO's index to the rank among car lanes
      if (demand_.depart_lane[v] >= 0 && static_cast<uint32_t>(demand_.depart_lane[v]) < nlanes)
        candidates[nc++] = first + static_cast<uint32_t>(demand_.depart_lane[v]);
      break;
    case DepartLane::Random: {
      const uint64_t draw = rng_bits(opt_.seed ^ kDepartRngSalt, v, 0);
      candidates[nc++] = first + static_cast<uint32_t>(draw % nlanes);
      break;
    }
    case DepartLane::Best:  // as SUMO: only lanes that lead on along the route (wait for one otherwise)
      for (uint32_t l = first; l < first + nlanes && nc < 64; ++l)
        if (leads_on(l)) candidates[nc++] = l;
      if (!teleported) break;
      [[fallthrough]];
    case DepartLane::Free:
      for (uint32_t l = first; l < first + nlanes && nc < 64; ++l)
        if (leads_on(l)) candidates[nc++] = l;
      for (uint32_t l = first; l < first + nlanes && nc < 64; ++l)
        if (!leads_on(l)) candidates[nc++] = l;
      break;
    default:
      candidates[nc++] = first;
  }
  if (nc == 0) candidates[nc++] = first;

  for (uint32_t k = 0; k < nc; ++k) {
    const uint32_t l = candidates[k];
    const float lane_len = net_.lane_length[l];
    float pos = std::min(lane_len, length + 0.1f);
    if (!teleported) {
      switch (static_cast<DepartPos>(demand_.depart_pos_kind[v])) {
        case DepartPos::Given: {
          const float p = demand_.depart_pos[v];
          pos = std::clamp(p, 0.0f, lane_len);  // negative values were made absolute by the builder
          break;
        }
        case DepartPos::Random:
        case DepartPos::RandomFree:
          pos = std::min(lane_len, length + static_cast<float>(rng_uniform_double(opt_.seed ^ kDepartRngSalt, v, 1)) *
                                                std::max(0.0f, lane_len - length));
          break;
        default:
          break;
      }
    }
    const float v0 = desired_speed(net_.lane_speed[l], demand_.speed_factor[v], t.max_speed[type]);
    float speed = 0;
    bool speed_given = false;
    if (!teleported) {
      switch (static_cast<DepartSpeed>(demand_.depart_speed_kind[v])) {
        case DepartSpeed::Given:
          speed = demand_.depart_speed[v];
          speed_given = true;
          break;
        case DepartSpeed::Max:
        case DepartSpeed::Desired:
        case DepartSpeed::SpeedLimit:
        case DepartSpeed::Avg:
        case DepartSpeed::Last:
          speed = v0;
          break;
        case DepartSpeed::Random:
          speed = v0 * static_cast<float>(rng_uniform_double(opt_.seed ^ kDepartRngSalt, v, 2));
          break;
        default:
          break;
      }
    }
    // Body cells must be free.
    const int32_t rear_cell = static_cast<int32_t>(cell_of(nv, static_cast<int32_t>(l), pos - length));
    const int32_t front_cell = static_cast<int32_t>(cell_of(nv, static_cast<int32_t>(l), pos));
    if (first_occupied(map, nv, static_cast<int32_t>(l), rear_cell, front_cell) >= 0) continue;
    // Leader ahead: the inserted vehicle must be able to follow it safely.
    const int32_t cells = static_cast<int32_t>(lane_cells(nv, static_cast<int32_t>(l)));
    const IdmParams p{t.accel[type], t.decel[type], t.emergency_decel[type], t.tau[type], min_gap, t.delta[type]};
    const int32_t look = front_cell + 1 + static_cast<int32_t>(lookahead_distance(p, speed, dt) + min_gap);
    const int32_t ahead = front_cell + 1 < cells
                              ? first_occupied(map, nv, static_cast<int32_t>(l), front_cell + 1, std::min(look, cells - 1))
                              : -1;
    if (ahead >= 0) {
      const float gap = static_cast<float>(ahead) - pos;
      const float vl = decode_cell_speed(map[nv.lane_cell_begin[l] + static_cast<uint32_t>(ahead)]);
      if (gap < min_gap) continue;
      const float safe = safe_speed(gap, vl, max_emergency_decel_, p.decel, dt);
      if (speed > safe) {
        if (speed_given) continue;
        speed = safe;
      }
    }
    // Follower behind: it must be able to stay safe behind the new vehicle.
    if (rear_cell > 0) {
      const int32_t back = std::max(0, rear_cell - 1 - static_cast<int32_t>(lookahead_distance(p, net_.lane_speed[l], dt)));
      const int32_t lag = last_occupied(map, nv, static_cast<int32_t>(l), back, rear_cell - 1);
      if (lag >= 0) {
        const float gap = (pos - length) - static_cast<float>(lag + 1);
        const float vl = decode_cell_speed(map[nv.lane_cell_begin[l] + static_cast<uint32_t>(lag)]) + 0.25f;
        if (gap <= 0 || std::max(0.0f, vl - min_decel_ * dt) > safe_speed(gap, speed, max_emergency_decel_, min_decel_, dt))
          continue;
      }
    }
    // Insert.
    status_[v] = kRunning;
    lane_[v] = static_cast<int32_t>(l);
    pos_[v] = pos;
    speed_[v] = speed;
    prev_[v] = -1;
    prev2_[v] = -1;
    stopped_steps_[v] = 0;
    apply_footprint(map, nv, Footprint{static_cast<int32_t>(l), -1, -1, pos}, length, encode_cell_speed(speed));
    if (!teleported) {
      ++counts_.inserted;
      depart_delay_sum_ += time() - demand_.depart[v];
      depart_time_[v] = static_cast<float>(time());
      depart_lane_[v] = static_cast<int32_t>(l);
      depart_pos_[v] = pos;
      depart_speed_[v] = speed;
      ++lane_counters_.departed[l];
    } else {
      teleport_pending_[v] = 0;
      ++lane_counters_.entered[l];
    }
    return true;
  }
  return false;
}

void Simulation::rebuild_active() {
  // Keep running vehicles and those that left the road this step (their old footprint is cleared by
  // the next step's clear pass); add the newly inserted ones; ascending order keeps passes deterministic.
  // Member scratch buffers: fresh large vectors every step would cost page faults.
  std::vector<uint32_t>& next = scratch_;
  next.clear();
  for (uint32_t v : active_)
    if (status_[v] == kRunning || old_lane_[v] >= 0) next.push_back(v);
  std::sort(inserted_now_.begin(), inserted_now_.end());
  active_.clear();
  std::set_union(next.begin(), next.end(), inserted_now_.begin(), inserted_now_.end(), std::back_inserter(active_));
  inserted_now_.clear();
  uint64_t running = 0;
  for (uint32_t v : active_) running += status_[v] == kRunning;
  counts_.running = running;
  counts_.waiting = waiting_;
}

void Simulation::sample_fcd(FcdFrame& frame) const {
  frame.time = time();
  frame.vehicle.clear();
  frame.lane.clear();
  frame.pos.clear();
  frame.speed.clear();
  for (uint32_t v : active_) {
    if (status_[v] != kRunning) continue;
    frame.vehicle.push_back(v);
    frame.lane.push_back(static_cast<uint32_t>(lane_[v]));
    frame.pos.push_back(pos_[v]);
    frame.speed.push_back(speed_[v]);
  }
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
  double speed_sum = 0, rel_sum = 0;
  uint64_t running = 0, halting = 0;
  const VehicleTypes& t = demand_.types;
  for (uint32_t v : active_) {
    if (status_[v] != kRunning) continue;
    ++running;
    speed_sum += speed_[v];
    const float v0 = desired_speed(net_.lane_speed[lane_[v]], demand_.speed_factor[v], t.max_speed[demand_.vehicle_type[v]]);
    if (v0 > 0) rel_sum += speed_[v] / v0;
    if (speed_[v] < kHaltingSpeed) ++halting;
  }
  r.halting = halting;
  if (running > 0) {
    r.mean_speed = speed_sum / static_cast<double>(running);
    r.mean_speed_relative = rel_sum / static_cast<double>(running);
  }
  // As SUMO: meanWaitingTime is the mean insertion delay of the vehicles inserted so far, meanTravelTime
  // the mean trip duration of the vehicles that arrived so far.
  if (counts_.inserted > 0) r.mean_waiting_time = depart_delay_sum_ / static_cast<double>(counts_.inserted);
  if (counts_.arrived > 0) r.mean_travel_time = travel_time_sum_ / static_cast<double>(counts_.arrived);
  return r;
}

std::string Simulation::check_lane_map() const {
  std::vector<int64_t> owner(net_.num_cells(), -1);
  const NetView nv = engine_net_.view(net_);
  std::vector<uint8_t> expect(net_.num_cells(), 0);
  for (uint32_t v : active_) {
    if (status_[v] != kRunning) continue;
    const Footprint fp{lane_[v], prev_[v], prev2_[v], pos_[v]};
    std::vector<uint8_t> mark(net_.num_cells(), 0);
    apply_footprint(mark.data(), nv, fp, demand_.types.length[demand_.vehicle_type[v]], 1);
    for (uint64_t c = 0; c < mark.size(); ++c) {
      if (!mark[c]) continue;
      if (owner[c] >= 0)
        return "vehicles " + demand_.vehicle_id[static_cast<size_t>(owner[c])] + " and " + demand_.vehicle_id[v] +
               " share cell " + std::to_string(c) + " at t=" + std::to_string(time());
      owner[c] = v;
      expect[c] = 1;
    }
  }
  const std::vector<uint8_t>& map = map_[cur_];
  for (uint64_t c = 0; c < map.size(); ++c)
    if ((map[c] != 0) != (expect[c] != 0))
      return "lane map cell " + std::to_string(c) + (map[c] ? " marked but no vehicle there" : " unmarked under a vehicle") +
             " at t=" + std::to_string(time());
  return "";
}

}  // namespace lpsim

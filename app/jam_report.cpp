#include "app/jam_report.hpp"

#include <algorithm>
#include <unordered_map>
#include <utility>

#include "kernels/step_view.hpp"

namespace lpsim {

namespace {

// SUMO's halting threshold, the one tripinfo's waiting time uses.
constexpr float kStandingSpeed = 0.1f;
// A chain goes on through vehicles crawling in the queue (below 10 km/h, bounded by a leader or by the room
// on the next lane) up to what holds the queue's head; a faster vehicle ends it, as traffic that flows.
constexpr float kQueueSpeed = 10.0f / 3.6f;
constexpr double kTimeSlack = 1e-9;
constexpr size_t kReasons = kStop + 1;

bool held_by_vehicle(const JamVehicleState& s) { return s.reason == kLeader || s.reason == kNoRoom; }

bool has_blocker(const JamVehicleState& s) { return s.speed < kQueueSpeed && held_by_vehicle(s); }

}  // namespace

JamRecorder::Episode JamRecorder::started(double t) {
  Episode e;
  e.begin = t;
  e.reason_steps.assign(kReasons, 0);
  return e;
}

JamRecorder::JamRecorder(const std::string& path, double stop_time, const Network& net, Simulation& sim,
                         int64_t continue_at)
    : net_(net), writer_(path, net, sim.demand(), stop_time, continue_at), stop_time_(stop_time) {}

const JamRecorder::Snapshot* JamRecorder::in(const std::vector<Snapshot>& snap, uint32_t step,
                                             uint32_t v) const {
  return v < snap.size() && snap[v].step == step ? &snap[v] : nullptr;
}

void JamRecorder::take_snapshot(Simulation& sim) {
  ++step_;
  std::swap(cur_, prev_);
  sim.sample_fcd(frame_);
  const VehicleQuery q = sim.query();
  const size_t vehicles = sim.demand().size();  // trips may be added while it runs
  if (cur_.size() < vehicles) cur_.resize(vehicles);
  if (order_index_.size() < vehicles) order_index_.resize(vehicles);
  for (size_t i = 0; i < frame_.vehicle.size(); ++i) {
    const uint32_t v = frame_.vehicle[i];
    // Every vehicle's reason, as a moving vehicle may end a chain (the head of a slow queue).
    cur_[v] = Snapshot{
        step_, JamVehicleState{v, frame_.lane[i], frame_.pos[i], frame_.speed[i], q.limit_reason(v)}, -1};
  }
}

void JamRecorder::find_blockers(const Simulation& sim) {
  bool any = false;
  // Chains are read only from vehicles standing: without one, no blocker is needed.
  for (const uint32_t v : frame_.vehicle)
    any = any || (cur_[v].state.speed < kStandingSpeed && held_by_vehicle(cur_[v].state));
  if (!any) return;
  order_.clear();
  for (size_t i = 0; i < frame_.vehicle.size(); ++i)
    order_.push_back(OnLane{frame_.lane[i], frame_.pos[i], frame_.vehicle[i]});
  std::sort(order_.begin(), order_.end(), [](const OnLane& a, const OnLane& b) {
    return a.lane != b.lane ? a.lane < b.lane : a.pos != b.pos ? a.pos < b.pos : a.vehicle < b.vehicle;
  });
  for (size_t i = 0; i < order_.size(); ++i) order_index_[order_[i].vehicle] = static_cast<uint32_t>(i);
  const VehicleQuery q = sim.query();
  for (const uint32_t v : frame_.vehicle)
    if (has_blocker(cur_[v].state)) cur_[v].blocker = vehicle_ahead(sim.demand(), q, order_index_[v]);
}

int32_t JamRecorder::next_lane(const Demand& d, const VehicleQuery& q, uint32_t v, uint32_t lane) const {
  const uint32_t rp = q.route_pos(v);  // on an internal lane: the edge it came from
  if (rp + 1 >= d.route_length[v]) return -1;
  const uint32_t next_edge = d.route_edges[d.route_begin[v] + rp + 1];
  for (uint32_t c = net_.lane_conn_begin[lane]; c < net_.lane_conn_begin[lane + 1]; ++c)
    if (net_.conn_to_edge[c] == next_edge)
      return net_.conn_via_lane[c] >= 0 ? net_.conn_via_lane[c] : static_cast<int32_t>(net_.conn_to_lane[c]);
  return -1;
}

int64_t JamRecorder::vehicle_ahead(const Demand& d, const VehicleQuery& q, size_t at) const {
  const OnLane& me = order_[at];
  if (at + 1 < order_.size() && order_[at + 1].lane == me.lane) return order_[at + 1].vehicle;
  // Along its route: through the junction's internal lanes (at most a few) to the next edge's lane.
  int32_t lane = static_cast<int32_t>(me.lane);
  for (int hop = 0; hop < 4; ++hop) {
    lane = next_lane(d, q, me.vehicle, static_cast<uint32_t>(lane));
    if (lane < 0) return -1;
    const auto first = std::lower_bound(order_.begin(), order_.end(), static_cast<uint32_t>(lane),
                                        [](const OnLane& a, uint32_t l) { return a.lane < l; });
    if (first != order_.end() && first->lane == static_cast<uint32_t>(lane)) return first->vehicle;
    if (!net_.edge_is_internal[net_.lane_edge[static_cast<uint32_t>(lane)]]) return -1;
  }
  return -1;
}

JamRecord JamRecorder::record(uint32_t v, const Episode& e, double end, JamEnd how, TeleportCause cause,
                              const std::vector<Snapshot>& snap, uint32_t step, uint32_t lane,
                              double dt) const {
  JamRecord r;
  r.begin = e.begin;
  r.end = end;
  r.ended = how;
  r.teleport = cause;
  const Snapshot* s = in(snap, step, v);
  r.where = s != nullptr ? s->state : JamVehicleState{v, lane, 0, 0, 0};
  r.reason_seconds.resize(kReasons);
  for (size_t k = 0; k < kReasons && k < e.reason_steps.size(); ++k)
    r.reason_seconds[k] = static_cast<double>(e.reason_steps[k]) * dt;
  // Follow the blockers until one is not blocked by another, or the chain comes back: a deadlock cycle when
  // every vehicle in it stands (a ring of crawling vehicles still moves).
  std::unordered_map<uint32_t, int32_t> seen;  // vehicle -> its index in the chain
  auto standing_from = [&](size_t k) {
    return std::all_of(r.chain.begin() + static_cast<std::ptrdiff_t>(k), r.chain.end(),
                       [](const JamVehicleState& c) { return c.speed < kStandingSpeed; });
  };
  for (int64_t b = s != nullptr ? s->blocker : -1; b >= 0;) {
    const uint32_t bv = static_cast<uint32_t>(b);
    if (bv == v) {
      if (r.where.speed < kStandingSpeed && standing_from(0)) r.cycle_from = JamRecord::kSelf;
      break;
    }
    if (const auto it = seen.find(bv); it != seen.end()) {
      if (standing_from(static_cast<size_t>(it->second))) r.cycle_from = it->second;
      break;
    }
    const Snapshot* bs = in(snap, step, bv);
    if (bs == nullptr) break;
    seen.emplace(bv, static_cast<int32_t>(r.chain.size()));
    r.chain.push_back(bs->state);
    b = bs->blocker;
  }
  return r;
}

// An episode runs from the first step a vehicle is seen standing to the first it is not (or the run's
// end), so that its length is the standing steps before that: each is counted, with its reason, one step
// later, when the next snapshot shows whether the episode goes on.
void JamRecorder::count_last_step(Episode& e, uint32_t v) const {
  const Snapshot* s = in(prev_, step_ - 1, v);
  if (s == nullptr || e.reason_steps.empty()) return;
  ++e.reason_steps[s->state.reason < kReasons ? s->state.reason : 0];
}

JamRecord JamRecorder::with_held(const Episode& e, JamRecord r) {
  if (e.held_known) {
    r.where = e.held.where;
    r.chain = e.held.chain;
    r.cycle_from = e.held.cycle_from;
  }
  return r;
}

void JamRecorder::after_step(Simulation& sim) {
  take_snapshot(sim);
  find_blockers(sim);
  const double t = sim.time(), dt = sim.step_length();
  std::vector<std::pair<uint32_t, JamRecord>> ended;
  // A teleport is recorded however long the vehicle stood, from the last step it was on the road.
  for (const TeleportEvent& te : sim.teleport_events()) {
    const auto it = standing_.find(te.vehicle);
    Episode e = it != standing_.end() ? it->second : started(t);
    count_last_step(e, te.vehicle);
    ended.emplace_back(te.vehicle,
                       record(te.vehicle, e, t, JamEnd::Teleported, te.cause, prev_, step_ - 1, te.lane, dt));
    if (it != standing_.end()) standing_.erase(it);
  }
  for (auto it = standing_.begin(); it != standing_.end();) {
    count_last_step(it->second, it->first);
    Episode& e = it->second;
    const Snapshot* s = in(cur_, step_, it->first);
    if (s != nullptr && s->state.speed < kStandingSpeed) {
      // Standing now, the episode is at least t + dt - begin long: past the stop time, take what holds it.
      if (!e.held_known && t + dt - e.begin + kTimeSlack >= stop_time_) {
        e.held = record(it->first, e, t, JamEnd::RunEnded, TeleportCause::Jam, cur_, step_, 0, dt);
        e.held_known = true;
      }
      ++it;
      continue;
    }
    if (t - e.begin + kTimeSlack >= stop_time_)
      ended.emplace_back(it->first,
                         with_held(e, record(it->first, e, t, s != nullptr ? JamEnd::Moved : JamEnd::LeftRoad,
                                             TeleportCause::Jam, prev_, step_ - 1, 0, dt)));
    it = standing_.erase(it);
  }
  for (const uint32_t v : frame_.vehicle) {
    const JamVehicleState& s = cur_[v].state;
    if (s.speed >= kStandingSpeed || standing_.count(v) != 0) continue;
    standing_.emplace(v, started(t));
  }
  std::stable_sort(ended.begin(), ended.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [v, r] : ended) writer_.write(r);
}

void JamRecorder::finish(Simulation& sim) {
  const double t = sim.time();
  for (const auto& [v, e] : standing_)
    if (t - e.begin + kTimeSlack >= stop_time_)
      writer_.write(with_held(
          e, record(v, e, t, JamEnd::RunEnded, TeleportCause::Jam, cur_, step_, 0, sim.step_length())));
  standing_.clear();
  writer_.close();
}

}  // namespace lpsim

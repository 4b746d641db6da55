#include "engine/trip_ledger.hpp"

#include <algorithm>
#include <stdexcept>

namespace lpsim {

void TripLedger::resize(uint32_t n) {
  status_.resize(n, kPending);
  resume_rp_.resize(n, 0);
  resume_speed_.resize(n, 0);
  resume_lane_.resize(n, -1);
  resume_pos_.resize(n, -1);
  depart_time_.resize(n, 0);
  depart_pos_.resize(n, 0);
  depart_speed_.resize(n, 0);
  depart_lane_.resize(n, -1);
}

void TripLedger::departed(uint32_t v, double now, double depart_due, const SlotInit& init) {
  depart_delay_sum_ += now - depart_due;
  depart_time_[v] = static_cast<float>(now);
  depart_lane_[v] = init.lane;
  depart_pos_[v] = init.pos;
  depart_speed_[v] = init.speed;
}

void TripLedger::copy_trip(const TripLedger& from, uint32_t v) {
  status_[v] = from.status_[v];
  resume_rp_[v] = from.resume_rp_[v];
  resume_speed_[v] = from.resume_speed_[v];
  resume_lane_[v] = from.resume_lane_[v];
  resume_pos_[v] = from.resume_pos_[v];
  if (const TripCounters* c = from.carried(v))
    carried_[v] = *c;
  else
    carried_.erase(v);
  set_departure(v, from.departure(v));
}

void TripLedger::set_totals(double depart_delay_sum, double travel_time_sum,
                            std::vector<TripRecord> finished) {
  depart_delay_sum_ = depart_delay_sum;
  travel_time_sum_ = travel_time_sum;
  finished_ = std::move(finished);
}

void TripLedger::set_departure(uint32_t v, const DepartRecord& d) {
  depart_time_[v] = d.time;
  depart_pos_[v] = d.pos;
  depart_speed_[v] = d.speed;
  depart_lane_[v] = d.lane;
}

void TripLedger::teleporting(const VehicleEnd& e, uint32_t rp) {
  status_[e.vehicle] = kTeleporting;
  resume_rp_[e.vehicle] = rp;
  resume_speed_[e.vehicle] = 0;
  resume_lane_[e.vehicle] = -1;
  resume_pos_[e.vehicle] = -1;
  carried_[e.vehicle] = trip_counters(e);
}

void TripLedger::handed_out(uint32_t v, const TripCounters& counters) {
  status_[v] = kMigrated;
  carried_[v] = counters;
}

void TripLedger::handed_back(uint32_t v, uint32_t rp, int32_t lane, float pos_left, float pos_wanted,
                             float speed) {
  status_[v] = kTeleporting;  // off the road, queued to re-enter with what handed_out() kept
  resume_rp_[v] = rp;
  resume_speed_[v] = speed;
  resume_lane_[v] = lane;
  resume_pos_[v] = pos_wanted;
  // reentering() adds the position it enters at: the length then counts from where the other side stopped.
  carried_.at(v).route_length -= pos_left;
}

uint32_t TripLedger::reentering(SlotInit& init) {
  const auto c = carried_.find(init.vehicle);
  if (c == carried_.end()) throw std::logic_error("a vehicle re-enters that did not teleport");
  // On the road again: a part it leaves would otherwise still report it as teleporting (an unfinished trip).
  status_[init.vehicle] = kPending;
  init.route_length = c->second.route_length + (resume_pos_[init.vehicle] >= 0 ? init.pos : 0.0f);
  init.time_loss = c->second.time_loss;
  init.waiting_steps = c->second.waiting_steps;
  init.waiting_count = c->second.waiting_count;
  init.stop_steps = c->second.stop_steps;
  const uint32_t next_stop = c->second.next_stop;
  carried_.erase(c);
  return next_stop;
}

void TripLedger::ended(const VehicleEnd& e, bool teleported, double now, double depart_due,
                       double step_length, float speed_factor, bool removed) {
  const uint32_t v = e.vehicle;
  status_[v] = kArrived;
  TripRecord r;
  r.vehicle = v;
  r.depart = depart_time_[v];
  r.depart_delay = depart_time_[v] - depart_due;
  r.arrival = now;
  r.depart_lane = static_cast<uint32_t>(depart_lane_[v]);
  r.arrival_lane = static_cast<uint32_t>(e.lane);
  r.depart_pos = depart_pos_[v];
  r.depart_speed = depart_speed_[v];
  r.arrival_pos = e.pos;
  r.arrival_speed = teleported ? 0.0f : e.speed;
  r.route_length = e.route_length;
  r.waiting_time = static_cast<double>(e.waiting_steps) * step_length;
  r.waiting_count = e.waiting_count;
  r.stop_time = static_cast<double>(e.stop_steps) * step_length;
  r.time_loss = e.time_loss;
  r.speed_factor = speed_factor;
  r.teleported = teleported;
  r.removed = removed;
  travel_time_sum_ += r.arrival - r.depart;
  finished_.push_back(r);
  // The record carries the departure on; the account keeps only that the trip ended, so that a saved state
  // holds nothing of the trips that ended but their status.
  set_departure(v, DepartRecord{});
}

TripCounters TripLedger::drop_carried(uint32_t v) {
  TripCounters c;
  if (const auto it = carried_.find(v); it != carried_.end()) {
    c = it->second;
    carried_.erase(it);
  }
  return c;
}

std::vector<TripRecord> TripLedger::take_finished() {
  std::vector<TripRecord> out;
  out.swap(finished_);
  // A step ends its trips in vehicle order; those a command removed between steps come in the commands'.
  std::sort(out.begin(), out.end(), [](const TripRecord& a, const TripRecord& b) {
    return a.arrival != b.arrival ? a.arrival < b.arrival : a.vehicle < b.vehicle;
  });
  return out;
}

}  // namespace lpsim

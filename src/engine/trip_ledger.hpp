#pragma once
// The host's account of every trip, on the road or off it: its status while it holds no slot (pending,
// teleporting to re-enter, arrived or removed), where a teleported vehicle re-enters and the trip counters it
// carries over the teleport, its departure, and the trip records of those that ended.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "engine/insertion_queues.hpp"
#include "engine/samples.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

/// Where and when a vehicle entered the road (its trip record's depart fields): what travels with a vehicle
/// that drives into another part of a partitioned run.
struct DepartRecord {
  float time = 0, pos = 0, speed = 0;
  int32_t lane = -1;
};

/// A trip's counters, summed over the time it spent on the road so far (what a vehicle carries over a
/// teleport, or out to a co-simulated SUMO and back).
struct TripCounters {
  float route_length = 0, time_loss = 0;
  uint32_t waiting_steps = 0, waiting_count = 0, next_stop = 0, stop_steps = 0;
};

/// The counters a vehicle that leaves the road carries on.
inline TripCounters trip_counters(const VehicleEnd& e) {
  return TripCounters{e.route_length,  e.time_loss, e.waiting_steps,
                      e.waiting_count, e.next_stop, e.stop_steps};
}

class TripLedger {
 public:
  /// Room for trips [0, n) (the trip table grows during a run); new trips are pending.
  void resize(uint32_t n);

  uint8_t status(uint32_t v) const { return status_[v]; }
  void set_status(uint32_t v, uint8_t s) { status_[v] = s; }
  uint32_t resume_route_pos(uint32_t v) const { return resume_rp_[v]; }
  void set_resume_route_pos(uint32_t v, uint32_t rp) { resume_rp_[v] = rp; }
  /// Where and how each re-entering trip asks to enter (after a teleport: any best lane, its start,
  /// standing).
  ReentryWants reentry_wants() const {
    return ReentryWants{resume_rp_.data(), resume_lane_.data(), resume_pos_.data(), resume_speed_.data()};
  }

  /// Vehicle v, due at `depart_due` (s), was inserted at time `now` where `init` says.
  void departed(uint32_t v, double now, double depart_due, const SlotInit& init);
  /// A teleporting vehicle waits to re-enter at route position `rp`, carrying the counters of `end`.
  void teleporting(const VehicleEnd& end, uint32_t rp);
  /// A teleported or handed-back vehicle re-enters: `init` takes the counters it carried. Returns the first
  /// of its scheduled stops it had not made.
  uint32_t reentering(SlotInit& init);
  /// Vehicle v left for another simulator with `counters` (status kMigrated).
  void handed_out(uint32_t v, const TripCounters& counters);
  /// A handed-out vehicle comes back to re-enter at route position `rp` on `lane` (-1: any best lane) with
  /// its front at `pos_wanted` (-1: the lane start), asking for `speed`, with the counters it left with. The
  /// other simulator reports its own piece, which ends at `pos_left`: the route length it drives in LPSim
  /// counts from there, wherever it re-enters.
  void handed_back(uint32_t v, uint32_t rp, int32_t lane, float pos_left, float pos_wanted, float speed);
  /// The counters a teleporting or handed-out vehicle carries (null: none).
  const TripCounters* carried(uint32_t v) const {
    const auto c = carried_.find(v);
    return c == carried_.end() ? nullptr : &c->second;
  }

  DepartRecord departure(uint32_t v) const {
    return DepartRecord{depart_time_[v], depart_pos_[v], depart_speed_[v], depart_lane_[v]};
  }
  void set_departure(uint32_t v, const DepartRecord& d);

  /// A trip ended at time `now` (`removed`: by a remove command): its record joins those taken by
  /// take_finished(), which carries its departure on (departure() is then none).
  void ended(const VehicleEnd& end, bool teleported, double now, double depart_due, double step_length,
             float speed_factor, bool removed = false);
  /// A teleporting vehicle's trip ends before it re-entered: its carried counters leave the account.
  TripCounters drop_carried(uint32_t v);
  std::vector<TripRecord> take_finished();

  double depart_delay_sum() const { return depart_delay_sum_; }
  double travel_time_sum() const { return travel_time_sum_; }

  // --- A partitioned run's state re-cut for other parts (state_recut.hpp). ---
  /// Trips [0, size()).
  uint32_t size() const { return static_cast<uint32_t>(status_.size()); }
  /// Trip v's whole account (status, re-entry, carried counters, departure) as `from` has it.
  void copy_trip(const TripLedger& from, uint32_t v);
  /// The sums and the records of ended trips not yet taken, as a run's totals.
  void set_totals(double depart_delay_sum, double travel_time_sum, std::vector<TripRecord> finished);
  const std::vector<TripRecord>& finished() const { return finished_; }

  template <class A>
  void visit_state(A& a) {
    // Per trip, mostly the values of trips not departed yet (zero, but the positions' and lanes' -1).
    a.sparse(status_);
    a.sparse(resume_rp_);
    a.sparse(resume_speed_);
    a.sparse(resume_pos_, -1.0f);
    a.sparse(resume_lane_, int32_t{-1});
    a(carried_);
    a.sparse(depart_time_);
    a.sparse(depart_pos_);
    a.sparse(depart_speed_);
    a.sparse(depart_lane_, int32_t{-1});
    a(finished_);
    a(depart_delay_sum_);
    a(travel_time_sum_);
  }

 private:
  std::vector<uint8_t> status_;
  std::vector<uint32_t> resume_rp_;
  std::vector<float> resume_speed_, resume_pos_;
  std::vector<int32_t> resume_lane_;
  std::unordered_map<uint32_t, TripCounters> carried_;
  // Departure records for tripinfo.
  std::vector<float> depart_time_, depart_pos_, depart_speed_;
  std::vector<int32_t> depart_lane_;
  std::vector<TripRecord> finished_;
  double depart_delay_sum_ = 0, travel_time_sum_ = 0;
};

}  // namespace lpsim

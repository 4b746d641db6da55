#pragma once
// The recorder behind `lpsim run --jam-report FILE`: after each step it reads the Simulation's state (never
// changing it) and writes one record for every teleport and every episode of a vehicle standing (speed
// < 0.1 m/s) at least the stop time: where it stood, what bounded its speed (the plan's StopReason), and for
// a leader or no-room reason the chain of vehicles blocking it, a chain that comes back to one of its own
// vehicles being a deadlock cycle. A Run without the option holds no recorder and does no work for it.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "converters/jam_report_writer.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

class JamRecorder {
 public:
  /// Opens the report at `path` (with `continue_at` >= 0 continues the one a saved run left there); net and
  /// the simulation's demand must outlive the recorder.
  JamRecorder(const std::string& path, double stop_time, const Network& net, Simulation& sim,
              int64_t continue_at = -1);

  /// Reads the state after a step: ends the episodes of vehicles that moved, left or teleported (a record
  /// for each teleport and each episode of at least the stop time), starts those of vehicles now standing.
  void after_step(Simulation& sim);
  /// Records the episodes still going on (as running at the end) and closes the file.
  void finish(Simulation& sim);
  void flush() { writer_.flush(); }
  /// The report handed to its file: where a resumed run continues it.
  uint64_t continue_point() { return writer_.continue_point(); }
  /// A checkpoint's share (between steps): the last step's snapshot of the running vehicles (the next step
  /// ends episodes from it) and the episodes going on.
  template <class A>
  void visit_state(A& a);

 private:
  // A running vehicle in one step's snapshot, and the vehicle blocking it (-1: none, or not asked for).
  struct Snapshot {
    uint32_t step = ~0u;  // the snapshot it belongs to (entries of other steps are stale)
    JamVehicleState state;
    int64_t blocker = -1;
  };
  struct Episode {
    double begin = 0;
    std::vector<uint32_t> reason_steps;  // steps standing per StopReason
    // Where it stood and what held it in the step its standing reached the stop time: the last standing
    // step would show every queue at the moment it is released, its leader already moving.
    bool held_known = false;
    JamRecord held;

    template <class A>
    void visit_state(A& a) {
      a(begin);
      a(reason_steps);
      a(held_known);
      a(held);
    }
  };

  static Episode started(double t);
  void take_snapshot(Simulation& sim);
  /// `r` with where the vehicle stood and what held it taken from the step it had stood the stop time.
  static JamRecord with_held(const Episode& e, JamRecord r);
  void count_last_step(Episode& e, uint32_t v) const;
  void find_blockers(const Simulation& sim);
  /// The first vehicle ahead of the running vehicle `at` (index into order_): on its lane, else the first
  /// on the lane it enters next along its route; -1 if none.
  int64_t vehicle_ahead(const Demand& d, const VehicleQuery& q, size_t at) const;
  /// The lane after `lane` along vehicle v's route (its connection's internal lane, else its target), or
  /// -1 when the lane leads nowhere along it.
  int32_t next_lane(const Demand& d, const VehicleQuery& q, uint32_t v, uint32_t lane) const;
  const Snapshot* in(const std::vector<Snapshot>& snap, uint32_t step, uint32_t v) const;
  /// The record of vehicle v's episode `e`, ended at `end`, from snapshot `snap` of step `step` (the last
  /// one it stood in); `lane` where that snapshot lacks it (a teleport's lane).
  JamRecord record(uint32_t v, const Episode& e, double end, JamEnd how, TeleportCause cause,
                   const std::vector<Snapshot>& snap, uint32_t step, uint32_t lane, double dt) const;

  const Network& net_;
  JamReportWriter writer_;
  double stop_time_;
  std::vector<Snapshot> cur_, prev_;  // by vehicle: this step's running vehicles, and the last step's
  uint32_t step_ = 0;                 // snapshots taken so far (cur_ holds step_, prev_ step_ - 1)
  // This step's running vehicles sorted by (lane, pos, vehicle): the vehicle ahead on a lane is the next
  // entry, the last one on a lane the first entry of it.
  struct OnLane {
    uint32_t lane;
    float pos;
    uint32_t vehicle;
  };
  std::vector<OnLane> order_;
  std::vector<uint32_t> order_index_;     // by vehicle: its entry in order_ (valid when cur_ is this step's)
  std::map<uint32_t, Episode> standing_;  // vehicles standing as of the last step, by vehicle
  FcdFrame frame_;                        // this step's running vehicles
};

template <class A>
void JamRecorder::visit_state(A& a) {
  a(step_);
  std::vector<uint32_t> vehicles;
  std::vector<JamVehicleState> states;
  std::vector<int64_t> blockers;
  std::vector<uint32_t> standing;
  std::vector<Episode> episodes;
  if constexpr (!A::kReads) {
    for (uint32_t v = 0; v < cur_.size(); ++v)
      if (cur_[v].step == step_)
        vehicles.push_back(v), states.push_back(cur_[v].state), blockers.push_back(cur_[v].blocker);
    for (const auto& [v, e] : standing_) standing.push_back(v), episodes.push_back(e);
  }
  a(vehicles);
  a(states);
  a(blockers);
  a(standing);
  a(episodes);
  if constexpr (A::kReads) {
    if (states.size() != vehicles.size() || blockers.size() != vehicles.size() ||
        episodes.size() != standing.size())
      a.fail("the jam report's lists differ in length");
    cur_.clear();
    prev_.clear();
    for (size_t i = 0; i < vehicles.size(); ++i) {
      if (vehicles[i] >= cur_.size()) cur_.resize(vehicles[i] + size_t{1});
      cur_[vehicles[i]] = Snapshot{step_, states[i], blockers[i]};
    }
    standing_.clear();
    for (size_t i = 0; i < standing.size(); ++i) standing_.emplace(standing[i], episodes[i]);
  }
}

}  // namespace lpsim

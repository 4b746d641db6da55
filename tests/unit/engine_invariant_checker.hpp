#pragma once
// Test support: checks the engine's invariants after every step of a run (used by the unit and the slow
// suites): vehicle accounting, the lane map (no shared cell, map equal to the vehicles' footprints), no
// vehicle entering a junction against a red light, moves only along connections, speeds and positions
// within bounds. Failures are reported through gtest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "app/simulation_options.hpp"
#include "converters/cli_options.hpp"
#include "engine/simulation.hpp"
#include "kernels/signal_state.hpp"

namespace lpsim::engine_test {

inline std::string scenarios_dir() { return LPSIM_SCENARIOS_DIR; }

inline Scenario load_sumo_scenario(const std::string& name, const std::vector<std::string>& extra = {}) {
  // Appended, not a chain of operator+: GCC 12 at -O1 warns falsely (-Warray-bounds) on that chain here.
  std::string cfg = scenarios_dir();
  cfg.append("/").append(name).append("/").append(name).append(".sumocfg");
  std::vector<std::string> args{"-c", cfg};
  args.insert(args.end(), extra.begin(), extra.end());
  return load_scenario(parse_cli_options(args));
}

inline Scenario load_csv_scenario() {
  const std::string dir = scenarios_dir() + "/lpsim_csv_small/";
  return load_scenario(parse_cli_options({"--lpsim-nodes", dir + "nodes.csv", "--lpsim-edges",
                                          dir + "edges.csv", "--lpsim-od", dir + "od.csv"}));
}

inline int64_t to_ms(double seconds) { return std::llround(seconds * 1000.0); }

// Relative and absolute slack on speed bounds: speeds are floats computed in several operations.
constexpr float kSpeedRelTol = 1e-4f;
constexpr float kSpeedAbsTol = 1e-3f;
constexpr float kPosTol = 1e-3f;

/// What the checker found over a run, besides failures: proof that the checks had something to check.
struct RunStats {
  uint64_t steps = 0;
  uint64_t lane_map_checks = 0;
  uint64_t junction_entries = 0;    // normal lane -> next edge, any connection
  uint64_t signalised_entries = 0;  // of those, through a connection with a signal
  uint64_t entries_on_yellow = 0;
  uint64_t lane_changes = 0;
  uint64_t teleport_jumps = 0;  // moves explained by a teleport
  uint64_t tail_lanes = 0;      // running vehicles seen with a tail on a lane behind their front's
  uint64_t trip_records = 0;
  float max_speed_over_new_lane = 0;  // max of speed / (limit of the lane the vehicle ends on x factor)
};

/// Checks every invariant between two consecutive states of a Simulation. Call before_step(), then
/// sim.step(), then after_step(). Failures are collected (the first few with full detail).
class InvariantChecker {
 public:
  /// lane_map_every: run check_lane_map() every that many steps. limit_on_entered_lane: also require the
  /// speed after a step to respect the limit of the lane the vehicle ends it on (see the disabled test).
  InvariantChecker(const Scenario& sc, Simulation& sim, uint32_t lane_map_every,
                   bool limit_on_entered_lane = false)
      : net_(sc.network),
        demand_(sim.demand()),
        sim_(sim),
        lane_map_every_(lane_map_every),
        limit_on_entered_lane_(limit_on_entered_lane),
        hops_(connection_hops(sc.network)) {
    grow();
    check_counts();
    check_lane_map();
  }

  void before_step() {
    grow();
    for (uint32_t v : sim_.active()) {
      status_[v] = sim_.query().status(v);
      lane_[v] = sim_.query().lane(v);
      pos_[v] = sim_.query().pos(v);
      speed_[v] = sim_.query().speed(v);
    }
    active_before_ = sim_.active();
    counts_before_ = sim_.counts();
  }

  void after_step() {
    ++stats_.steps;
    check_counts();
    if (stats_.steps % lane_map_every_ == 0) check_lane_map();
    check_trips();
    for (uint32_t v : sim_.active()) check_vehicle(v);
    // Vehicles that left active() this step must have arrived (or be queued after a teleport).
    for (uint32_t v : active_before_) {
      if (status_[v] != kRunning || std::binary_search(sim_.active().begin(), sim_.active().end(), v))
        continue;
      if (sim_.query().status(v) == kRunning) fail(v, "running but no longer in active()");
    }
  }

  /// Runs until finished() or `max_time` (s), checking after every step.
  void run_to_end(double max_time) {
    while (!sim_.finished() && sim_.time() < max_time) {
      before_step();
      sim_.step();
      after_step();
    }
  }

  void expect_no_failures(const std::string& what) const {
    std::ostringstream all;
    for (const auto& f : failures_) all << "  " << f << "\n";
    EXPECT_EQ(failure_count_, 0u) << what << ": " << failure_count_ << " invariant failures, first ones:\n"
                                  << all.str();
  }

  const RunStats& stats() const { return stats_; }
  uint64_t failure_count() const { return failure_count_; }
  /// Every trip record the run wrote (the checker takes them from the simulation after each step).
  const std::vector<TripRecord>& trips() const { return trips_; }

 private:
  // The simulation's trips grow when trips are added during the run.
  void grow() {
    const uint32_t nv = demand_.size();
    status_.resize(nv, kPending);
    lane_.resize(nv, -1);
    pos_.resize(nv, 0);
    speed_.resize(nv, 0);
    seen_trip_.resize(nv, 0);
  }

  void fail(uint32_t v, const std::string& what) {
    fail_text("vehicle " + demand_.vehicle_id[v] + ": " + what);
  }
  void fail_text(const std::string& what) {
    ++failure_count_;
    if (failures_.size() < 12) failures_.push_back("t=" + std::to_string(sim_.time()) + " " + what);
  }

  std::string lane_text(int32_t l) const { return l >= 0 ? net_.lane_id[static_cast<size_t>(l)] : "(none)"; }

  // Every loaded vehicle is in exactly one state: not yet due, waiting to be inserted (including a
  // teleported vehicle queued for re-insertion), running, arrived, or removed without insertion.
  // Derived from simulation.cpp: enqueue_due moves due vehicles into the insertion queues (waiting) or
  // removes them; try_insert makes them running; commit/handle_departures_from_road make them arrived or
  // queue them again after a teleport (status kTeleporting, counted in waiting, already inserted).
  void check_counts() {
    const Simulation::Counts& c = sim_.counts();
    const int64_t now = to_ms(sim_.time());
    uint64_t not_due = 0, running = 0, arrived = 0, pending = 0, teleporting = 0;
    for (uint32_t v = 0; v < demand_.size(); ++v) {
      if (to_ms(demand_.depart[v]) > now) ++not_due;
      switch (sim_.query().status(v)) {
        case kRunning:
          ++running;
          break;
        case kArrived:
          ++arrived;
          break;
        case kTeleporting:
          ++teleporting;
          break;
        default:
          ++pending;
      }
    }
    auto check = [&](bool ok, const std::string& what) {
      if (!ok) fail_text("counts: " + what);
    };
    check(c.loaded == demand_.size(),
          "loaded " + std::to_string(c.loaded) + " != vehicles " + std::to_string(demand_.size()));
    check(c.loaded == c.removed + not_due + c.waiting + c.running + c.arrived,
          "loaded " + std::to_string(c.loaded) + " != removed " + std::to_string(c.removed) + " + not due " +
              std::to_string(not_due) + " + waiting " + std::to_string(c.waiting) + " + running " +
              std::to_string(c.running) + " + arrived " + std::to_string(c.arrived));
    check(c.inserted == c.running + c.arrived + teleporting,
          "inserted " + std::to_string(c.inserted) + " != running " + std::to_string(c.running) +
              " + arrived " + std::to_string(c.arrived) + " + queued after teleport " +
              std::to_string(teleporting));
    check(running == c.running, "running " + std::to_string(c.running) + " but " + std::to_string(running) +
                                    " vehicles have status running");
    check(arrived == c.arrived + c.removed, "arrived " + std::to_string(c.arrived) + " + removed " +
                                                std::to_string(c.removed) + " but " +
                                                std::to_string(arrived) + " vehicles have status arrived");
    check(pending + teleporting == not_due + c.waiting,
          std::to_string(pending + teleporting) + " vehicles pending or queued but not due " +
              std::to_string(not_due) + " + waiting " + std::to_string(c.waiting));
    if (stats_.steps > 0) {
      const Simulation::Counts& b = counts_before_;
      check(c.arrived >= b.arrived && c.inserted >= b.inserted && c.removed >= b.removed &&
                c.teleports >= b.teleports,
            "a cumulative count decreased");
    }
  }

  void check_lane_map() {
    ++stats_.lane_map_checks;
    const std::string problem = sim_.check_lane_map();
    if (!problem.empty()) fail_text("lane map: " + problem);
  }

  void check_trips() {
    const uint64_t arrived_now = sim_.counts().arrived - counts_before_.arrived;
    const std::vector<TripRecord> trips = sim_.take_finished_trips();
    if (trips.size() != arrived_now)
      fail_text(std::to_string(trips.size()) + " trip records for " + std::to_string(arrived_now) +
                " arrivals");
    trips_.insert(trips_.end(), trips.begin(), trips.end());
    for (const TripRecord& r : trips) {
      ++stats_.trip_records;
      if (seen_trip_[r.vehicle]++) fail(r.vehicle, "second trip record");
      if (sim_.query().status(r.vehicle) != kArrived) fail(r.vehicle, "trip record but not arrived");
      if (std::fabs(r.arrival - sim_.time()) > 1e-9)
        fail(r.vehicle, "trip record with arrival " + std::to_string(r.arrival));
    }
  }

  float limit_on(uint32_t v, int32_t lane) const {
    return net_.lane_speed[static_cast<size_t>(lane)] * demand_.speed_factor[v];
  }

  bool internal(int32_t lane) const {
    return net_.edge_is_internal[net_.lane_edge[static_cast<size_t>(lane)]] != 0;
  }

  /// The connection leaving `from` whose first lane (its via lane, or its target lane when direct) is `to`.
  int32_t connection_between(int32_t from, int32_t to) const {
    for (uint32_t c = net_.lane_conn_begin[static_cast<size_t>(from)];
         c < net_.lane_conn_begin[static_cast<size_t>(from) + 1]; ++c) {
      const int32_t first =
          net_.conn_via_lane[c] >= 0 ? net_.conn_via_lane[c] : static_cast<int32_t>(net_.conn_to_lane[c]);
      if (first == to) return static_cast<int32_t>(c);
    }
    return -1;
  }

  /// Lanes entered from `from` in at most two hops along connections that end on `to` (the path of an
  /// arriving vehicle, whose tail lanes the engine does not update). Empty when there is none.
  std::vector<int32_t> search_path(int32_t from, int32_t to) const {
    auto next_lanes = [&](int32_t l) {
      std::vector<int32_t> out;
      for (uint32_t c = net_.lane_conn_begin[static_cast<size_t>(l)];
           c < net_.lane_conn_begin[static_cast<size_t>(l) + 1]; ++c)
        out.push_back(net_.conn_via_lane[c] >= 0 ? net_.conn_via_lane[c]
                                                 : static_cast<int32_t>(net_.conn_to_lane[c]));
      return out;
    };
    for (int32_t a : next_lanes(from)) {
      if (a == to) return {from, a};
      for (int32_t b : next_lanes(a))
        if (b == to) return {from, a, b};
    }
    return {};
  }

  void check_vehicle(uint32_t v) {
    const uint8_t st = sim_.query().status(v);
    const bool was_running =
        status_[v] == kRunning && std::binary_search(active_before_.begin(), active_before_.end(), v);
    if (st != kRunning && !(st == kArrived && was_running)) return;
    const int32_t lane = sim_.query().lane(v);
    const float pos = sim_.query().pos(v), speed = sim_.query().speed(v);
    if (lane < 0 || static_cast<uint32_t>(lane) >= net_.num_lanes()) {
      fail(v, "on no lane (" + std::to_string(lane) + ")");
      return;
    }
    const float len = net_.lane_length[static_cast<size_t>(lane)];
    if (st == kRunning) check_tail_lanes(v, lane);
    if (!(speed >= 0.0f)) fail(v, "negative speed " + std::to_string(speed));
    if (!(pos >= -kPosTol && pos <= len + kPosTol))
      fail(v, "pos " + std::to_string(pos) + " outside lane " + lane_text(lane) + " of length " +
                  std::to_string(len));
    stats_.max_speed_over_new_lane = std::max(stats_.max_speed_over_new_lane, speed / limit_on(v, lane));

    if (!was_running) {  // inserted this step (first time or after a teleport)
      const bool given = demand_.depart_speed_kind[v] == static_cast<uint8_t>(DepartSpeed::Given);
      if (!given && speed > limit_on(v, lane) * (1 + kSpeedRelTol) + kSpeedAbsTol)
        fail(v, "inserted at " + std::to_string(speed) + " m/s on " + lane_text(lane) + " (limit x factor " +
                    std::to_string(limit_on(v, lane)) + ")");
      return;
    }

    // A vehicle that teleported this step and re-entered at once was put on its next route edge without
    // driving there (possibly past a red light).
    const auto& jumps = sim_.teleports_of_last_step();
    if (std::any_of(jumps.begin(), jumps.end(), [v](const TeleportMove& m) { return m.vehicle == v; })) {
      ++stats_.teleport_jumps;
      return;
    }

    // The speed of a step is chosen on the lane the vehicle starts it on; a vehicle entering a slower lane
    // may carry more than that lane's limit into it (as in SUMO) but must not gain speed above it.
    const int32_t old_lane = lane_[v];
    const float bound = std::max(limit_on(v, old_lane), speed_[v]);
    if (speed > bound * (1 + kSpeedRelTol) + kSpeedAbsTol)
      fail(v, "speed " + std::to_string(speed) + " on " + lane_text(lane) + " from " +
                  std::to_string(speed_[v]) + " on " + lane_text(old_lane) + " (limit x factor " +
                  std::to_string(limit_on(v, old_lane)) + ")");

    if (limit_on_entered_lane_ && lane != old_lane &&
        speed > limit_on(v, lane) * (1 + kSpeedRelTol) + kSpeedAbsTol)
      fail(v, "entered " + lane_text(lane) + " (limit x factor " + std::to_string(limit_on(v, lane)) +
                  " m/s) at " + std::to_string(speed) + " m/s from " + lane_text(old_lane) + " at " +
                  std::to_string(pos_[v]) + " m, " + std::to_string(speed_[v]) + " m/s; now at " +
                  std::to_string(pos) + " m");

    if (lane == old_lane) {
      if (pos < pos_[v] - kPosTol)
        fail(v, "moved back on " + lane_text(lane) + " from " + std::to_string(pos_[v]) + " to " +
                    std::to_string(pos));
      return;
    }
    if (net_.lane_edge[static_cast<size_t>(lane)] == net_.lane_edge[static_cast<size_t>(old_lane)]) {
      ++stats_.lane_changes;
      if (internal(lane))
        fail(v, "lane change on internal lanes " + lane_text(old_lane) + " -> " + lane_text(lane));
      if (pos < pos_[v] - kPosTol)
        fail(v, "moved back changing lanes " + lane_text(old_lane) + " -> " + lane_text(lane));
      return;
    }
    check_path(v, old_lane, lane);
  }

  /// Edge `up` is edge `down`, or leads into it along one hop of a connection (from lane to internal lane,
  /// internal lane to lane, or lane to lane).
  bool one_hop_upstream(uint32_t up, uint32_t down) const {
    return up == down || std::binary_search(hops_.begin(), hops_.end(), uint64_t{up} << 32 | down);
  }

  /// The edge pairs one connection hop apart, for one_hop_upstream.
  static std::vector<uint64_t> connection_hops(const Network& net) {
    std::vector<uint64_t> hops;
    auto hop = [&](uint32_t a, uint32_t b) { hops.push_back(uint64_t{a} << 32 | b); };
    for (uint32_t c = 0; c < net.num_connections(); ++c) {
      const uint32_t from = net.lane_edge[net.conn_from_lane[c]], to = net.lane_edge[net.conn_to_lane[c]];
      hop(from, to);
      if (net.conn_via_lane[c] >= 0) {
        const uint32_t via = net.lane_edge[static_cast<uint32_t>(net.conn_via_lane[c])];
        hop(from, via);
        hop(via, to);
      }
    }
    std::sort(hops.begin(), hops.end());
    return hops;
  }

  // A running vehicle's tail lanes (prev, prev2), which its footprint covers where it reaches back, each lie
  // on the edge of the lane ahead of it or one connection hop upstream of it (after a lane change the tail
  // may stay behind the lane beside the new one).
  void check_tail_lanes(uint32_t v, int32_t lane) {
    const VehicleQuery q = sim_.query();
    const HostState& s = q.state();
    const int32_t k = q.slot(v);
    const int32_t prev = s.veh.prev[k], prev2 = s.veh.prev2[k];
    if (prev < 0) {
      if (prev2 >= 0) fail(v, "a second tail lane " + lane_text(prev2) + " without a first");
      return;
    }
    ++stats_.tail_lanes;
    auto edge = [&](int32_t l) { return net_.lane_edge[static_cast<size_t>(l)]; };
    if (!one_hop_upstream(edge(prev), edge(lane)))
      fail(v, "tail lane " + lane_text(prev) + " is not one hop behind " + lane_text(lane));
    if (prev2 >= 0 && !one_hop_upstream(edge(prev2), edge(prev)))
      fail(v, "tail lane " + lane_text(prev2) + " is not one hop behind " + lane_text(prev));
  }

  // The lanes driven this step, found by searching the connections (the tail lanes prev/prev2 say only where
  // the body lies, and an arriving vehicle's are not updated; the lane-map check covers the footprint).
  // Every hop must follow a connection, and every normal lane end crossed must not have been red.
  void check_path(uint32_t v, int32_t old_lane, int32_t lane) {
    const std::vector<int32_t> path = search_path(old_lane, lane);
    if (path.empty()) {
      // A teleported vehicle re-enters on the next edge of its route without driving there.
      if (sim_.counts().teleports > counts_before_.teleports && sim_.query().status(v) == kRunning) {
        ++stats_.teleport_jumps;
        return;
      }
      fail(v, "moved from " + lane_text(old_lane) + " to " + lane_text(lane) +
                  " along no connection (two hops at most)");
      return;
    }
    for (size_t k = 0; k + 1 < path.size(); ++k) {
      const int32_t from = path[k];
      if (internal(from)) continue;
      const int32_t c = connection_between(from, path[k + 1]);
      ++stats_.junction_entries;
      if (net_.conn_signal[static_cast<size_t>(c)] < 0) continue;
      ++stats_.signalised_entries;
      // step() sets the signals for the step's end time (as SUMO) before the passes read them;
      // link_state() after the step returns exactly that state (before the step it still shows the
      // previous step's).
      const char state = sim_.query(StateParts::Full).link_state(static_cast<uint32_t>(c));
      if (signal_is_yellow(state)) ++stats_.entries_on_yellow;
      if (signal_is_red(state))
        fail(v, "entered " + lane_text(path[k + 1]) + " from " + lane_text(from) + " at signal state '" +
                    state + "' (was at " + std::to_string(pos_[v]) + " m, " + std::to_string(speed_[v]) +
                    " m/s)");
    }
  }

  const Network& net_;
  const Demand& demand_;
  Simulation& sim_;
  uint32_t lane_map_every_;
  bool limit_on_entered_lane_;
  std::vector<uint8_t> status_;
  std::vector<int32_t> lane_;
  std::vector<float> pos_, speed_;
  std::vector<uint32_t> active_before_;
  std::vector<uint8_t> seen_trip_;
  std::vector<uint64_t> hops_;  // edge pairs (up << 32 | down) one connection hop apart, ascending
  std::vector<TripRecord> trips_;
  Simulation::Counts counts_before_;
  RunStats stats_;
  std::vector<std::string> failures_;
  uint64_t failure_count_ = 0;
};

struct RunResult {
  RunStats stats;
  Simulation::Counts counts;
  bool finished = false;
  uint64_t failures = 0;
};

inline RunResult run_checked(const Scenario& sc, const std::string& name, const SimulationOptions& options,
                             uint32_t lane_map_every, double max_time = 7200) {
  Simulation sim(sc.network, sc.demand, options);
  InvariantChecker checker(sc, sim, lane_map_every);
  checker.run_to_end(max_time);
  checker.expect_no_failures(name);
  return RunResult{checker.stats(), sim.counts(), sim.finished(), checker.failure_count()};
}

inline RunResult run_checked(const Scenario& sc, const std::string& name, int threads,
                             uint32_t lane_map_every, double max_time = 7200) {
  SimulationOptions options = simulation_options(sc.config);
  options.threads = threads;
  return run_checked(sc, name, options, lane_map_every, max_time);
}

inline void expect_all_arrived(const RunResult& r, const std::string& name) {
  EXPECT_TRUE(r.finished) << name << " not finished: running " << r.counts.running << ", waiting "
                          << r.counts.waiting;
  EXPECT_EQ(r.counts.arrived + r.counts.removed, r.counts.loaded) << name;
  EXPECT_EQ(r.counts.removed, 0u) << name;
  EXPECT_EQ(r.stats.trip_records, r.counts.arrived) << name;
  EXPECT_EQ(r.counts.inserted, r.counts.loaded) << name;
}

}  // namespace lpsim::engine_test

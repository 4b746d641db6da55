#pragma once
// Test support: a run of grid_tls with a driver's commands between steps (unit/command_drive.hpp) in one part
// or in three, on either backend, and what the tests compare (tests/unit/engine_commands_test.cpp,
// tests/gpu).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "unit/command_drive.hpp"
#include "unit/engine_invariant_checker.hpp"
#include "unit/trip_changes.hpp"

namespace lpsim::engine_test {

inline CommandRun run_with_removals(const Scenario& sc, SimulationOptions options, bool in_three_parts) {
  CommandRun out;
  std::unique_ptr<InProcessParts> others;
  if (in_three_parts) {
    others = std::make_unique<InProcessParts>(sc.network, sc.demand, options, three_parts(sc), 60);
    options = others->part0_options(options);
  }
  run_part0(others.get(), [&] {
    Simulation sim(sc.network, sc.demand, options);
    drive_removals(sim, sc, !in_three_parts, out);
  });
  EXPECT_TRUE(out.finished);
  EXPECT_GT(out.vehicles_at_removal, 10u);
  EXPECT_NE(out.junction_removed, 0u) << "no vehicle inside a junction";
  EXPECT_NE(out.running_removed, 0u) << "no vehicle driving";
  return out;
}

inline bool drives_after(const CommandRun& run, uint32_t v, double t) {
  for (size_t i = 0; i < run.fcd.size(); i += 5)
    if (run.fcd[i] > t && run.fcd[i + 1] == double(v)) return true;
  return false;
}

inline const TripRecord* record_of(const CommandRun& run, uint32_t v) {
  for (const TripRecord& r : run.trips)
    if (r.vehicle == v) return &r;
  return nullptr;
}

/// Steps `sim` (grid_tls) to step `steps`, with commands on the way: at step 60 six trips added (three due at
/// once, three at 153-155 s) and the last loaded trip removed before it is due; at step 70 a running
/// vehicle removed.
inline void drive_with_commands(Simulation& sim, uint32_t steps) {
  const Demand& d = sim.demand();
  while (sim.step_index() < steps) {
    if (sim.step_index() == 60) {
      CommandQueue queue;
      for (int k = 0; k < 6; ++k) {
        NewTrip t;
        t.id = "added_" + std::to_string(k);
        t.type = d.vehicle_type[k];
        t.route.assign(d.route_edges.begin() + d.route_begin[k],
                       d.route_edges.begin() + d.route_begin[k] + d.route_length[k]);
        t.depart = k < 3 ? sim.time() : 150.0 + k;  // some due after the save
        t.speed_factor = 0.95f;
        queue.push(VehicleCommand::add(t));
      }
      queue.push(VehicleCommand::remove(d.size() - 1));  // not due yet
      for (const CommandOutcome& o : sim.apply_commands(queue.take())) EXPECT_TRUE(o.done()) << o.error;
    }
    if (sim.step_index() == 70) {
      FcdFrame frame;
      sim.sample_fcd(frame);
      ASSERT_GE(frame.vehicle.size(), 2u);
      const CommandOutcome o = sim.apply_commands({VehicleCommand::remove(frame.vehicle[0])})[0];
      EXPECT_TRUE(o.done()) << o.error;
    }
    sim.step();
  }
}

/// One batch sees its own commands (its state is fetched once): a route given twice, then the vehicle
/// removed, then its route and its removal refused.
inline void expect_a_batch_sees_its_own_commands(const SimulationOptions& options) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  Simulation sim(sc.network, sc.demand, options);
  while (sim.time() < 100) sim.step();
  std::vector<uint32_t> route;
  const int64_t picked = pick_reroute(sim, sc.network, route);
  ASSERT_GE(picked, 0);
  const auto v = static_cast<uint32_t>(picked);
  const std::vector<CommandOutcome> o = sim.apply_commands(
      {VehicleCommand::set_route(v, route), VehicleCommand::set_route(v, route), VehicleCommand::remove(v),
       VehicleCommand::set_route(v, route), VehicleCommand::remove(v)});
  ASSERT_EQ(o.size(), 5u);
  for (size_t i = 0; i < 3; ++i) EXPECT_TRUE(o[i].done()) << i << ": " << o[i].error;
  EXPECT_NE(o[3].error.find("new route refused: its trip has ended"), std::string::npos) << o[3].error;
  EXPECT_NE(o[4].error.find("not removed: its trip has ended"), std::string::npos) << o[4].error;
  for (int k = 0; k < 5; ++k) {
    sim.step();
    EXPECT_EQ(sim.check_lane_map(), "");
  }
  EXPECT_EQ(sim.query().status(v), kArrived);  // its slot gone after the step that cleared it
}

/// The two runs alike: the same outcomes, FCD, trip records and counts.
inline void expect_same_command_run(const CommandRun& one, const CommandRun& other, const char* what) {
  EXPECT_EQ(other.errors, one.errors) << what;
  EXPECT_EQ(other.running_removed, one.running_removed) << what;
  EXPECT_EQ(other.junction_removed, one.junction_removed) << what;
  EXPECT_TRUE(other.fcd == one.fcd) << what << ": FCD differs";
  ASSERT_EQ(other.trips.size(), one.trips.size()) << what;
  for (size_t i = 0; i < one.trips.size(); ++i) {
    const TripRecord &a = one.trips[i], &b = other.trips[i];
    EXPECT_TRUE(a.vehicle == b.vehicle && a.arrival == b.arrival && a.arrival_lane == b.arrival_lane &&
                a.arrival_pos == b.arrival_pos && a.route_length == b.route_length &&
                a.removed == b.removed && a.time_loss == b.time_loss)
        << what << ": trip " << a.vehicle << " / " << b.vehicle << ": arrival " << a.arrival << " / "
        << b.arrival << ", lane " << a.arrival_lane << " / " << b.arrival_lane << ", pos " << a.arrival_pos
        << " / " << b.arrival_pos << ", removed " << a.removed << " / " << b.removed;
  }
  EXPECT_EQ(other.counts.cancelled, one.counts.cancelled) << what;
  EXPECT_EQ(other.counts.arrived, one.counts.arrived) << what;
  EXPECT_EQ(other.last_row.ended, one.last_row.ended) << what;
}

}  // namespace lpsim::engine_test

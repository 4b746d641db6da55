// A driver's commands between steps (engine/vehicle_commands.hpp): vehicles removed on the road, in an
// insertion queue and before they are due, trips added, refusals, and the same run in one part and in three.
#include <gtest/gtest.h>

#include <string>

#include "unit/command_run.hpp"

namespace lpsim::engine_test {
namespace {

TEST(EngineCommandsTest, RemovedVehiclesLeaveWhereTheyAreAndQueuedOnesNeverDepart) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const CommandRun run = run_with_removals(sc, simulation_options(sc.config), false);
  const uint32_t loaded = sc.demand.size();
  ASSERT_EQ(run.errors.size(), 13u);
  for (size_t i = 0; i < 11; ++i) EXPECT_EQ(run.errors[i], "") << "command " << i;
  EXPECT_NE(run.errors[11].find("not removed: its trip has ended"), std::string::npos) << run.errors[11];
  EXPECT_EQ(run.errors[12], "no vehicle " + std::to_string(loaded + 6));
  EXPECT_EQ(run.lane_map, "") << "the lane map holds exactly the vehicles on the road";

  // On the road: its trip ends there and then, marked removed, and it is gone from the next step on.
  for (const uint32_t v : {run.running_removed, run.junction_removed}) {
    const TripRecord* r = record_of(run, v);
    ASSERT_NE(r, nullptr) << v;
    EXPECT_TRUE(r->removed);
    EXPECT_FALSE(r->teleported);
    EXPECT_EQ(r->arrival, run.removed_at);
    EXPECT_GT(r->route_length, 0);
    EXPECT_FALSE(drives_after(run, v, run.removed_at));
  }
  EXPECT_GT(record_of(run, run.running_removed)->arrival_speed, 5.0f);
  const TripRecord* just_in = record_of(run, run.inserted_removed);
  ASSERT_NE(just_in, nullptr);
  EXPECT_TRUE(just_in->removed);
  EXPECT_EQ(just_in->depart, run.removed_at);
  EXPECT_EQ(just_in->arrival, run.removed_at);
  // Queued or not due: it never departs and leaves no trip record.
  for (const uint32_t v : {run.queued_removed, run.not_due_removed}) {
    EXPECT_EQ(record_of(run, v), nullptr) << v;
    EXPECT_FALSE(drives_after(run, v, 0)) << v;
  }
  // The other added trips drove; every trip is accounted for.
  for (int k = 1; k < 5; ++k) EXPECT_NE(record_of(run, loaded + static_cast<uint32_t>(k)), nullptr) << k;
  EXPECT_EQ(run.counts.loaded, loaded + 6);
  EXPECT_EQ(run.counts.cancelled, 2u);
  EXPECT_EQ(run.counts.inserted, loaded + 6 - 2);
  EXPECT_EQ(run.counts.arrived, run.trips.size());
  EXPECT_EQ(run.counts.arrived + run.counts.cancelled, loaded + 6);
  EXPECT_EQ(run.last_row.ended, loaded + 6);
  EXPECT_EQ(run.last_row.arrived, run.counts.arrived);
}

TEST(EngineCommandsTest, ABatchSeesItsOwnCommands) {
  expect_a_batch_sees_its_own_commands(simulation_options(load_sumo_scenario("grid_tls").config));
}

TEST(EngineCommandsTest, ThreePartsRunTheCommandsAsOnePart) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  EXPECT_GE(trip_from_a_shared_edge(sc), 0);
  expect_same_command_run(run_with_removals(sc, simulation_options(sc.config), false),
                          run_with_removals(sc, simulation_options(sc.config), true), "3 parts vs 1");
}

TEST(EngineCommandsTest, ThreadCountsGiveTheSameRun) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  SimulationOptions two_threads = simulation_options(sc.config);
  two_threads.threads = 2;
  expect_same_command_run(run_with_removals(sc, simulation_options(sc.config), false),
                          run_with_removals(sc, two_threads, false), "2 threads vs 1");
}

}  // namespace
}  // namespace lpsim::engine_test

// Engine invariants on every bundled scenario, checked after every step of a whole run (see
// engine_invariant_checker.hpp for what is checked).
#include <gtest/gtest.h>

#include <string>

#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

TEST(EngineInvariantsTest, GridTlsEveryStep) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const RunResult r = run_checked(sc, "grid_tls", 1, 1);
  expect_all_arrived(r, "grid_tls");
  EXPECT_EQ(r.counts.loaded, 1000u);
  EXPECT_EQ(r.stats.lane_map_checks, r.stats.steps + 1);
  // Every junction is signalised: the red-light check must have seen many entries, some on yellow.
  EXPECT_GT(r.stats.signalised_entries, 1000u);
  EXPECT_EQ(r.stats.signalised_entries, r.stats.junction_entries);
  EXPECT_GT(r.stats.lane_changes, 0u);
  EXPECT_GT(r.stats.tail_lanes, 1000u);  // vehicles crossing junctions, their tails checked
}

TEST(EngineInvariantsTest, RandomNetEveryStep) {
  const Scenario sc = load_sumo_scenario("random_net");
  const RunResult r = run_checked(sc, "random_net", 1, 1);
  expect_all_arrived(r, "random_net");
  EXPECT_EQ(r.counts.loaded, 300u);
  EXPECT_GT(r.stats.junction_entries, r.stats.signalised_entries);  // mostly unsignalised junctions
  EXPECT_GT(r.stats.signalised_entries, 0u);
}

TEST(EngineInvariantsTest, FlowsEveryStep) {
  const Scenario sc = load_sumo_scenario("flows");
  const RunResult r = run_checked(sc, "flows", 1, 1);
  expect_all_arrived(r, "flows");
  EXPECT_GT(r.counts.loaded, 200u);
}

TEST(EngineInvariantsTest, LpsimCsvSmallEveryStep) {
  const Scenario sc = load_csv_scenario();
  const RunResult r = run_checked(sc, "lpsim_csv_small", 1, 1);
  expect_all_arrived(r, "lpsim_csv_small");
  EXPECT_EQ(r.counts.loaded, 8u);
  EXPECT_GT(r.stats.signalised_entries, 0u);  // the cross at osmid 1001 is signalised
}

// A vehicle never enters a slower lane faster than that lane's limit (x its speed factor, as SUMO's
// freeSpeed keeps it short of the boundary until it is slow enough).
TEST(EngineInvariantsTest, SpeedWithinLimitOfEnteredLane) {
  for (const std::string name : {"grid_tls", "random_net", "flows"}) {
    const Scenario sc = load_sumo_scenario(name);
    Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
    InvariantChecker checker(sc, sim, 50, true);
    checker.run_to_end(7200);
    checker.expect_no_failures(name + " (limit of the entered lane)");
  }
}

// A short time-to-teleport: stuck vehicles jump to their next route edge and re-enter from the queue there.
TEST(EngineInvariantsTest, GridTlsWithTeleportsEveryStep) {
  const Scenario sc = load_sumo_scenario("grid_tls", {"--time-to-teleport", "20"});
  const RunResult r = run_checked(sc, "grid_tls with teleports", 1, 1);
  EXPECT_GT(r.counts.teleports, 100u);
  EXPECT_GT(r.stats.teleport_jumps, 0u);
  EXPECT_EQ(r.counts.arrived + r.counts.removed, r.counts.loaded);
}

TEST(EngineInvariantsTest, GridTlsHalfSecondSteps) {
  const Scenario sc = load_sumo_scenario("grid_tls", {"--step-length", "0.5"});
  ASSERT_EQ(sc.config.step_length, 0.5);
  const RunResult r = run_checked(sc, "grid_tls step 0.5", 1, 1);
  expect_all_arrived(r, "grid_tls step 0.5");
  EXPECT_GT(r.stats.signalised_entries, 1000u);
}

}  // namespace
}  // namespace lpsim::engine_test

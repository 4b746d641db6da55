// Renumbering the slots of the vehicles on the road by lane (SimulationOptions::slot_sort_interval) changes
// only where a vehicle's state is stored: every step's positions, the trip records, the summary and the lane
// counters equal those of a run that never renumbers, and the per-vehicle queries follow the vehicles.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "unit/run_trace.hpp"

namespace lpsim::engine_test {
namespace {

Trace run(const Scenario& sc, uint32_t interval) {
  SimulationOptions o = simulation_options(sc.config);
  o.slot_sort_interval = interval;
  return run_trace(sc, o);
}

void check(const std::string& name, const std::vector<std::string>& args, bool teleports) {
  const Scenario sc = load_sumo_scenario(name, args);
  const Trace never = run(sc, 0);
  ASSERT_GT(never.trips.size(), 0u);
  ASSERT_GT(never.max_active, 20u) << name << ": too few vehicles at once for renumbering to matter";
  if (teleports) {
    ASSERT_GT(never.teleports, 10u) << name << ": the vehicles holding two slots after a teleport";
  }
  expect_same_trace(never, run(sc, 1), name + ": renumbered every step vs never");
  expect_same_trace(never, run(sc, 5), name + ": renumbered every 5th step vs never");
}

TEST(SlotSortTest, GridTlsResultsDoNotDependOnSlotNumbers) { check("grid_tls", {}, false); }

TEST(SlotSortTest, GridTlsWithTeleportsResultsDoNotDependOnSlotNumbers) {
  check("grid_tls", {"--time-to-teleport", "20"}, true);
}

TEST(SlotSortTest, FlowsResultsDoNotDependOnSlotNumbers) { check("flows", {}, false); }

}  // namespace
}  // namespace lpsim::engine_test

// Slots of the vehicles on the road: the lowest free one is taken first, and a run's slot columns stay as
// long as the most vehicles on the road at once, not the whole demand.
#include "engine/slot_pool.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

TEST(SlotPoolTest, TakesTheLowestFreeSlot) {
  SlotPool pool;
  EXPECT_EQ(pool.take(), 0u);
  EXPECT_EQ(pool.take(), 1u);
  EXPECT_EQ(pool.take(), 2u);
  pool.release(2);
  pool.release(0);
  EXPECT_EQ(pool.take(), 0u);
  EXPECT_EQ(pool.take(), 2u);
  EXPECT_EQ(pool.take(), 3u);
  EXPECT_EQ(pool.size(), 4u);
}

// After the slots in use were renumbered 0..n-1 (Simulation::sort_slots), the next one taken is n; the peak
// keeps the most ever handed out.
TEST(SlotPoolTest, ResetLeavesTheFirstSlotsInUse) {
  SlotPool pool;
  for (int k = 0; k < 5; ++k) pool.take();
  pool.release(1);
  pool.release(3);
  pool.reset(3);
  EXPECT_EQ(pool.size(), 3u);
  EXPECT_EQ(pool.take(), 3u);
  EXPECT_EQ(pool.take(), 4u);
  EXPECT_EQ(pool.take(), 5u);
  EXPECT_EQ(pool.size(), 6u);
  EXPECT_EQ(pool.peak(), 6u);
  pool.reset(2);
  EXPECT_EQ(pool.size(), 2u);
  EXPECT_EQ(pool.peak(), 6u);
}

// A vehicle holds its slot while on the road and for the step after it leaves (its footprint is cleared
// then), so at an insertion the slots in use are those of the vehicles running now, of those that left in
// this step and the step before, and of the ones being inserted.
TEST(SlotPoolTest, SlotsAreRecycledAsVehiclesLeave) {
  for (const std::string name : {"grid_tls", "flows"}) {
    const Scenario sc = load_sumo_scenario(name);
    Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
    uint64_t bound = sim.counts().running, peak_running = sim.counts().running, ends_before = 0;
    while (!sim.finished() && sim.time() < 7200) {
      const Simulation::Counts before = sim.counts();
      sim.step();
      const Simulation::Counts& c = sim.counts();
      const uint64_t ends = (c.arrived - before.arrived) + (c.teleports - before.teleports);
      bound = std::max(bound, c.running + ends + ends_before);
      peak_running = std::max(peak_running, c.running);
      ends_before = ends;
    }
    EXPECT_TRUE(sim.finished()) << name;
    EXPECT_GE(sim.slots_used(), peak_running) << name;
    EXPECT_LE(sim.slots_used(), bound) << name;
    EXPECT_LT(sim.slots_used(), sc.demand.size() / 2) << name << ": slots must be reused";
  }
}

}  // namespace
}  // namespace lpsim::engine_test

#pragma once
// Test support: claims and merge requests carry the step in 24 bits (kernels/step_view.hpp,
// step_marks_wrap). A run past 2^24 steps must not let the marks of the steps before the wrap outrank its
// own, or vehicles stop entering the lanes claimed then. A state of grid_tls moved to 40 steps before the
// wrap goes on as one moved elsewhere: the same lane entries within 5 % (lane changes draw on the step
// number, so the runs differ a little). Without the wrap's zeroing the entries fall by 60 %.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <vector>

#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {

inline void expect_lane_entries_across_the_step_wrap(const SimulationOptions& options) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  Simulation saved(sc.network, sc.demand, options);
  while (saved.time() < 120) saved.step();
  const std::vector<uint8_t> state = saved.save_state();
  // The first part's state follows the parts' count, the partition digest and its length; its clock, then
  // its step, lead it.
  constexpr size_t kStepAt = sizeof(uint32_t) + sizeof(uint64_t) + sizeof(uint64_t) + sizeof(int64_t);
  uint32_t step = 0;
  std::memcpy(&step, state.data() + kStepAt, sizeof step);
  ASSERT_EQ(step, saved.step_index());
  // Lane entries (a vehicle's front on a lane it was not on the step before) in 200 steps from `first_step`.
  auto entries_from = [&](uint32_t first_step) {
    std::vector<uint8_t> moved = state;
    std::memcpy(moved.data() + kStepAt, &first_step, sizeof first_step);
    Simulation sim(sc.network, sc.demand, options);
    sim.load_state(moved, "moved state");
    std::map<uint32_t, uint32_t> lane_of;
    int entries = 0;
    FcdFrame frame;
    for (int k = 0; k < 200; ++k) {
      sim.step();
      sim.sample_fcd(frame);
      for (size_t i = 0; i < frame.vehicle.size(); ++i) {
        auto [it, fresh] = lane_of.emplace(frame.vehicle[i], frame.lane[i]);
        if (!fresh && it->second != frame.lane[i]) ++entries, it->second = frame.lane[i];
      }
    }
    EXPECT_EQ(sim.check_lane_map(), "");
    return entries;
  };
  const int far = entries_from(1u << 23);
  const int across = entries_from((1u << 24) - 40);
  EXPECT_GT(far, 500);
  EXPECT_NEAR(across, far, far / 20) << "vehicles stopped entering lanes after the wrap";
}

}  // namespace lpsim::engine_test

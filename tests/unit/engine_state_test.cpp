// Checkpoints of the engine: a Simulation saved between two steps and loaded into a fresh one made from the
// same scenario steps on exactly as the saved one does, and saving changes nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "app/simulation_options.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

// Every value the outputs read, written exactly (floats as hex), after each step from now to the end.
std::string trace_to_end(Simulation& sim, uint32_t max_steps) {
  std::string out;
  char buf[256];
  FcdFrame frame;
  for (uint32_t n = 0; n < max_steps && !sim.finished(); ++n) {
    sim.step();
    sim.sample_fcd(frame);
    std::snprintf(buf, sizeof buf, "t %a\n", frame.time);
    out += buf;
    for (size_t i = 0; i < frame.vehicle.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%u %u %a %a\n", frame.vehicle[i], frame.lane[i],
                    static_cast<double>(frame.pos[i]), static_cast<double>(frame.speed[i]));
      out += buf;
    }
    const SummaryRow r = sim.summary_row();
    std::snprintf(buf, sizeof buf, "summary %llu %llu %llu %llu %llu %llu %a %a %a %a\n",
                  static_cast<unsigned long long>(r.inserted), static_cast<unsigned long long>(r.running),
                  static_cast<unsigned long long>(r.waiting), static_cast<unsigned long long>(r.arrived),
                  static_cast<unsigned long long>(r.teleports), static_cast<unsigned long long>(r.halting),
                  r.mean_speed, r.mean_speed_relative, r.mean_waiting_time, r.mean_travel_time);
    out += buf;
    for (const TripRecord& t : sim.take_finished_trips()) {
      std::snprintf(buf, sizeof buf, "trip %u %a %a %a %u %a %a %a %u %d\n", t.vehicle, t.depart, t.arrival,
                    t.route_length, t.arrival_lane, static_cast<double>(t.arrival_pos), t.waiting_time,
                    t.time_loss, t.waiting_count, t.teleported ? 1 : 0);
      out += buf;
    }
  }
  const LaneCounters& c = sim.collect_lane_counters();
  for (size_t l = 0; l < c.sampled_steps.size(); ++l) {
    std::snprintf(buf, sizeof buf, "lane %zu %lld %lld %lld %lld %lld %lld\n", l,
                  static_cast<long long>(c.sampled_steps[l]), static_cast<long long>(c.travelled_mm[l]),
                  static_cast<long long>(c.waiting_steps[l]), static_cast<long long>(c.time_loss_ms[l]),
                  static_cast<long long>(c.departed[l]), static_cast<long long>(c.left[l]));
    out += buf;
  }
  for (const TripRecord& t : sim.unfinished_trips(sim.time(), true)) {
    std::snprintf(buf, sizeof buf, "unfinished %u %u %a\n", t.vehicle, t.unfinished, t.route_length);
    out += buf;
  }
  return out;
}

// "" when the traces are equal, else their first differing line.
std::string first_difference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  size_t at = 0, line = 1;
  while (at < a.size() && at < b.size() && a[at] == b[at]) {
    if (a[at] == '\n') ++line;
    ++at;
  }
  const size_t begin = a.rfind('\n', at == 0 ? 0 : at - 1);
  const size_t from = begin == std::string::npos ? 0 : begin + 1;
  return "line " + std::to_string(line) + ": '" + a.substr(from, a.find('\n', from) - from) + "' against '" +
         b.substr(from, b.find('\n', from) - from) + "'";
}

class EngineStateTest : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineStateTest, AResumedRunStepsOnAsTheSavedOneAndSavingChangesNothing) {
  const Scenario sc = load_sumo_scenario(GetParam());
  SimulationOptions options = simulation_options(sc.config);
  options.lane_counters = true;
  constexpr uint32_t kMostSteps = 4000;
  // How many steps the whole run takes, to save a third and two thirds of the way.
  uint32_t steps = 0;
  {
    Simulation sim(sc.network, sc.demand, options);
    while (steps < kMostSteps && !sim.finished()) sim.step(), ++steps;
  }
  ASSERT_GT(steps, 6u);
  for (const uint32_t at : {steps / 3, 2 * steps / 3}) {
    Simulation whole(sc.network, sc.demand, options);
    for (uint32_t n = 0; n < at; ++n) whole.step();
    const std::string uninterrupted = trace_to_end(whole, kMostSteps);

    Simulation saved(sc.network, sc.demand, options);
    for (uint32_t n = 0; n < at; ++n) saved.step();
    const std::vector<uint8_t> state = saved.save_state();
    EXPECT_EQ(first_difference(trace_to_end(saved, kMostSteps), uninterrupted), "")
        << GetParam() << ": saving at step " << at;

    Simulation resumed(sc.network, sc.demand, options);
    resumed.load_state(state, "state of step " + std::to_string(at));
    EXPECT_EQ(resumed.step_index(), at);
    const std::vector<uint8_t> again = resumed.save_state();
    size_t differs = 0;
    while (differs < again.size() && differs < state.size() && again[differs] == state[differs]) ++differs;
    EXPECT_TRUE(again == state) << GetParam() << ": the state read back, saved again, differs from byte "
                                << differs << " of " << state.size() << " (" << again.size() << " now)";
    EXPECT_EQ(first_difference(trace_to_end(resumed, kMostSteps), uninterrupted), "")
        << GetParam() << ": resumed at step " << at;
  }
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, EngineStateTest,
                         ::testing::Values("grid_tls", "actuated_cross", "city_mixed", "flows", "keep_clear",
                                           "motorway_ramps", "random_net", "reroute_block",
                                           "emissions_classes", "emissions_redlight", "cosim_line"));

TEST(EngineStateTest, AStateThatDoesNotFitTheRunIsRefused) {
  const Scenario grid = load_sumo_scenario("grid_tls");
  const Scenario flows = load_sumo_scenario("flows");
  Simulation a(grid.network, grid.demand, simulation_options(grid.config));
  for (int n = 0; n < 20; ++n) a.step();
  std::vector<uint8_t> state = a.save_state();
  Simulation other(flows.network, flows.demand, simulation_options(flows.config));
  EXPECT_THROW(other.load_state(state, "grid state"), std::runtime_error);
  std::vector<uint8_t> cut(state.begin(), state.begin() + static_cast<std::ptrdiff_t>(state.size() / 2));
  Simulation b(grid.network, grid.demand, simulation_options(grid.config));
  try {
    b.load_state(cut, "cut state");
    FAIL() << "a truncated state was loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cut state"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lpsim::engine_test

// Checkpoints of the engine: a Simulation saved between two steps and loaded into a fresh one made from the
// same scenario steps on exactly as the saved one does, and saving changes nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/partitioned_parts.hpp"
#include "app/simulation_options.hpp"
#include "backends/backend_state.hpp"
#include "engine/host_books.hpp"
#include "engine/saved_state.hpp"
#include "engine/state_archive.hpp"
#include "unit/command_run.hpp"
#include "unit/engine_invariant_checker.hpp"
#include "unit/state_trace.hpp"
#include "unit/step_wrap.hpp"

namespace lpsim::engine_test {
namespace {

class EngineStateTest : public ::testing::TestWithParam<std::string> {};

// A saved state taken apart (SavedState, each part's SavedPartState, its books and its backend's tables) and
// put together again: the same bytes, so that the pieces hold the whole state. Returns the parts' states;
// `active`: the slots the parts' passes visit, in all.
std::vector<SavedPartState> take_apart_and_put_together(const std::vector<uint8_t>& state, const Network& net,
                                                        const std::string& what, size_t& active) {
  active = 0;
  StateIn in(state.data(), state.size(), what);
  SavedState saved;
  in(saved);
  EXPECT_TRUE(in.done()) << what;
  std::vector<SavedPartState> parts(saved.parts.size());
  for (size_t p = 0; p < saved.parts.size(); ++p) {
    StateIn part_in(saved.parts[p].data(), saved.parts[p].size(), what);
    part_in(parts[p]);
    EXPECT_TRUE(part_in.done()) << what << ", part " << p;
    const std::vector<uint8_t>& books_bytes = parts[p].sections[kSectionBooks];
    StateIn books_in(books_bytes.data(), books_bytes.size(), what);
    HostBooks books(net);
    books_in(books);
    EXPECT_TRUE(books_in.done()) << what << ", part " << p;
    BackendState backend;
    decode_backend_state(parts[p].sections[kSectionBackend], books.slots.size(), backend);
    EXPECT_EQ(backend.map_index, parts[p].map) << what << ", part " << p;
    EXPECT_EQ(backend.tables.active.size(), books.num_active) << what << ", part " << p;
    active += books.num_active;
    EXPECT_TRUE(encode_backend_state(backend) == parts[p].sections[kSectionBackend])
        << what << ", part " << p;
    StateOut part_out;
    part_out(parts[p]);
    EXPECT_TRUE(part_out.bytes() == saved.parts[p]) << what << ", part " << p;
  }
  StateOut out;
  out(saved);
  EXPECT_TRUE(out.bytes() == state) << what;
  return parts;
}

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
    size_t active = 0;
    const std::vector<SavedPartState> pieces =
        take_apart_and_put_together(state, sc.network, GetParam(), active);
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(pieces[0].step, at);

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

// A driver's commands before the save (trips added, some due after it; a vehicle re-routed; vehicles
// removed): the state holds the trips added, and the resumed run goes on as the uninterrupted one.
TEST(EngineStateTest, ARunWithCommandsResumesAsItWouldHaveGoneOn) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const SimulationOptions options = simulation_options(sc.config);
  constexpr uint32_t kSaveAt = 100, kMostSteps = 4000;
  Simulation whole(sc.network, sc.demand, options);
  drive_with_commands(whole, kSaveAt);
  const std::string uninterrupted = trace_to_end(whole, kMostSteps);
  Simulation saved(sc.network, sc.demand, options);
  drive_with_commands(saved, kSaveAt);
  const std::vector<uint8_t> state = saved.save_state();
  Simulation resumed(sc.network, sc.demand, options);
  resumed.load_state(state, "state with commands");
  EXPECT_EQ(resumed.demand().size(), sc.demand.size() + 6);
  EXPECT_EQ(resumed.vehicle_index("added_4"), int64_t{sc.demand.size()} + 4);
  EXPECT_TRUE(resumed.save_state() == state) << "the state read back, saved again, differs";
  EXPECT_EQ(first_difference(trace_to_end(resumed, kMostSteps), uninterrupted), "");
  EXPECT_NE(uninterrupted.find("trip " + std::to_string(sc.demand.size() + 4) + " "), std::string::npos)
      << "an added trip due after the save drove";
}

// Every part's state, gathered by part 0, taken apart and put together again, with the partition that saved
// it.
TEST(EngineStateTest, APartitionedStateTakenApartAndPutTogetherIsTheSameState) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  SimulationOptions options = simulation_options(sc.config);
  options.lane_counters = true;
  const std::vector<PartPlan> plans = three_parts(sc);
  std::vector<uint8_t> state;
  InProcessParts others(sc.network, sc.demand, options, plans, 60);
  run_part0(&others, [&] {
    Simulation sim(sc.network, sc.demand, others.part0_options(options));
    for (int n = 0; n < 200; ++n) sim.step();
    state = sim.save_state();
  });
  size_t active = 0;
  const std::vector<SavedPartState> parts = take_apart_and_put_together(state, sc.network, "3 parts", active);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_GT(active, 50u) << "vehicles on the road in the saved parts";
  for (const SavedPartState& p : parts) EXPECT_EQ(p.step, 200u);
  StateIn in(state.data(), state.size(), "3 parts");
  SavedState saved;
  in(saved);
  EXPECT_EQ(saved.edge_part, plans[0].edge_owner);
}

TEST(EngineStateTest, StepMarksWrapAfter2To24StepsAndVehiclesStillEnterLanes) {
  expect_lane_entries_across_the_step_wrap(simulation_options(load_sumo_scenario("grid_tls").config));
}

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

// A state resumed in other parts than those that saved it (engine/state_recut.hpp): saved in three parts and
// resumed in one or two, saved in one and resumed in three, the run goes on exactly as the uninterrupted one.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "app/partitioned_parts.hpp"
#include "app/simulation_options.hpp"
#include "engine/host_books.hpp"
#include "engine/saved_state.hpp"
#include "engine/state_archive.hpp"
#include "unit/command_run.hpp"
#include "unit/state_trace.hpp"

namespace lpsim::engine_test {
namespace {

std::vector<PartPlan> plans_of(const Scenario& sc, int parts) {
  if (parts == 1) return {};
  const Network& net = sc.network;
  const std::vector<int32_t> edge_part = edge_parts_from_junctions(
      net, partition_junctions(build_junction_graph(net, sc.demand, 1.0), parts, PartitionMethod::Metis, 2));
  return part_plans(net, edge_part, parts, longest_vehicle(sc.demand));
}

// f(part 0's Simulation) in the parts of `plans` (none: one part), the others on threads.
template <class F>
void in_parts(const Scenario& sc, const SimulationOptions& options, const std::vector<PartPlan>& plans,
              F&& f) {
  if (plans.empty()) {
    Simulation sim(sc.network, sc.demand, options);
    f(sim);
    return;
  }
  InProcessParts others(sc.network, sc.demand, options, plans, 60);
  run_part0(&others, [&] {
    Simulation sim(sc.network, sc.demand, others.part0_options(options));
    f(sim);
  });
}

// Whether a teleported vehicle waits in an insertion queue to re-enter in `state` (of one part).
bool queued_teleport(const std::vector<uint8_t>& state, const Network& net) {
  StateIn in(state.data(), state.size(), "state");
  SavedState saved;
  in(saved);
  SavedPartState part;
  StateIn part_in(saved.parts.at(0).data(), saved.parts[0].size(), "part");
  part_in(part);
  const std::vector<uint8_t>& b = part.sections[kSectionBooks];
  StateIn books_in(b.data(), b.size(), "books");
  HostBooks books(net);
  books_in(books);
  bool found = false;
  books.queues.for_each_queue([&](uint32_t, const uint32_t* first, const uint32_t* last) {
    found = found || std::any_of(first, last, [](uint32_t e) { return (e & kInsertTeleported) != 0; });
  });
  return found;
}

class EngineRecutTest : public ::testing::TestWithParam<std::string> {};

// Saved half way through the run, and traced for a quarter of it, so that trips are still running at the end
// (the trace ends with the unfinished ones). "_teleports": with a 20 s time to teleport, so that vehicles
// teleport and re-enter; "_requeued": also, and saved at the first step from a quarter of the run on where a
// teleported vehicle waits to re-enter (its account moves with its queue).
TEST_P(EngineRecutTest, AStateResumedInOtherPartsGoesOnAsTheUninterruptedRun) {
  const std::string name = GetParam();
  const bool requeued = name.ends_with("_requeued"), teleports = requeued || name.ends_with("_teleports");
  const Scenario sc = load_sumo_scenario(teleports ? name.substr(0, name.rfind('_')) : name);
  SimulationOptions options = simulation_options(sc.config);
  options.lane_counters = true;
  if (teleports) options.time_to_teleport = 20;
  constexpr uint32_t kMostSteps = 4000;
  uint32_t steps = 0;
  in_parts(sc, options, {}, [&](Simulation& sim) {
    while (steps < kMostSteps && !sim.finished()) sim.step(), ++steps;
  });
  ASSERT_GT(steps, 6u);
  uint32_t at = requeued ? steps / 4 : steps / 2;
  const uint32_t traced = steps / 4;
  std::string uninterrupted;
  in_parts(sc, options, {}, [&](Simulation& sim) {
    for (uint32_t n = 0; n < at; ++n) sim.step();
    while (requeued && at < steps && !queued_teleport(sim.save_state(), sc.network)) sim.step(), ++at;
    uninterrupted = trace_to_end(sim, traced);
  });
  ASSERT_LT(at, steps) << "no teleported vehicle waits to re-enter after a quarter of the run";
  EXPECT_NE(uninterrupted.find("unfinished"), std::string::npos) << "no trip running at the trace's end";
  // Each unfinished trip once (a teleported vehicle that re-entered is on the road, not teleporting).
  std::vector<std::string> unfinished;
  for (size_t at_line = uninterrupted.find("\nunfinished "); at_line != std::string::npos;
       at_line = uninterrupted.find("\nunfinished ", at_line + 1))
    unfinished.push_back(
        uninterrupted.substr(at_line + 12, uninterrupted.find(' ', at_line + 12) - at_line - 12));
  std::sort(unfinished.begin(), unfinished.end());
  EXPECT_EQ(std::adjacent_find(unfinished.begin(), unfinished.end()), unfinished.end())
      << GetParam() << ": a trip written twice as unfinished";
  for (const auto& [saved_in, resumed_in] : {std::pair{3, 1}, std::pair{1, 3}, std::pair{3, 2}}) {
    std::vector<uint8_t> state;
    in_parts(sc, options, plans_of(sc, saved_in), [&](Simulation& sim) {
      for (uint32_t n = 0; n < at; ++n) sim.step();
      state = sim.save_state();
    });
    std::string resumed;
    in_parts(sc, options, plans_of(sc, resumed_in), [&](Simulation& sim) {
      sim.load_state(state, "state of step " + std::to_string(at));
      EXPECT_EQ(sim.step_index(), at);
      resumed = trace_to_end(sim, traced);
    });
    EXPECT_EQ(first_difference(resumed, uninterrupted), "")
        << GetParam() << ": saved in " << saved_in << " parts at step " << at << ", resumed in "
        << resumed_in;
  }
}

// A driver's commands before the save (trips added, some due after it; a vehicle re-routed; vehicles
// removed): the re-cut state holds them, and the resumed run goes on as the uninterrupted one.
TEST(EngineRecutCommandsTest, ARunWithCommandsResumesInOtherPartsAsItWouldHaveGoneOn) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const SimulationOptions options = simulation_options(sc.config);
  constexpr uint32_t kSaveAt = 100, kMostSteps = 4000;
  std::string uninterrupted;
  in_parts(sc, options, {}, [&](Simulation& sim) {
    drive_with_commands(sim, kSaveAt);
    uninterrupted = trace_to_end(sim, kMostSteps);
  });
  ASSERT_NE(uninterrupted.find("trip " + std::to_string(sc.demand.size() + 4) + " "), std::string::npos)
      << "an added trip due after the save drove";
  for (const auto& [saved_in, resumed_in] : {std::pair{3, 1}, std::pair{1, 3}, std::pair{3, 2}}) {
    std::vector<uint8_t> state;
    in_parts(sc, options, plans_of(sc, saved_in), [&](Simulation& sim) {
      drive_with_commands(sim, kSaveAt);
      state = sim.save_state();
    });
    std::string resumed;
    in_parts(sc, options, plans_of(sc, resumed_in), [&](Simulation& sim) {
      sim.load_state(state, "state with commands");
      EXPECT_EQ(sim.demand().size(), sc.demand.size() + 6);
      resumed = trace_to_end(sim, kMostSteps);
    });
    EXPECT_EQ(first_difference(resumed, uninterrupted), "")
        << "saved in " << saved_in << " parts, resumed in " << resumed_in;
  }
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, EngineRecutTest,
                         ::testing::Values("grid_tls", "actuated_cross", "city_mixed", "flows", "keep_clear",
                                           "motorway_ramps", "random_net", "reroute_block",
                                           "emissions_classes", "emissions_redlight", "cosim_line",
                                           "grid_tls_teleports", "city_mixed_requeued"));

}  // namespace
}  // namespace lpsim::engine_test

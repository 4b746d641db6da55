// How many parts `lpsim run --parts K` runs: K, or fewer when each part would carry fewer vehicles per step
// than --parts.min-vehicles (their exchanges would cost more than they save), said on stderr; the outputs are
// the same either way.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/partitioned_parts.hpp"
#include "app/simulation_options.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim {
namespace {

const std::string kGrid = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";

// The estimate the choice rests on is the vehicles on the road per step in free flow: within a factor of two
// of what the run has on the road on average while its demand departs and drives (grid_tls: signals, some
// queues; motorway_ramps: free flow).
TEST(PartsChoiceTest, TheEstimateOfVehiclesPerStepIsWhatTheRunCarries) {
  for (const std::string name : {"grid_tls", "motorway_ramps", "flows"}) {
    const Scenario sc = engine_test::load_sumo_scenario(name);
    const double estimate = mean_vehicles_per_step(sc, sc.config);
    Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
    double running = 0;
    uint32_t steps = 0;
    const double end = sc.config.end >= 0 ? sc.config.end : 1e9;
    while (!sim.finished() && sim.time() < end) {
      sim.step();
      running += static_cast<double>(sim.counts().running);
      ++steps;
    }
    const double measured = running / steps;
    EXPECT_GT(estimate, measured / 2) << name << ": measured " << measured;
    EXPECT_LT(estimate, measured * 2) << name << ": measured " << measured;
  }
}

TEST(PartsChoiceTest, PartsTooSmallRunAsOnePartAndSaySo) {
  test::TempDir dir("lpsim_parts_choice");
  const std::vector<std::string> run{
      "run", "-c", kGrid, "--end", "300", "--no-step-log", "--tripinfo-output", "trips.xml"};
  std::vector<std::string> asked = run;
  asked.insert(asked.end(), {"--parts", "2"});
  const test::CliResult one = test::run_lpsim(dir.path(), asked);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.err.find("lpsim: warning: --parts 2: about "), std::string::npos) << one.err;
  EXPECT_NE(one.err.find("fewer than 2500 per part: running 1 part"), std::string::npos) << one.err;
  EXPECT_EQ(one.out.find("Partitions:"), std::string::npos) << one.out;
  const std::string trips_one = test::read_file(dir.path() / "trips.xml");

  // A threshold the scenario passes keeps the parts; 0 always does; --no-warnings silences the choice.
  for (const char* min : {"1", "0"}) {
    std::vector<std::string> kept = asked;
    kept.insert(kept.end(), {"--parts.min-vehicles", min});
    const test::CliResult two = test::run_lpsim(dir.path(), kept);
    ASSERT_EQ(two.exit_code, 0) << two.err;
    EXPECT_EQ(two.err.find("--parts 2:"), std::string::npos) << two.err;
    EXPECT_NE(two.out.find("Partitions: 2 parts"), std::string::npos) << two.out;
    EXPECT_EQ(test::read_file(dir.path() / "trips.xml"), trips_one) << "--parts.min-vehicles " << min;
  }
  asked.push_back("--no-warnings");
  const test::CliResult quiet = test::run_lpsim(dir.path(), asked);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("--parts 2:"), std::string::npos) << quiet.err;
}

}  // namespace
}  // namespace lpsim

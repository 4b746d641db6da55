// Engine invariants in more configurations than the unit suite affords: several threads in one process,
// other seeds (other speed factors and lane draws, so other encounters), half-second steps everywhere.
#include <gtest/gtest.h>

#include <string>

#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

// Four threads on a two-core machine: slower than the unit suite's runs, hence this suite.
TEST(EngineInvariantsSlowTest, GridTlsFourThreads) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const RunResult r = run_checked(sc, "grid_tls threads 4", 4, 1);
  expect_all_arrived(r, "grid_tls threads 4");
  EXPECT_GT(r.stats.signalised_entries, 1000u);
}

TEST(EngineInvariantsSlowTest, OtherSeeds) {
  for (const std::string seed : {"1", "77", "424242"}) {
    for (const std::string name : {"grid_tls", "random_net", "flows"}) {
      const Scenario sc = load_sumo_scenario(name, {"--seed", seed});
      const std::string what = name + " seed " + seed;
      const RunResult r = run_checked(sc, what, 1, 1);
      expect_all_arrived(r, what);
      EXPECT_GT(r.stats.junction_entries, r.counts.loaded) << what;
    }
  }
}

TEST(EngineInvariantsSlowTest, HalfSecondStepsEverywhere) {
  for (const std::string name : {"random_net", "flows"}) {
    const Scenario sc = load_sumo_scenario(name, {"--step-length", "0.5"});
    const RunResult r = run_checked(sc, name + " step 0.5", 1, 1);
    expect_all_arrived(r, name + " step 0.5");
  }
  const Scenario csv = load_csv_scenario();
  ConfigSpec config = csv.config;
  config.step_length = 0.5;
  const Scenario half = load_scenario(config);
  const RunResult r = run_checked(half, "lpsim_csv_small step 0.5", 1, 1);
  expect_all_arrived(r, "lpsim_csv_small step 0.5");
}

}  // namespace
}  // namespace lpsim::engine_test

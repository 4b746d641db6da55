// simulation_options maps a config onto the engine's options.
#include <gtest/gtest.h>

#include "app/simulation_options.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {
namespace {

TEST(SimulationOptionsTest, MapsEveryEngineFieldOfTheConfig) {
  ConfigSpec config;
  config.begin = 12.5;
  config.step_length = 0.25;
  config.seed = 987654321012LL;
  config.threads = 3;
  config.time_to_teleport = 42;
  config.device = ComputeDevice::Gpu;
  const SimulationOptions o = simulation_options(config);
  EXPECT_EQ(o.begin, 12.5);
  EXPECT_EQ(o.step_length, 0.25);
  EXPECT_EQ(o.seed, 987654321012u);
  EXPECT_EQ(o.threads, 3);
  EXPECT_EQ(o.time_to_teleport, 42);
  // Left to the driver (device probing, outputs): the engine's defaults.
  const SimulationOptions defaults;
  EXPECT_FALSE(o.gpu);
  EXPECT_EQ(o.lane_counters, defaults.lane_counters);
  EXPECT_EQ(o.slot_sort_interval, defaults.slot_sort_interval);
}

TEST(SimulationOptionsTest, NoThreadCountStepsOnOneThread) {
  ConfigSpec config;
  ASSERT_EQ(config.threads, 0);
  EXPECT_EQ(simulation_options(config).threads, 1);
}

TEST(SimulationOptionsTest, CommandLineReachesTheEngine) {
  const SimulationOptions o =
      simulation_options(parse_cli_options({"--begin", "0:01:00", "--step-length", "0.5", "--seed", "7",
                                            "--threads", "2", "--time-to-teleport", "-1"}));
  EXPECT_EQ(o.begin, 60);
  EXPECT_EQ(o.step_length, 0.5);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(o.time_to_teleport, -1);
}

}  // namespace
}  // namespace lpsim

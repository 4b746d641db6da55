// The engine invariants (tests/unit/engine_invariant_checker.hpp: every vehicle accounted for, no shared
// lane-map cell, no entry on red, speeds within limits) checked after every step of whole runs on the GPU
// backend, whose state the checker reads back from the device each step. Skipped without a usable GPU.
#include <gtest/gtest.h>

#include <string>

#include "backends/cuda/cuda_stepper.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

RunResult run_checked_on_gpu(const Scenario& sc, const std::string& name) {
  SimulationOptions options = simulation_options(sc.config);
  options.backend = make_cuda_stepper;
  return run_checked(sc, name + " on the GPU", options, 1);
}

class GpuInvariantsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const CudaDeviceStatus gpu = cuda_device_status();
    if (!gpu.usable)
      GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): GPU invariants not checked";
  }
};

TEST_F(GpuInvariantsTest, GridTlsEveryStep) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const RunResult r = run_checked_on_gpu(sc, "grid_tls");
  expect_all_arrived(r, "grid_tls");
  EXPECT_GT(r.stats.signalised_entries, 1000u);
}

TEST_F(GpuInvariantsTest, RandomNetAndFlowsEveryStep) {
  for (const std::string name : {"random_net", "flows"}) {
    const Scenario sc = load_sumo_scenario(name);
    expect_all_arrived(run_checked_on_gpu(sc, name), name);
  }
}

TEST_F(GpuInvariantsTest, GridTlsWithTeleportsEveryStep) {
  const Scenario sc = load_sumo_scenario("grid_tls", {"--time-to-teleport", "20"});
  const RunResult r = run_checked_on_gpu(sc, "grid_tls with teleports");
  EXPECT_GT(r.counts.teleports, 0u);
  EXPECT_EQ(r.counts.arrived + r.counts.removed, r.counts.loaded);
}

}  // namespace
}  // namespace lpsim::engine_test

// A driver's commands between steps on the CUDA backend (vehicles removed on the road, queued and not due,
// trips added): the run equal bit for bit to the CPU backend's (tests/unit/command_run.hpp). Skipped without
// a usable GPU; the emulated suite runs it always.
#include <gtest/gtest.h>

#include "backends/cuda/cuda_stepper.hpp"
#include "unit/command_run.hpp"

namespace lpsim::engine_test {
namespace {

TEST(GpuCommandsTest, RemovalsAndAdditionsAsOnTheCpu) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): commands not checked";
  const Scenario sc = load_sumo_scenario("grid_tls");
  SimulationOptions cpu = simulation_options(sc.config);
  SimulationOptions on_gpu = cpu;
  on_gpu.backend = make_cuda_stepper;
  const CommandRun reference = run_with_removals(sc, cpu, false);
  const CommandRun run = run_with_removals(sc, on_gpu, false);
  EXPECT_EQ(run.lane_map, "");
  expect_same_command_run(reference, run, "GPU vs CPU");
}

TEST(GpuCommandsTest, ABatchSeesItsOwnCommands) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): commands not checked";
  SimulationOptions on_gpu = simulation_options(load_sumo_scenario("grid_tls").config);
  on_gpu.backend = make_cuda_stepper;
  expect_a_batch_sees_its_own_commands(on_gpu);
}

}  // namespace
}  // namespace lpsim::engine_test

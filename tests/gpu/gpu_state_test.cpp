// Checkpoints on the CUDA backend: a state saved on the device resumes on the device and on the CPU, and a
// state saved on the CPU resumes on the device, each stepping on exactly as the uninterrupted CPU run
// (tests/unit/state_trace.hpp). Skipped without a usable GPU; the emulated suite runs it always.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/simulation_options.hpp"
#include "backends/cuda/cuda_stepper.hpp"
#include "unit/command_run.hpp"
#include "unit/engine_invariant_checker.hpp"
#include "unit/state_trace.hpp"
#include "unit/step_wrap.hpp"

namespace lpsim::engine_test {
namespace {

class GpuStateTest : public ::testing::TestWithParam<std::string> {};

TEST_P(GpuStateTest, AStateMovesBetweenTheDeviceAndTheCpu) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): states not checked";
  const Scenario sc = load_sumo_scenario(GetParam());
  SimulationOptions cpu = simulation_options(sc.config);
  cpu.lane_counters = true;
  SimulationOptions device = cpu;
  device.backend = make_cuda_stepper;
  constexpr uint32_t kAt = 400, kMostSteps = 4000;
  auto saved_at = [&](const SimulationOptions& o) {
    Simulation sim(sc.network, sc.demand, o);
    for (uint32_t n = 0; n < kAt; ++n) sim.step();
    return sim.save_state();
  };
  std::string uninterrupted;
  {
    Simulation whole(sc.network, sc.demand, cpu);
    for (uint32_t n = 0; n < kAt; ++n) whole.step();
    uninterrupted = trace_to_end(whole, kMostSteps);
  }
  const std::vector<uint8_t> from_cpu = saved_at(cpu), from_device = saved_at(device);
  EXPECT_TRUE(from_device == from_cpu) << GetParam() << ": the device's state is not the CPU's";
  for (const auto& [state, o, what] :
       {std::tuple{&from_device, &device, "device to device"},
        std::tuple{&from_device, &cpu, "device to CPU"}, std::tuple{&from_cpu, &device, "CPU to device"}}) {
    Simulation resumed(sc.network, sc.demand, *o);
    resumed.load_state(*state, what);
    EXPECT_EQ(first_difference(trace_to_end(resumed, kMostSteps), uninterrupted), "")
        << GetParam() << ": " << what;
  }
}

// A run with a driver's commands (trips added, vehicles removed) saved on the CPU resumes on the device as
// the CPU run goes on: the device's trip table takes the added trips from the state.
TEST(GpuStateTest, ARunWithCommandsResumesOnTheDevice) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): states not checked";
  const Scenario sc = load_sumo_scenario("grid_tls");
  const SimulationOptions cpu = simulation_options(sc.config);
  SimulationOptions device = cpu;
  device.backend = make_cuda_stepper;
  constexpr uint32_t kSaveAt = 100, kMostSteps = 4000;
  Simulation whole(sc.network, sc.demand, cpu);
  drive_with_commands(whole, kSaveAt);
  const std::vector<uint8_t> state = whole.save_state();
  const std::string uninterrupted = trace_to_end(whole, kMostSteps);
  Simulation resumed(sc.network, sc.demand, device);
  resumed.load_state(state, "state with commands");
  EXPECT_EQ(first_difference(trace_to_end(resumed, kMostSteps), uninterrupted), "");
}

TEST(GpuStepWrapTest, VehiclesStillEnterLanesAfter2To24Steps) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): the wrap not checked";
  SimulationOptions device = simulation_options(load_sumo_scenario("grid_tls").config);
  device.backend = make_cuda_stepper;
  expect_lane_entries_across_the_step_wrap(device);
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, GpuStateTest,
                         ::testing::Values("grid_tls", "actuated_cross", "reroute_block", "city_mixed"));

}  // namespace
}  // namespace lpsim::engine_test

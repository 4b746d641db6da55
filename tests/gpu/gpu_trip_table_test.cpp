// Trips added mid-run and routes replaced on the CUDA backend (its trip table on the device grows and its
// slots take new routes): every invariant after every step, and the run equal bit for bit to the CPU
// backend's (tests/unit/trip_changes.hpp). Skipped without a usable GPU; the emulated suite runs it always.
#include <gtest/gtest.h>

#include "backends/cuda/cuda_stepper.hpp"
#include "unit/trip_changes.hpp"

namespace lpsim::engine_test {
namespace {

TEST(GpuTripTableTest, AddedTripsAndNewRoutesAsOnTheCpu) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable)
    GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): trip changes not checked";
  const Scenario sc = load_sumo_scenario("grid_tls");
  SimulationOptions cpu = simulation_options(sc.config);
  SimulationOptions on_gpu = cpu;
  on_gpu.backend = make_cuda_stepper;
  const TripChangesRun reference = run_with_trip_changes(sc, cpu);
  const TripChangesRun run = run_with_trip_changes(sc, on_gpu);
  EXPECT_EQ(run.result.failures, 0u);
  expect_all_arrived(run.result, "grid_tls with trip changes on the GPU");
  EXPECT_EQ(run.visited, run.new_route);
  expect_same_run(reference, run, "GPU vs CPU");
}

}  // namespace
}  // namespace lpsim::engine_test

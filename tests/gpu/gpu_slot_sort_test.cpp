// The device's slot renumbering (CudaStepper::sort_slots) against a CPU run that never renumbers: the same
// positions every step, trip records, summary, per-vehicle queries and lane counters, bit for bit. Skipped
// without a usable GPU.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "backends/cuda/cuda_stepper.hpp"
#include "unit/run_trace.hpp"

namespace lpsim::engine_test {
namespace {

class GpuSlotSortTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const CudaDeviceStatus gpu = cuda_device_status();
    if (!gpu.usable)
      GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): GPU slot sorting not checked";
  }

  static void check(const std::string& name, const std::vector<std::string>& args) {
    const Scenario sc = load_sumo_scenario(name, args);
    SimulationOptions cpu = simulation_options(sc.config);
    cpu.slot_sort_interval = 0;
    const Trace reference = run_trace(sc, cpu);
    ASSERT_GT(reference.trips.size(), 0u);
    for (const uint32_t interval : {1u, 5u}) {
      SimulationOptions gpu = cpu;
      gpu.backend = make_cuda_stepper;
      gpu.slot_sort_interval = interval;
      expect_same_trace(reference, run_trace(sc, gpu),
                        name + ": GPU renumbering every " + std::to_string(interval) + " steps vs CPU never");
    }
  }
};

TEST_F(GpuSlotSortTest, GridTls) { check("grid_tls", {}); }

TEST_F(GpuSlotSortTest, GridTlsWithTeleports) { check("grid_tls", {"--time-to-teleport", "20"}); }

}  // namespace
}  // namespace lpsim::engine_test

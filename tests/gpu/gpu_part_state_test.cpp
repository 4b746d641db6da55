// Checkpoints of a partitioned run on the CUDA backend (`lpsim run --device gpu --parts 3`): its parts'
// states resume on the CPU, a CPU run's on the device, in the same parts or re-cut for others, and either way
// every output is byte for byte that of the run never stopped in one part on the CPU. Skipped without a
// usable GPU; the emulated suite runs it always.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "backends/cuda/cuda_stepper.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kOutputs{"trip.xml", "fcd.xml", "summary.xml", "edge.xml"};

test::CliResult run(const fs::path& dir, const std::string& name, const std::vector<std::string>& extra) {
  const fs::path config = fs::path(LPSIM_SCENARIOS_DIR) / name / (name + ".sumocfg");
  std::vector<std::string> args{"run",
                                config.string(),
                                "--tripinfo-output",
                                "trip.xml",
                                "--fcd-output",
                                "fcd.xml",
                                "--summary-output",
                                "summary.xml",
                                "--edgedata-output",
                                "edge.xml",
                                "--no-step-log",
                                "-W"};
  args.insert(args.end(), extra.begin(), extra.end());
  fs::create_directories(dir);
  return test::run_lpsim(dir, args);
}

class GpuPartStateTest : public ::testing::TestWithParam<std::string> {};

TEST_P(GpuPartStateTest, APartitionedStateMovesBetweenTheDeviceAndTheCpu) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): states not checked";
  const std::string name = GetParam();
  test::TempDir tmp("lpsim_gpu_part_state");
  const test::CliResult whole = run(tmp.path() / "whole", name, {});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  // Saved in 3 parts; resumed in the same, or re-cut for 2 parts or one.
  struct Move {
    std::string from, to, parts;
  };
  for (const Move& m :
       {Move{"gpu", "cpu", "3"}, Move{"cpu", "gpu", "3"}, Move{"gpu", "cpu", "2"}, Move{"cpu", "gpu", "1"}}) {
    const std::string& from = m.from;
    const std::string& to = m.to;
    const fs::path dir = tmp.path() / (from + "_to_" + to + "_in_" + m.parts);
    std::vector<std::string> saving{"--parts", "3", "--parts.min-vehicles", "0"},
        resuming{"--parts", m.parts, "--parts.min-vehicles", "0"};
    saving.insert(saving.end(), {"--device", from, "--save-state.times", "311"});
    resuming.insert(resuming.end(), {"--device", to, "--load-state", "state_311.00.lpstate"});
    const test::CliResult saved = run(dir, name, saving);
    ASSERT_EQ(saved.exit_code, 0) << saved.err;
    const test::CliResult resumed = run(dir, name, resuming);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    for (const std::string& f : kOutputs)
      EXPECT_TRUE(test::read_file(tmp.path() / "whole" / f) == test::read_file(dir / f))
          << name << ": " << f << " differs, saved on the " << from << " in 3 parts, resumed on the " << to
          << " in " << m.parts;
  }
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, GpuPartStateTest,
                         ::testing::Values("grid_tls", "reroute_block", "actuated_cross"));

}  // namespace
}  // namespace lpsim

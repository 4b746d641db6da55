// The CUDA backend: `lpsim run --device gpu` writes byte for byte the outputs of `--device cpu` on the
// bundled scenarios (skipped, saying why, where no usable CUDA device exists), and device selection
// behaves as documented on any machine (auto falls back to the CPU, gpu without a device is bad input).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "app/device_select.hpp"
#include "backends/cuda/cuda_stepper.hpp"
#include "core/error.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

std::string line_at(const std::string& s, size_t i) {
  const size_t b = s.rfind('\n', i == 0 ? 0 : i - 1);
  const size_t e = s.find('\n', i);
  return s.substr(b == std::string::npos ? 0 : b + 1,
                  e == std::string::npos ? std::string::npos : e - (b + 1));
}

// Where two texts first differ, with the line around it on each side.
std::string first_difference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  return "byte " + std::to_string(i) + ":\n  cpu: " + line_at(a, i) + "\n  gpu: " + line_at(b, i);
}

size_t count(const std::string& s, const std::string& needle) {
  size_t n = 0;
  for (size_t at = s.find(needle); at != std::string::npos; at = s.find(needle, at + 1)) ++n;
  return n;
}

// Runs `lpsim run <scenario> <args>` in `dir` (args: options separated by blanks), capturing stdout and
// stderr.
test::CliResult run_scenario(const fs::path& dir, const std::string& scenario, const std::string& args) {
  std::vector<std::string> words{
      "run", std::string(LPSIM_SCENARIOS_DIR) + "/" + scenario + "/" + scenario + ".sumocfg"};
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  return test::run_lpsim(dir, words);
}

struct Outputs {
  std::string fcd, tripinfo, edgedata, summary;
};

Outputs run_on(const fs::path& root, const std::string& scenario, const std::string& args,
               const std::string& device) {
  const fs::path dir = root / device;
  fs::create_directories(dir);
  const test::CliResult r = run_scenario(dir, scenario,
                                         "--device " + device + " " + args +
                                             " --fcd-output fcd.xml --tripinfo-output tripinfo.xml"
                                             " --edgedata-output edgedata.xml --summary-output summary.xml");
  EXPECT_EQ(r.exit_code, 0) << "--device " << device << ":\n" << r.out << r.err;
  // The summary's duration attribute is wall time: the only value allowed to differ.
  static const std::regex duration(" duration=\"[^\"]*\"");
  return Outputs{test::read_file(dir / "fcd.xml"), test::read_file(dir / "tripinfo.xml"),
                 test::read_file(dir / "edgedata.xml"),
                 std::regex_replace(test::read_file(dir / "summary.xml"), duration, " duration=\"masked\"")};
}

struct IdentityCase {
  friend void PrintTo(const IdentityCase& c, std::ostream* os) { *os << c.name; }
  const char* name;           // test name
  const char* scenario;       // bundled scenario
  const char* args;           // extra lpsim run options
  bool teleports;             // the case must teleport vehicles (checks that path too)
  const char* gpu_args = "";  // options of the device's run only (its network split into parts)
};

class GpuIdentityTest : public ::testing::TestWithParam<IdentityCase> {};

TEST_P(GpuIdentityTest, GpuOutputsEqualCpuOutputsByteForByte) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable)
    GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): CPU/GPU identity not checked";
  const test::TempDir tmp("lpsim_gpu");
  const IdentityCase& c = GetParam();
  const Outputs cpu = run_on(tmp.path(), c.scenario, c.args, "cpu");
  const Outputs dev = run_on(tmp.path(), c.scenario, std::string(c.args) + " " + c.gpu_args, "gpu");
  if (c.teleports) {
    EXPECT_TRUE(std::regex_search(cpu.summary, std::regex(" teleports=\"[1-9]")))
        << "no teleport in the CPU run";
  }
  // The CPU run must have produced real content, or two empty files would pass.
  EXPECT_GT(count(cpu.tripinfo, "<tripinfo "), 10u);
  EXPECT_GT(count(cpu.fcd, "<vehicle "), 1000u);
  EXPECT_GE(count(cpu.edgedata, "<edge "), 6u);  // reroute_block has six edges
  EXPECT_TRUE(cpu.fcd == dev.fcd) << "fcd differs at " << first_difference(cpu.fcd, dev.fcd);
  EXPECT_TRUE(cpu.tripinfo == dev.tripinfo)
      << "tripinfo differs at " << first_difference(cpu.tripinfo, dev.tripinfo);
  EXPECT_TRUE(cpu.edgedata == dev.edgedata)
      << "edgedata differs at " << first_difference(cpu.edgedata, dev.edgedata);
  EXPECT_TRUE(cpu.summary == dev.summary)
      << "summary differs at " << first_difference(cpu.summary, dev.summary);
}

// Signals (grid_tls), right of way (random_net), random departures and flows (flows), 0.5 s steps with
// edgeData intervals, teleports with re-insertion (a short time-to-teleport on the signalised grid), and the
// device's run split into parts (their exchanges read and write the device's state; teleported vehicles
// re-enter in the part that owns their next edge) against the CPU in one part; junction blockers ignored
// (--ignore-junction-blocker 0: every vehicle on a junction lane) in parts.
INSTANTIATE_TEST_SUITE_P(
    BundledScenarios, GpuIdentityTest,
    ::testing::Values(IdentityCase{"grid_tls", "grid_tls", "", false},
                      IdentityCase{"random_net", "random_net", "", false},
                      IdentityCase{"flows", "flows", "", false},
                      // The rerouting device: speeds sampled from the device's state, routes set on it.
                      IdentityCase{"reroute_block", "reroute_block", "", false},
                      IdentityCase{"reroute_block_in_2_parts", "reroute_block", "", false,
                                   "--parts 2 --parts.min-vehicles 0"},
                      IdentityCase{"grid_tls_half_step", "grid_tls", "--step-length 0.5", false},
                      IdentityCase{"grid_tls_teleports", "grid_tls", "--time-to-teleport 20", true},
                      IdentityCase{"grid_tls_in_3_parts", "grid_tls", "", false,
                                   "--parts 3 --parts.min-vehicles 0"},
                      IdentityCase{"grid_tls_teleports_in_4_parts", "grid_tls", "--time-to-teleport 20", true,
                                   "--parts 4 --parts.min-vehicles 0"},
                      // The junction lanes' stand times (double-buffered like the lane map) in 3 parts.
                      IdentityCase{"grid_tls_ignore_junction_blockers_in_3_parts", "grid_tls",
                                   "--ignore-junction-blocker 0", false, "--parts 3 --parts.min-vehicles 0"}),
    [](const ::testing::TestParamInfo<IdentityCase>& info) { return std::string(info.param.name); });

TEST(DeviceSelectTest, CpuIsAlwaysTheCpu) {
  const DeviceChoice c = select_device(ComputeDevice::Cpu);
  EXPECT_EQ(c.backend, &make_cpu_stepper);
  EXPECT_EQ(c.description.rfind("cpu", 0), 0u) << c.description;
}

TEST(DeviceSelectTest, AutoTakesTheGpuExactlyWhenOneIsUsable) {
  const CudaDeviceStatus gpu = cuda_device_status();
  EXPECT_FALSE(gpu.description.empty());
  const DeviceChoice c = select_device(ComputeDevice::Auto);
  EXPECT_EQ(c.backend, gpu.usable ? &make_cuda_stepper : &make_cpu_stepper);
  EXPECT_EQ(c.description.rfind(gpu.usable ? "gpu (" : "cpu (", 0), 0u) << c.description;
  EXPECT_NE(c.description.find(gpu.description), std::string::npos) << c.description;
}

TEST(DeviceSelectTest, GpuWithoutAUsableDeviceIsBadInputNamingTheReason) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (gpu.usable) {
    EXPECT_EQ(select_device(ComputeDevice::Gpu).backend, &make_cuda_stepper);
    return;
  }
  try {
    select_device(ComputeDevice::Gpu);
    FAIL() << "--device gpu accepted without a usable GPU";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--device gpu"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(gpu.description), std::string::npos) << e.what();
  }
}

#if !defined(LPSIM_HAVE_CUDA)
TEST(DeviceSelectTest, BuildWithoutCudaSaysSo) {
  EXPECT_FALSE(cuda_device_status().usable);
  EXPECT_EQ(cuda_device_status().description, "built without CUDA");
}
#endif

TEST(DeviceCliTest, GpuWithoutAUsableDeviceExitsWithStatus2AndOneLine) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (gpu.usable) GTEST_SKIP() << "a CUDA device is usable (" << gpu.description << ")";
  const test::TempDir tmp("lpsim_gpu");
  const test::CliResult r = run_scenario(tmp.path(), "grid_tls", "--device gpu --end 10");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err,
            "lpsim: error: command line: --device gpu: no usable CUDA device: " + gpu.description + "\n");
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(DeviceCliTest, UnknownDeviceIsBadInput) {
  const test::TempDir tmp("lpsim_gpu");
  const test::CliResult r = run_scenario(tmp.path(), "grid_tls", "--device tpu --end 10");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, "lpsim: error: command line: --device: expected auto, cpu or gpu, got 'tpu'\n");
}

TEST(DeviceCliTest, AutoPrintsTheChosenDeviceOnOneStderrLine) {
  const test::TempDir tmp("lpsim_gpu");
  const test::CliResult r = run_scenario(tmp.path(), "grid_tls", "--device auto --end 60");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const DeviceChoice expected = select_device(ComputeDevice::Auto);
  EXPECT_EQ(r.err, "lpsim: device " + expected.description + "\n");
  EXPECT_NE(r.out.find("Simulation ended at time: 60.00"), std::string::npos) << r.out;
}

TEST(DeviceCliTest, CpuPrintsNothingAboutTheDevice) {
  const test::TempDir tmp("lpsim_gpu");
  const test::CliResult r = run_scenario(tmp.path(), "grid_tls", "--device cpu --end 60");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace
}  // namespace lpsim

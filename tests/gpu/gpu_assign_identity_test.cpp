// `lpsim assign --device gpu`: the iterations' simulations on the CUDA backend choose the same routes as on
// the CPU (scenarios/reroute_block, where the routes change from iteration to iteration), so the assigned
// routes, their alternatives and every iteration's gap and mean trip time are the same. Skipped, saying why,
// where no usable CUDA device exists (the emulated build runs it everywhere).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "backends/cuda/cuda_stepper.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

// Each iteration line's number, gap, mean trip time, finished trips and teleports (not its CPU seconds).
std::string iteration_values(const std::string& out) {
  std::string kept;
  for (const std::string& line : test::lines_of(out)) {
    std::istringstream in(line);
    std::string iteration, gap, mean, finished, teleports;
    if (!(in >> iteration >> gap >> mean >> finished >> teleports) ||
        iteration.find_first_not_of("0123456789") != std::string::npos)
      continue;
    kept += iteration + " " + gap + " " + mean + " " + finished + " " + teleports + "\n";
  }
  return kept;
}

TEST(GpuAssignIdentityTest, GpuIterationsChooseTheCpuRoutes) {
  const CudaDeviceStatus gpu = cuda_device_status();
  if (!gpu.usable) GTEST_SKIP() << "no usable CUDA device (" << gpu.description << "): not checked";
  const test::TempDir tmp("lpsim_gpu_assign");
  // Appended piecewise: GCC 12 warns falsely (-Warray-bounds) on "literal" + std::string temporaries.
  std::string s = LPSIM_SCENARIOS_DIR;
  s += "/reroute_block/";
  std::vector<test::CliResult> runs;
  for (const std::string device : {"cpu", "gpu"}) {
    std::string routes = device;
    routes += ".rou.xml";
    runs.push_back(test::run_lpsim(
        tmp.path(),
        {"assign", "-n", s + "reroute_block.net.xml", "-r", s + "reroute_block.rou.xml", "-o", routes,
         "--iterations", "4", "--aggregation", "60", "--time-to-teleport", "-1", "--device", device}));
  }
  ASSERT_EQ(runs[0].exit_code, 0) << runs[0].err;
  ASSERT_EQ(runs[1].exit_code, 0) << runs[1].err;
  EXPECT_EQ(test::read_file(tmp.path() / "cpu.rou.xml"), test::read_file(tmp.path() / "gpu.rou.xml"));
  EXPECT_EQ(test::read_file(tmp.path() / "cpu.rou.alt.xml"), test::read_file(tmp.path() / "gpu.rou.alt.xml"));
  EXPECT_EQ(iteration_values(runs[0].out), iteration_values(runs[1].out));
  EXPECT_NE(iteration_values(runs[0].out).find("\n3 "), std::string::npos) << runs[0].out;
}

}  // namespace
}  // namespace lpsim

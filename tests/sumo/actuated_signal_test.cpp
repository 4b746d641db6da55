// An actuated traffic light (scenarios/actuated_cross: netconvert's default actuated program, a busy
// north-south pair of approaches and a quiet east-west one) run by the real sumo and by lpsim: SUMO's gap
// control holds the busy green while vehicles keep crossing its loops, so the mean trip takes far less time
// than under the same phases run as a fixed-time plan. LPSim's mean duration and waiting time must be SUMO's
// within a few percent, and the fixed-time run must not be (so the comparison can tell the two apart).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::TempDir;

const std::string kScenario = std::string(LPSIM_SCENARIOS_DIR) + "/actuated_cross/";

struct TripMeans {
  int count = 0;
  double duration = 0, waiting = 0;
};

TripMeans trip_means(const std::string& tripinfo) {
  const std::regex trip(R"re(<tripinfo [^>]*duration="([0-9.]+)"[^>]*waitingTime="([0-9.]+)")re");
  TripMeans m;
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), trip); it != std::sregex_iterator();
       ++it) {
    ++m.count;
    m.duration += std::stod((*it)[1]);
    m.waiting += std::stod((*it)[2]);
  }
  if (m.count > 0) m.duration /= m.count, m.waiting /= m.count;
  return m;
}

class ActuatedSignalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "sumo not found";
  }
  TripMeans run_sumo() {
    const fs::path out = dir_.path() / "sumo_tripinfo.xml";
    const std::string cmd = "sumo -c " + test::shell_quote(kScenario + "actuated_cross.sumocfg") +
                            " --tripinfo-output " + test::shell_quote(out.string()) +
                            " --no-step-log --seed 42 > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return trip_means(read_file(out));
  }
  TripMeans run_lpsim(const std::vector<std::string>& extra) {
    const fs::path out = dir_.path() / "lpsim_tripinfo.xml";
    std::vector<std::string> args{
        "run",        "-c",           kScenario + "actuated_cross.sumocfg", "--tripinfo-output",
        out.string(), "--no-step-log"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::run_lpsim(dir_.path(), args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return trip_means(read_file(out));
  }
  TempDir dir_;
};

TEST_F(ActuatedSignalTest, MeanDurationAndWaitingAsSumosGapControl) {
  const TripMeans sumo = run_sumo();
  const TripMeans lpsim = run_lpsim({});
  ASSERT_EQ(sumo.count, 660);
  ASSERT_EQ(lpsim.count, 660);
  EXPECT_NEAR(lpsim.duration, sumo.duration, 0.06 * sumo.duration)
      << "SUMO " << sumo.duration << " s, LPSim " << lpsim.duration << " s";
  // Waiting times are a few seconds per trip: within 2 s of SUMO's.
  EXPECT_NEAR(lpsim.waiting, sumo.waiting, 2.0) << "SUMO " << sumo.waiting << " s, LPSim " << lpsim.waiting;

  // The same phases run as a fixed-time plan (an add-file program of type static replaces the net's).
  const fs::path fixed = dir_.path() / "static.add.xml";
  const std::string net = read_file(kScenario + "actuated_cross.net.xml");
  const std::regex program(R"re(<tlLogic id="C" type="actuated"[\s\S]*?</tlLogic>)re");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(net, m, program));
  std::ofstream(fixed) << "<additional>\n"
                       << std::regex_replace(m.str(), std::regex("type=\"actuated\" programID=\"0\""),
                                             "type=\"static\" programID=\"fixed\"")
                       << "\n</additional>\n";
  const TripMeans fixed_time = run_lpsim({"-a", fixed.string()});
  EXPECT_GT(fixed_time.duration, 1.15 * sumo.duration)
      << "SUMO " << sumo.duration << " s, LPSim fixed-time " << fixed_time.duration << " s";
}

}  // namespace
}  // namespace lpsim

// Progress of `lpsim run` when stderr is not a terminal (a log file, a batch job): a whole line every
// --progress-interval wall seconds, never a carriage return; none with SUMO's --no-step-log.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

const std::string kGridCfg = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";

class CliProgressTest : public ::testing::Test {
 protected:
  test::TempDir tmp_{"lpsim_progress"};
};

TEST_F(CliProgressTest, LinesWithoutTerminal) {
  // An interval of 1 ms: the run (3600 steps) lasts longer than that many times over.
  const test::CliResult r =
      test::run_lpsim(tmp_.path(), {"run", "-c", kGridCfg, "--no-warnings", "--progress-interval", "0.001"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  static const std::regex line(
      R"(lpsim: t=([0-9]+\.[0-9]{2}) running [0-9]+ arrived [0-9]+ waiting [0-9]+  \S+ veh-updates/s  ETA [0-9]+ s)");
  std::vector<double> times;
  for (size_t from = 0, nl; (nl = r.err.find('\n', from)) != std::string::npos; from = nl + 1) {
    const std::string text = r.err.substr(from, nl - from);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(text, m, line)) << text;
    times.push_back(std::stod(m[1].str()));
  }
  ASSERT_GE(times.size(), 2u) << r.err;
  for (size_t k = 1; k < times.size(); ++k) EXPECT_GT(times[k], times[k - 1]);
  EXPECT_LE(times.back(), 3600);
}

TEST_F(CliProgressTest, NoStepLogSilencesIt) {
  const test::CliResult r = test::run_lpsim(
      tmp_.path(), {"run", "-c", kGridCfg, "--no-warnings", "--progress-interval", "0.001", "--no-step-log"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST_F(CliProgressTest, IntervalMustBePositive) {
  const test::CliResult r = test::run_lpsim(tmp_.path(), {"run", "-c", kGridCfg, "--progress-interval", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "lpsim: error: command line: --progress-interval: expected a number > 0, got '0'\n");
}

}  // namespace
}  // namespace lpsim

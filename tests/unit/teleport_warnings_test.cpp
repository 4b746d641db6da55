// `lpsim run` warns of every teleport on stderr in SUMO's words, and --no-warnings (-W) silences them.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

test::CliResult run_grid_with_teleports(const std::vector<std::string>& extra) {
  const test::TempDir tmp("lpsim_teleport_warnings");
  std::vector<std::string> args{"run",
                                "-c",
                                std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg",
                                "--time-to-teleport",
                                "20",
                                "--end",
                                "600"};
  args.insert(args.end(), extra.begin(), extra.end());
  return test::run_lpsim(tmp.path(), args);
}

TEST(TeleportWarningsTest, OneSumoStyleWarningPerTeleport) {
  const test::CliResult r = run_grid_with_teleports({});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("Teleports: (\\d+)"))) << r.out;
  const long teleports = std::stol(m[1]);
  EXPECT_GT(teleports, 0);
  const std::regex line(
      "Warning: Teleporting vehicle '[^']+'; waited too long \\((jam|yield|wrong lane)\\), "
      "lane='[A-Z0-9]+_[0-9]+', time=[0-9]+\\.[0-9]{2}\\.");
  long warnings = 0;
  std::istringstream lines(r.err);
  for (std::string l; std::getline(lines, l);) {
    if (l.rfind("Warning: Teleporting", 0) != 0) continue;
    EXPECT_TRUE(std::regex_match(l, line)) << l;
    ++warnings;
  }
  EXPECT_EQ(warnings, teleports);
}

TEST(TeleportWarningsTest, NoWarningsSilencesThem) {
  for (const std::string flag : {"--no-warnings", "-W"}) {
    const test::CliResult r = run_grid_with_teleports({flag});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Teleports: "), std::string::npos);
    EXPECT_EQ(r.err.find("Warning: Teleporting"), std::string::npos) << flag;
  }
}

}  // namespace
}  // namespace lpsim

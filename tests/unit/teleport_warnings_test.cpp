// `lpsim run` warns of every teleport on stderr in SUMO's words, and --no-warnings (-W) silences them.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CliRun run_grid_with_teleports(const std::string& extra) {
  const test::TempDir tmp("lpsim_teleport_warnings");
  CliRun r;
  const fs::path& dir = tmp.path();
  std::string cmd = std::string("'") + LPSIM_BINARY + "' run -c '" + LPSIM_SCENARIOS_DIR +
                    "/grid_tls/grid_tls.sumocfg' --time-to-teleport 20 --end 600 " + extra + " > '" +
                    (dir / "out").string() + "' 2> '" + (dir / "err").string() + "'";
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "out");
  r.err = slurp(dir / "err");
  return r;
}

TEST(TeleportWarningsTest, OneSumoStyleWarningPerTeleport) {
  const CliRun r = run_grid_with_teleports("");
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
    const CliRun r = run_grid_with_teleports(flag);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Teleports: "), std::string::npos);
    EXPECT_EQ(r.err.find("Warning: Teleporting"), std::string::npos) << flag;
  }
}

}  // namespace
}  // namespace lpsim

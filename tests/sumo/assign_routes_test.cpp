// What `lpsim assign` writes is SUMO's: the assigned routes and their alternatives validate against
// routes_file.xsd, and the real sumo loads and runs both with every vehicle (scenarios/reroute_block).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

std::string scenario(const std::string& file) {
  return std::string(LPSIM_SCENARIOS_DIR) + "/reroute_block/" + file;
}

TEST(AssignRoutes, SumoValidatesLoadsAndRunsThem) {
  if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "SUMO not installed";
  test::TempDir dir("lpsim_assign_sumo");
  const test::CliResult a =
      test::run_lpsim(dir.path(), {"assign", "-n", scenario("reroute_block.net.xml"), "-r",
                                   scenario("reroute_block.rou.xml"), "-o", "assigned.rou.xml",
                                   "--iterations", "3", "--aggregation", "60", "--time-to-teleport", "-1"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::string schema = std::string(test::kSumoXsdDir) + "/routes_file.xsd";
  for (const char* file : {"assigned.rou.xml", "assigned.rou.alt.xml"}) {
    if (std::system("xmllint --version > /dev/null 2>&1") == 0 && std::filesystem::exists(schema)) {
      const std::string cmd = "xmllint --noout --schema " + test::usable_sumo_schema(schema, dir) + " " +
                              (dir.path() / file).string() + " > " + (dir.path() / "xmllint.log").string() +
                              " 2>&1";
      EXPECT_EQ(std::system(cmd.c_str()), 0) << file << ": " << test::read_file(dir.path() / "xmllint.log");
    }
    const test::CliResult sumo =
        test::run_program(dir.path(), {"sumo"},
                          {"-n", scenario("reroute_block.net.xml"), "-r", file, "--time-to-teleport", "-1",
                           "--no-step-log", "--duration-log.statistics", "--xml-validation", "never"});
    ASSERT_EQ(sumo.exit_code, 0) << file << ": " << sumo.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(sumo.out, m, std::regex("Inserted: ([0-9]+)"))) << sumo.out;
    EXPECT_EQ(m[1], "121") << file;
  }
}

}  // namespace
}  // namespace lpsim

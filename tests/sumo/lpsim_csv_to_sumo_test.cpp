// tools/lpsim_csv_to_sumo.py on scenarios/lpsim_csv_small: netconvert builds a .net.xml from the CSV network
// that keeps its edges, lanes, lengths and traffic lights, and that `lpsim info -n` loads with the same
// junctions, car lanes, lane-km and signal programs as LPSim's own reading of the CSV. Bad CSV input is one
// error line naming file:line and exit status 2. Needs python3 and netconvert (skipped without netconvert).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::read_file;
using test::run_lpsim;
using test::TempDir;

const std::string kSmall = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small/";
const std::string kTool = std::string(LPSIM_SOURCE_DIR) + "/tools/lpsim_csv_to_sumo.py";

// Runs the converter in `dir` (see test::run_program).
CliResult run_tool(const fs::path& dir, const std::vector<std::string>& args) {
  return test::run_program(dir, {"python3", kTool}, args);
}

size_t count_matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<size_t>(std::distance(std::sregex_iterator(text.begin(), text.end(), re), {}));
}

// The line of `lpsim info` output that starts with `key`.
std::string info_line(const std::string& info, const std::string& key) {
  for (size_t begin = 0; begin < info.size();) {
    const size_t end = std::min(info.find('\n', begin), info.size());
    if (info.compare(begin, key.size(), key) == 0) return info.substr(begin, end - begin);
    begin = end + 1;
  }
  return "(no line starting " + key + ")";
}

class LpsimCsvToSumoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("netconvert")) GTEST_SKIP() << "netconvert not found (SUMO not installed)";
  }
  TempDir dir_{"lpsim_csv_to_sumo"};
};

TEST_F(LpsimCsvToSumoTest, SmallCsvNetworkBecomesANetThatSumoAndLpsimLoadAlike) {
  const CliResult tool = run_tool(
      dir_.path(), {"--nodes", kSmall + "nodes.csv", "--edges", kSmall + "edges.csv", "-o", "small.net.xml"});
  ASSERT_EQ(tool.exit_code, 0) << tool.out << tool.err;
  EXPECT_NE(tool.out.find("(6 nodes, 1 traffic lights)"), std::string::npos) << tool.out;
  EXPECT_NE(tool.out.find("netconvert: exit 0"), std::string::npos) << tool.out;
  EXPECT_TRUE(fs::exists(dir_.path() / "small.nod.xml"));
  EXPECT_TRUE(fs::exists(dir_.path() / "small.edg.xml"));

  const std::string net = read_file(dir_.path() / "small.net.xml");
  // Every CSV edge is a normal edge (internal ones have ids starting with ':').
  EXPECT_EQ(count_matches(net, "<edge id=\"[^:]"), 10u);
  EXPECT_EQ(count_matches(net, "<tlLogic id=\"1001\""), 1u);
  EXPECT_EQ(count_matches(net, "<tlLogic "), 1u);
  // The CSV length, not the projected distance, and LPSim's defaults: edge 7 has no speed (13.89 m/s),
  // edge 8 has 0 lanes (one lane), 35 mph is 15.65 m/s.
  EXPECT_NE(net.find("<edge id=\"6\" from=\"1004\" to=\"1001\" priority=\"11\" length=\"178.50\">"),
            std::string::npos);
  EXPECT_NE(net.find("<lane id=\"7_0\" index=\"0\" speed=\"13.89\" length=\"178.50\""), std::string::npos);
  EXPECT_EQ(count_matches(net, "<lane id=\"8_"), 1u);
  EXPECT_NE(net.find("<lane id=\"0_1\" index=\"1\" speed=\"15.65\" length=\"176.00\""), std::string::npos);

  const CliResult from_net = run_lpsim(dir_.path(), {"info", "-n", "small.net.xml"});
  ASSERT_EQ(from_net.exit_code, 0) << from_net.err;
  EXPECT_EQ(info_line(from_net.out, "edges:"), "edges: 10 normal, 22 internal");
  const CliResult from_csv = run_lpsim(
      dir_.path(), {"info", "--lpsim-nodes", kSmall + "nodes.csv", "--lpsim-edges", kSmall + "edges.csv"});
  ASSERT_EQ(from_csv.exit_code, 0) << from_csv.err;
  for (const std::string key : {"junctions:", "signal programs:"})
    EXPECT_EQ(info_line(from_net.out, key), info_line(from_csv.out, key));
  // Same car lanes and lane-km (the CSV lengths); the internal lanes are netconvert's alone.
  const std::string lanes = "lanes: 14 vehicle lanes on normal edges (2.475 lane-km), ";
  EXPECT_EQ(info_line(from_csv.out, "lanes:").rfind(lanes, 0), 0u) << from_csv.out;
  EXPECT_EQ(info_line(from_net.out, "lanes:").rfind(lanes, 0), 0u) << from_net.out;
}

TEST_F(LpsimCsvToSumoTest, FullHeaderVariantTakesTheOsmidColumns) {
  const CliResult tool = run_tool(dir_.path(), {"--nodes", kSmall + "nodes.csv", "--edges",
                                                kSmall + "edges_full_header.csv", "-o", "full.net.xml"});
  ASSERT_EQ(tool.exit_code, 0) << tool.out << tool.err;
  const std::string net = read_file(dir_.path() / "full.net.xml");
  EXPECT_EQ(count_matches(net, "<edge id=\"[^:]"), 10u);
  EXPECT_NE(net.find("<edge id=\"0\" from=\"1002\" to=\"1001\""), std::string::npos);
}

TEST_F(LpsimCsvToSumoTest, UnknownNodeIsOneErrorLineNamingFileAndLine) {
  dir_.write("nodes.csv", "osmid,x,y,ref,highway\n1,-122.26,37.87,,\n2,-122.262,37.87,,\n");
  dir_.write("edges.csv", "uniqueid,u,v,length,lanes,speed_mph\n0,1,2,176,1,25\n1,2,99,176,1,25\n");
  const CliResult tool =
      run_tool(dir_.path(), {"--nodes", "nodes.csv", "--edges", "edges.csv", "-o", "bad.net.xml"});
  EXPECT_EQ(tool.exit_code, 2);
  EXPECT_EQ(tool.err,
            "lpsim_csv_to_sumo: error: edges.csv:3: column v: unknown node '99' (not in the nodes file)\n");
  EXPECT_FALSE(fs::exists(dir_.path() / "bad.net.xml"));
}

}  // namespace
}  // namespace lpsim

// Error messages that used to mislead: each names the real cause and the line that holds it. The real
// `lpsim` binary runs on files written to a fresh temp dir (built on scenarios/grid_tls), as a user runs it.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

const std::string kGridNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";
const std::string kCsvDir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small";

class CliMessagesTest : public ::testing::Test {
 protected:
  test::CliResult run(const std::vector<std::string>& args) const {
    return test::run_lpsim(tmp_.path(), args);
  }

  // Exit status 2 and exactly the one line "lpsim: error: <where>: <message>".
  void expect_error(const test::CliResult& r, const std::string& where, const std::string& message) const {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "lpsim: error: " + where + ": " + message + "\n");
  }

  test::TempDir tmp_{"lpsim_cli_messages"};
};

// A period that rounds to 0 ms is named as given, with the reason, not as "period 0".
TEST_F(CliMessagesTest, FlowPeriodBelowOneMillisecondIsNamedAsGiven) {
  tmp_.write("f.rou.xml",
             "<routes>\n<!-- c -->\n"
             "<flow id=\"f\" begin=\"0\" end=\"100\" period=\"1e-9\" from=\"A0B0\" to=\"B0C0\"/>\n"
             "</routes>\n");
  expect_error(run({"info", "-n", kGridNet, "-r", "f.rou.xml"}), "f.rou.xml:3",
               "flow 'f': period 1e-09 s is shorter than LPSim's time resolution of 1 ms");
  tmp_.write("v.rou.xml",
             "<routes>\n<!-- c -->\n"
             "<flow id=\"v\" begin=\"0\" end=\"100\" vehsPerHour=\"1e13\" from=\"A0B0\" to=\"B0C0\"/>\n"
             "</routes>\n");
  expect_error(
      run({"info", "-n", kGridNet, "-r", "v.rou.xml"}), "v.rou.xml:3",
      "flow 'v': vehsPerHour 1e+13 (a period of 3.6e-10 s) is shorter than LPSim's time resolution of 1 ms");
}

// Traffic light A1 of grid_tls has 12 links. Its first phase cut to 4 signals is the one blamed, on its own
// line, although the next phase is the first that disagrees with it.
TEST_F(CliMessagesTest, ShortPhaseStateIsBlamedOnItsOwnLine) {
  std::string net = test::read_file(kGridNet);
  const std::string first_phase = "<phase duration=\"42\" state=\"GGggrrrrGGGg\"/>";
  const size_t at = net.find(first_phase);
  ASSERT_NE(at, std::string::npos);
  const int line = 1 + static_cast<int>(std::count(net.begin(), net.begin() + static_cast<long>(at), '\n'));
  net.replace(at, first_phase.size(), "<phase duration=\"42\" state=\"GGgg\"/>");
  tmp_.write("short.net.xml", net);
  expect_error(run({"info", "-n", "short.net.xml"}), "short.net.xml:" + std::to_string(line),
               "tlLogic 'A1' program '0' phase 0: state 'GGgg' has 4 links, the program's other phases 12");
}

// An add-file program with too few links is blamed in the add-file, not on a connection of the network.
TEST_F(CliMessagesTest, BadAddFileTlLogicNamesTheAddFile) {
  tmp_.write("short.add.xml",
             "<additional>\n"
             "    <tlLogic id=\"A1\" type=\"static\" programID=\"1\" offset=\"0\">\n"
             "        <phase duration=\"42\" state=\"GGgg\"/>\n"
             "        <phase duration=\"42\" state=\"yyyy\"/>\n"
             "    </tlLogic>\n"
             "</additional>\n");
  expect_error(
      run({"info", "-n", kGridNet, "-a", "short.add.xml"}), "short.add.xml:3",
      "tlLogic 'A1' program '1' phase 0: state 'GGgg' has 4 links, but the network's connections use 12 "
      "(linkIndex up to 11)");
}

// As SUMO ("No initial signal plan loaded"): an add-file program cannot create a traffic light.
TEST_F(CliMessagesTest, AddFileTlLogicForNoTrafficLightIsRefused) {
  tmp_.write("ghost.add.xml",
             "<additional>\n"
             "    <tlLogic id=\"ghost\" type=\"static\" programID=\"1\" offset=\"0\">\n"
             "        <phase duration=\"42\" state=\"GGgg\"/>\n"
             "    </tlLogic>\n"
             "</additional>\n");
  expect_error(run({"info", "-n", kGridNet, "-a", "ghost.add.xml"}), "ghost.add.xml:2",
               "tlLogic 'ghost' program '1' names no traffic light of the network " + kGridNet);
}

TEST_F(CliMessagesTest, CarriageReturnOnlyCsvSaysSo) {
  std::string nodes = test::read_file(kCsvDir + "/nodes.csv");
  ASSERT_NE(nodes.find('\n'), std::string::npos);
  for (char& c : nodes)
    if (c == '\n') c = '\r';
  tmp_.write("nodes_cr.csv", nodes);
  expect_error(
      run({"info", "--lpsim-nodes", "nodes_cr.csv", "--lpsim-edges", kCsvDir + "/edges.csv"}),
      "nodes_cr.csv:1",
      "carriage return without a line feed: the file has CR-only line ends (convert them to LF or CRLF)");
}

}  // namespace
}  // namespace lpsim

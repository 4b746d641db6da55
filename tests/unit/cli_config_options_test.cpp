// Every setting is applied or refused: SUMO options LPSim does not implement are refused (exit 2, naming the
// option and file:line) when they could change the results, or named in one warning when they cannot, in a
// .sumocfg as on the command line; inputs that would be ignored (beside a snapshot, a CSV network beside a
// SUMO one) and options a command does not use are refused; times out of range or a begin after the end
// are exit 2. The real binary on real files in a temp dir.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::read_file;

const std::string kGridNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";
const std::string kCsvDir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small";

class CliConfigOptionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_.write("net.net.xml", read_file(kGridNet));
    tmp_.write(
        "r.rou.xml",
        "<routes>\n<vehicle id=\"v0\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n</routes>\n");
  }

  // A .sumocfg whose option elements start on line 5 (after the input section), one per line.
  void write_cfg(const std::string& name, const std::vector<std::string>& options) const {
    std::string text =
        "<configuration>\n  <input>\n    <net-file value=\"net.net.xml\"/>\n"
        "    <route-files value=\"r.rou.xml\"/>\n";
    for (const auto& o : options) text += "    " + o + "\n";
    text += "  </input>\n</configuration>\n";
    tmp_.write(name, text);
  }

  CliResult run(const std::vector<std::string>& args) const { return test::run_lpsim(tmp_.path(), args); }

  test::TempDir tmp_{"lpsim_cfg_opts"};
};

// Exit 2, exactly one line "lpsim: error: <where>: ..." containing every one of `names`.
void expect_error(const CliResult& r, const std::string& where, const std::vector<std::string>& names) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  const std::string prefix = "lpsim: error: " + where + ": ";
  EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << "expected prefix '" << prefix << "' in: " << r.err;
  for (const auto& n : names)
    EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' missing: " << r.err;
}

TEST_F(CliConfigOptionsTest, ResultChangingSumoOptionInACfgIsRefusedAtItsLine) {
  write_cfg("s.sumocfg", {"<begin value=\"0\"/>", "<scale value=\"3\"/>"});
  expect_error(run({"info", "-c", "s.sumocfg"}), "s.sumocfg:6", {"<scale>", "'3'", "not supported by LPSim"});
  for (const std::string option :
       {"<mesosim value=\"true\"/>", "<remote-port value=\"8813\"/>",
        "<device.rerouting.output value=\"w.xml\"/>", "<load-state.offset value=\"100\"/>",
        "<time-to-teleport.disconnected value=\"10\"/>", "<emission-output value=\"em.xml\"/>",
        "<vehroute-output value=\"vr.xml\"/>", "<lanechange.duration value=\"3\"/>",
        "<lateral-resolution value=\"0.8\"/>"}) {
    SCOPED_TRACE(option);
    write_cfg("u.sumocfg", {option});
    const std::string name = option.substr(1, option.find(' ') - 1);
    expect_error(run({"run", "-c", "u.sumocfg", "--end", "5"}), "u.sumocfg:5",
                 {"<" + name + ">", "not supported by LPSim"});
  }
  EXPECT_FALSE(fs::exists(tmp_.path() / "em.xml"));
}

TEST_F(CliConfigOptionsTest, ResultChangingSumoOptionOnTheCommandLineIsRefused) {
  expect_error(run({"run", "-n", "net.net.xml", "-r", "r.rou.xml", "--scale", "3"}), "command line",
               {"--scale", "'3'", "not supported by LPSim"});
  expect_error(run({"info", "-n", "net.net.xml", "-r", "r.rou.xml", "--mesosim"}), "command line",
               {"--mesosim", "not supported by LPSim"});
}

TEST_F(CliConfigOptionsTest, SumoDefaultValuesAreAcceptedSilently) {
  write_cfg("d.sumocfg", {"<scale value=\"1.0\"/>", "<mesosim value=\"false\"/>",
                          "<collision.action value=\"teleport\"/>", "<emission-output value=\"\"/>"});
  const auto r = run({"info", "-c", "d.sumocfg", "--remote-port", "0"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST_F(CliConfigOptionsTest, InertOptionsGiveOneWarningNamingThem) {
  write_cfg("i.sumocfg",
            {"<verbose value=\"true\"/>", "<log value=\"sumo.log\"/>",
             "<duration-log.disable value=\"true\"/>", "<gui-settings-file value=\"gui.xml\"/>"});
  const auto r = run({"run", "-c", "i.sumocfg", "--end", "5", "-v", "--duration-log.statistics", "--start"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err,
            "lpsim: warning: ignoring SUMO options that cannot change LPSim's results: verbose, log, "
            "duration-log.disable, "
            "gui-settings-file, duration-log.statistics, start\n");
}

TEST_F(CliConfigOptionsTest, NamesSumoDoesNotKnowAreErrorsInACfgToo) {
  write_cfg("x.sumocfg", {"<foo-bar value=\"1\"/>"});
  expect_error(run({"info", "-c", "x.sumocfg"}), "x.sumocfg:5", {"<foo-bar>", "unknown option"});
  write_cfg("y.sumocfg", {"<device value=\"gpu\"/>"});  // LPSim's own options stay off a .sumocfg
  expect_error(run({"info", "-c", "y.sumocfg"}), "y.sumocfg:5", {"<device>", "unknown option"});
  expect_error(run({"info", "-n", "net.net.xml", "--foo-bar", "1"}), "command line", {"'--foo-bar'"});
}

TEST_F(CliConfigOptionsTest, OptionsACommandDoesNotUseAreRefused) {
  expect_error(run({"info", "-n", "net.net.xml", "--fcd-output", "f.xml"}), "command line",
               {"'--fcd-output'", "not used by this command"});
  expect_error(run({"run", "-n", "net.net.xml", "-o", "x.lpsim"}), "command line", {"'-o'", "not used"});
  expect_error(run({"convert", "-n", "net.net.xml", "-o", "x.lpsim", "--device", "cpu"}), "command line",
               {"'--device'"});
  EXPECT_FALSE(fs::exists(tmp_.path() / "x.lpsim"));
}

TEST_F(CliConfigOptionsTest, InputOptionsBesideASnapshotAreRefused) {
  ASSERT_EQ(run({"convert", "-n", "net.net.xml", "-r", "r.rou.xml", "-o", "s.lpsim"}).exit_code, 0);
  write_cfg("s.sumocfg", {});
  expect_error(run({"info", "s.lpsim", "-n", "net.net.xml"}), "command line", {"-n", "'s.lpsim'"});
  expect_error(run({"run", "s.lpsim", "-r", "r.rou.xml"}), "command line", {"-r", "snapshot"});
  expect_error(run({"run", "s.lpsim", "-a", "r.rou.xml"}), "command line", {"-a", "snapshot"});
  expect_error(run({"run", "s.lpsim", "-c", "s.sumocfg"}), "command line", {"-c", "snapshot"});
  expect_error(run({"info", "s.lpsim", "--lpsim-od", kCsvDir + "/od.csv"}), "command line", {"--lpsim-od"});
  EXPECT_EQ(run({"run", "s.lpsim", "--end", "5"}).exit_code, 0);
  // Options that act only while loading were applied by convert.
  expect_error(run({"run", "s.lpsim", "--ignore-route-errors"}), "command line",
               {"--ignore-route-errors", "give it to lpsim convert"});
  expect_error(run({"info", "s.lpsim", "--weights.minor-penalty", "3"}), "command line",
               {"--weights.minor-penalty"});
  expect_error(run({"run", "s.lpsim", "--max-lane-map-gb", "1"}), "command line", {"--max-lane-map-gb"});
  // A seed still seeds the simulation's draws, but not the demand's: said, not hidden.
  const auto seeded = run({"run", "s.lpsim", "--end", "5", "--seed", "7"});
  EXPECT_EQ(seeded.exit_code, 0) << seeded.err;
  EXPECT_NE(seeded.err.find(
                "lpsim: warning: --seed beside the snapshot 's.lpsim' seeds the simulation's own draws only"),
            std::string::npos)
      << seeded.err;
}

TEST_F(CliConfigOptionsTest, CsvNetworkBesideASumoNetworkIsRefused) {
  write_cfg("s.sumocfg", {});
  auto r = run({"info", "-c", "s.sumocfg", "--lpsim-nodes", kCsvDir + "/nodes.csv", "--lpsim-edges",
                kCsvDir + "/edges.csv"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--lpsim-nodes given beside the SUMO network"), std::string::npos) << r.err;
  r = run({"info", "-n", "net.net.xml", "--lpsim-edges", kCsvDir + "/edges.csv"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--lpsim-edges"), std::string::npos) << r.err;
  r = run({"info", "--lpsim-nodes", kCsvDir + "/nodes.csv"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--lpsim-nodes needs --lpsim-edges too"), std::string::npos) << r.err;
}

TEST_F(CliConfigOptionsTest, BeginAfterEndIsRefusedBeginEqualEndRuns) {
  expect_error(run({"run", "-n", "net.net.xml", "-r", "r.rou.xml", "-b", "10", "-e", "5", "--tripinfo-output",
                    "t.xml"}),
               "command line", {"end time 5", "begin time 10"});
  EXPECT_FALSE(fs::exists(tmp_.path() / "t.xml"));
  write_cfg("w.sumocfg", {"<begin value=\"100\"/>", "<end value=\"50\"/>"});
  expect_error(run({"info", "-c", "w.sumocfg"}), "w.sumocfg:6", {"end time 50", "begin time 100"});
  // The command line's end repairs the cfg's window: only the merged window counts.
  EXPECT_EQ(run({"info", "-c", "w.sumocfg", "-e", "200"}).exit_code, 0);
  // SUMO runs begin == end (no step) and exits 0.
  const auto r = run({"run", "-n", "net.net.xml", "-r", "r.rou.xml", "-b", "10", "-e", "10"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(CliConfigOptionsTest, TimesBeyondTheEngineRangeAndNonFiniteValuesAreRefused) {
  const std::vector<std::string> base{"run", "-n", "net.net.xml", "-r", "r.rou.xml"};
  auto with = [&](std::vector<std::string> extra) {
    auto args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  expect_error(with({"-b", "1e17"}), "command line", {"--begin", "'1e17'", "1e12"});
  expect_error(with({"-e", "1e13"}), "command line", {"--end", "'1e13'"});
  expect_error(with({"--time-to-teleport", "-2e12"}), "command line", {"--time-to-teleport"});
  for (const std::string bad : {"nan", "inf", "-inf", "NaN"}) {
    SCOPED_TRACE(bad);
    expect_error(with({"--begin=" + bad}), "command line", {"--begin", "'" + bad + "'"});
    expect_error(with({"--step-length=" + bad}), "command line", {"--step-length"});
    expect_error(with({"--seed=" + bad}), "command line", {"--seed"});
    expect_error(with({"--max-lane-map-gb=" + bad}), "command line", {"--max-lane-map-gb"});
  }
  // Without '=', "-inf" reads as an option, so the value is missing: refused all the same.
  expect_error(with({"-e", "-inf"}), "command line", {"'-e'", "needs a value"});
  write_cfg("t.sumocfg", {"<end value=\"1e17\"/>"});
  expect_error(run({"info", "-c", "t.sumocfg"}), "t.sumocfg:5", {"<end>", "'1e17'"});
  // The bound itself is a time the run reaches and ends at.
  const auto r = with({"-b", "1e12"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace lpsim

#include "converters/cli_options.hpp"

#include <gtest/gtest.h>

#include <string>

#include "temp_dir.hpp"

namespace lpsim {
namespace {

using Args = std::vector<std::string>;

std::string error_of(const Args& args) {
  try {
    std::vector<std::string> rest;
    parse_cli_options(args, &rest);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

class CliOptionsTest : public ::testing::Test {
 protected:
  test::TempDir tmp_{"lpsim_cli"};
  std::string cfg_ =
      tmp_.write("run.sumocfg",
                 "<configuration>\n<input>\n<net-file value=\"cfg.net.xml\"/>\n"
                 "<route-files value=\"cfg.rou.xml\"/>\n</input>\n<time>\n<begin value=\"10\"/>\n"
                 "<end value=\"500\"/>\n</time>\n<seed value=\"7\"/>\n</configuration>\n");
};

TEST(SumoTimeTest, SecondsAndClockFormats) {
  EXPECT_EQ(parse_sumo_time("3600"), 3600.0);
  EXPECT_EQ(parse_sumo_time(" 0.25 "), 0.25);
  EXPECT_EQ(parse_sumo_time("-1"), -1.0);
  EXPECT_EQ(parse_sumo_time("1:00:00"), 3600.0);
  EXPECT_EQ(parse_sumo_time("0:01:30.5"), 90.5);
  EXPECT_EQ(parse_sumo_time("1:02:03:04"), 86400.0 + 2 * 3600 + 3 * 60 + 4);
  EXPECT_EQ(parse_sumo_time("-0:01:00"), -60.0);
  EXPECT_EQ(parse_sumo_time("25:00:00"), 90000.0);
  EXPECT_FALSE(parse_sumo_time("1:30"));
  EXPECT_FALSE(parse_sumo_time("1:2:3:4:5"));
  EXPECT_FALSE(parse_sumo_time("1::3"));
  EXPECT_FALSE(parse_sumo_time("1:-2:3"));
  EXPECT_FALSE(parse_sumo_time("1.5:00:00"));
  EXPECT_FALSE(parse_sumo_time("a:b:c"));
  EXPECT_FALSE(parse_sumo_time(""));
  EXPECT_FALSE(parse_sumo_time("nan"));
  EXPECT_FALSE(parse_sumo_time("10s"));
}

TEST(SumoBoolTest, AcceptsSumoSpellings) {
  for (const char* t : {"true", "TRUE", "yes", "on", "1", "x"}) EXPECT_EQ(parse_sumo_bool(t), true) << t;
  for (const char* f : {"false", "No", "off", "0", "-"}) EXPECT_EQ(parse_sumo_bool(f), false) << f;
  EXPECT_FALSE(parse_sumo_bool("2"));
  EXPECT_FALSE(parse_sumo_bool(""));
}

TEST(CliOptionsParse, BothValueFormsAndShortNames) {
  std::vector<std::string> rest;
  ConfigSpec c = parse_cli_options({"-n",
                                    "a.net.xml",
                                    "--route-files=r1.xml,r2.xml",
                                    "-a",
                                    "x.add.xml",
                                    "-b",
                                    "1:00:00",
                                    "--end=7200",
                                    "--step-length",
                                    "0.5",
                                    "--seed",
                                    "99",
                                    "--fcd-output",
                                    "fcd.xml",
                                    "--device.fcd.period=2",
                                    "--edgedata-output",
                                    "ed.xml",
                                    "--lanedata-output",
                                    "ld.xml",
                                    "--tripinfo-output",
                                    "ti.xml",
                                    "--summary-output",
                                    "su.xml",
                                    "--threads",
                                    "2",
                                    "--time-to-teleport",
                                    "-1",
                                    "--weights.minor-penalty",
                                    "4",
                                    "-o",
                                    "result.txt",
                                    "--lpsim-nodes",
                                    "nodes.csv",
                                    "--lpsim-edges=edges.csv",
                                    "--lpsim-od",
                                    "od.csv"},
                                   &rest);
  EXPECT_TRUE(rest.empty());
  EXPECT_EQ(c.net_file, "a.net.xml");
  EXPECT_EQ(c.route_files, (std::vector<std::string>{"r1.xml", "r2.xml"}));
  EXPECT_EQ(c.additional_files, (std::vector<std::string>{"x.add.xml"}));
  EXPECT_DOUBLE_EQ(c.begin, 3600);
  EXPECT_DOUBLE_EQ(c.end, 7200);
  EXPECT_DOUBLE_EQ(c.step_length, 0.5);
  EXPECT_EQ(c.seed, 99);
  EXPECT_EQ(c.outputs.fcd, "fcd.xml");
  EXPECT_DOUBLE_EQ(c.outputs.fcd_period, 2);
  EXPECT_EQ(c.outputs.edgedata, "ed.xml");
  EXPECT_EQ(c.outputs.lanedata, "ld.xml");
  EXPECT_EQ(c.outputs.tripinfo, "ti.xml");
  EXPECT_EQ(c.outputs.summary, "su.xml");
  EXPECT_EQ(c.threads, 2);
  EXPECT_DOUBLE_EQ(c.time_to_teleport, -1);
  EXPECT_DOUBLE_EQ(c.minor_penalty, 4);
  EXPECT_EQ(c.output_file, "result.txt");
  EXPECT_EQ(c.lpsim_nodes_csv, "nodes.csv");
  EXPECT_EQ(c.lpsim_edges_csv, "edges.csv");
  EXPECT_EQ(c.lpsim_od_csv, "od.csv");
  EXPECT_TRUE(c.config_file.empty());
  EXPECT_FALSE(c.ignore_route_errors);
}

TEST_F(CliOptionsTest, CommandLineOverridesConfigWhereverItAppears) {
  ConfigSpec c = parse_cli_options({"--end", "100", "-c", cfg_, "--seed=3"});
  EXPECT_EQ(c.config_file, cfg_);
  EXPECT_DOUBLE_EQ(c.end, 100);                                   // given before -c, still wins
  EXPECT_EQ(c.seed, 3);                                           // given after -c
  EXPECT_DOUBLE_EQ(c.begin, 10);                                  // from the cfg
  EXPECT_EQ(c.net_file, (tmp_.path() / "cfg.net.xml").string());  // cfg paths resolve against its folder
  ConfigSpec d =
      parse_cli_options({"-n", "mine.net.xml", "--configuration-file=" + cfg_, "-r", "a.xml b.xml"});
  EXPECT_EQ(d.net_file, "mine.net.xml");                                   // command-line paths stay as given
  EXPECT_EQ(d.route_files, (std::vector<std::string>{"a.xml", "b.xml"}));  // replaces the cfg's list
  EXPECT_EQ(d.seed, 7);
}

TEST_F(CliOptionsTest, PositionalArgumentsAreReturned) {
  std::vector<std::string> rest;
  ConfigSpec c = parse_cli_options({cfg_, "--ignore-route-errors", "extra", "--", "-n"}, &rest);
  EXPECT_EQ(rest, (std::vector<std::string>{cfg_, "extra", "-n"}));
  EXPECT_TRUE(c.ignore_route_errors);
  EXPECT_TRUE(c.net_file.empty());  // a positional cfg is not read as -c
  EXPECT_NE(error_of({"-c", cfg_, "-c", cfg_}).find("more than once"), std::string::npos);
  try {
    parse_cli_options({"-n", "a.net.xml", "stray"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'stray'"), std::string::npos) << e.what();
  }
}

TEST(CliOptionsParse, IgnoreRouteErrorsFlagForms) {
  EXPECT_TRUE(parse_cli_options({"--ignore-route-errors"}).ignore_route_errors);
  EXPECT_TRUE(parse_cli_options({"--ignore-route-errors", "true"}).ignore_route_errors);
  EXPECT_FALSE(parse_cli_options({"--ignore-route-errors", "false"}).ignore_route_errors);
  EXPECT_FALSE(parse_cli_options({"--ignore-route-errors=false"}).ignore_route_errors);
  ConfigSpec c = parse_cli_options({"--ignore-route-errors", "-n", "x.net.xml"});
  EXPECT_TRUE(c.ignore_route_errors);
  EXPECT_EQ(c.net_file, "x.net.xml");
}

TEST(CliOptionsParse, ErrorsNameTheOption) {
  EXPECT_NE(error_of({"--no-such-option", "1"}).find("--no-such-option"), std::string::npos);
  EXPECT_NE(error_of({"-z"}).find("'-z'"), std::string::npos);
  EXPECT_NE(error_of({"-n"}).find("'-n'"), std::string::npos);
  EXPECT_NE(error_of({"--fcd-output", "--seed", "3"}).find("--fcd-output"), std::string::npos);
  std::string msg = error_of({"--end", "later"});
  EXPECT_NE(msg.find("--end"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'later'"), std::string::npos) << msg;
  EXPECT_NE(error_of({"--ignore-route-errors=perhaps"}).find("'perhaps'"), std::string::npos);
  EXPECT_NE(error_of({"--output"}).find("--output"), std::string::npos);
  EXPECT_NE(error_of({"-c", "/nonexistent/run.sumocfg"}).find("/nonexistent/run.sumocfg"), std::string::npos);
  EXPECT_DOUBLE_EQ(parse_cli_options({"-e", "-1"}).end, -1);  // a negative number is a value, not an option
}

TEST(CliOptionsParse, StepLengthAndThreadsWithinRange) {
  for (const char* bad : {"0", "-1", "0.0005", "1e-30", "86401", "1e30"}) {
    const std::string msg = error_of({"--step-length", bad});
    EXPECT_NE(msg.find("from 0.001 to 86400 s"), std::string::npos) << bad << ": " << msg;
  }
  EXPECT_DOUBLE_EQ(parse_cli_options({"--step-length", "0.001"}).step_length, 0.001);
  EXPECT_DOUBLE_EQ(parse_cli_options({"--step-length", "86400"}).step_length, 86400);
  for (const char* bad : {"-1", "1025", "100000"}) {
    const std::string msg = error_of({"--threads", bad});
    EXPECT_NE(msg.find("from 0 to 1024"), std::string::npos) << bad << ": " << msg;
  }
  EXPECT_EQ(parse_cli_options({"--threads", "1024"}).threads, 1024);
}

}  // namespace
}  // namespace lpsim

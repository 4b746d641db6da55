// SUMO's jam teleports (MSLane::executeMovements): only the first vehicle of a lane teleports once it has
// waited --time-to-teleport; the ones behind it keep waiting, move up into the room it leaves, and their
// clocks start again. A queue at a light that stays red (a 200 m approach made with netconvert, ten cars at
// 5 s intervals, --time-to-teleport 100), run by the real sumo and by lpsim: both teleport the head about
// every 105 s (the wait plus the move up), one at a time, and name the cause "yield" (a red light has no
// priority). LPSim teleported every vehicle whose own clock ran out, two at a time after the first (eight
// against SUMO's six by 700 s), and called them "jam".
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;
using test::Teleport;
using test::teleports;
using test::TempDir;

TEST(TeleportRuleTest, OnlyTheFirstVehicleOfALaneTeleportsAsInSumo) {
  if (!test::have_sumo_tool("sumo") || !test::have_sumo_tool("netconvert"))
    GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_teleport_rule");
  dir.write("n.nod.xml",
            "<nodes><node id=\"a\" x=\"0\" y=\"0\"/><node id=\"b\" x=\"200\" y=\"0\" type=\"traffic_light\"/>"
            "<node id=\"c\" x=\"400\" y=\"0\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"ab\" from=\"a\" to=\"b\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"bc\" from=\"b\" to=\"c\" numLanes=\"1\" speed=\"13.89\"/></edges>\n");
  dir.write("red.add.xml",
            "<additional><tlLogic id=\"b\" type=\"static\" programID=\"red\" offset=\"0\">"
            "<phase duration=\"1000\" state=\"r\"/></tlLogic></additional>\n");
  dir.write("r.rou.xml",
            "<routes><flow id=\"q\" from=\"ab\" to=\"bc\" begin=\"0\" end=\"50\" period=\"5\"/></routes>\n");
  const CliResult net =
      test::run_program(dir.path(), {"netconvert"},
                        {"-n", "n.nod.xml", "-e", "n.edg.xml", "--no-turnarounds", "-o", "n.net.xml"});
  ASSERT_EQ(net.exit_code, 0) << net.err;
  const std::vector<std::string> common{"-n",          "n.net.xml",          "-r",  "r.rou.xml", "-a",
                                        "red.add.xml", "--time-to-teleport", "100", "--end",     "700"};
  std::vector<std::string> sumo_args = common;
  sumo_args.push_back("--no-step-log");
  const CliResult sumo = test::run_program(dir.path(), {"sumo"}, sumo_args);
  ASSERT_EQ(sumo.exit_code, 0) << sumo.err;
  std::vector<std::string> lpsim_args{"run"};
  lpsim_args.insert(lpsim_args.end(), common.begin(), common.end());
  const CliResult lpsim = test::run_lpsim(dir.path(), lpsim_args);
  ASSERT_EQ(lpsim.exit_code, 0) << lpsim.err;

  const std::vector<Teleport> s = teleports(sumo.err + sumo.out), l = teleports(lpsim.err + lpsim.out);
  ASSERT_EQ(s.size(), 6u) << sumo.err;
  ASSERT_EQ(l.size(), s.size()) << lpsim.err;
  for (size_t k = 0; k < s.size(); ++k) {
    EXPECT_EQ(l[k].id, s[k].id);
    EXPECT_EQ(l[k].cause, "yield");
    EXPECT_EQ(s[k].cause, "yield");
    EXPECT_NEAR(l[k].time, s[k].time, 10.0) << l[k].id;
  }
}

}  // namespace
}  // namespace lpsim

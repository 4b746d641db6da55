// SUMO's --time-to-teleport.highways (MSLane::executeMovements): on a road faster than
// --time-to-teleport.highways.min-speed (69 km/h by default), the first vehicle of a lane that does not lead
// on along its route teleports once it has waited that long, whatever --time-to-teleport says. A 2-lane,
// 30 m/s approach to a light that stays red, whose left lane has no connection onward (netconvert): forty
// cars fill the right lane first, then ten more come on the left lane and cannot merge. Run by the real sumo
// and by lpsim with --time-to-teleport 1000 (never within the run): both teleport left-lane vehicles only,
// for "wrong lane, highway" (SUMO 7 by 700 s, LPSim 8: SUMO lets a few follow the head within seconds, LPSim
// one each time its clock runs out again); without the option, or above the minimum speed, nobody
// teleports. LPSim refused the option before.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::Teleport;
using test::teleports;
using test::TempDir;

class TeleportHighwaysTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("sumo") || !test::have_sumo_tool("netconvert"))
      GTEST_SKIP() << "SUMO not installed";
    dir_.write(
        "n.nod.xml",
        "<nodes><node id=\"a\" x=\"0\" y=\"0\"/><node id=\"b\" x=\"300\" y=\"0\" type=\"traffic_light\"/>"
        "<node id=\"c\" x=\"600\" y=\"0\"/></nodes>\n");
    dir_.write("n.edg.xml",
               "<edges><edge id=\"ab\" from=\"a\" to=\"b\" numLanes=\"2\" speed=\"30\"/>"
               "<edge id=\"bc\" from=\"b\" to=\"c\" numLanes=\"1\" speed=\"30\"/></edges>\n");
    dir_.write(
        "n.con.xml",
        "<connections><connection from=\"ab\" to=\"bc\" fromLane=\"0\" toLane=\"0\"/></connections>\n");
    dir_.write("red.add.xml",
               "<additional><tlLogic id=\"b\" type=\"static\" programID=\"red\" offset=\"0\">"
               "<phase duration=\"1000\" state=\"r\"/></tlLogic></additional>\n");
    dir_.write(
        "r.rou.xml",
        "<routes><flow id=\"right\" from=\"ab\" to=\"bc\" begin=\"0\" end=\"80\" period=\"2\" "
        "departLane=\"0\"/><flow id=\"left\" from=\"ab\" to=\"bc\" begin=\"100\" end=\"150\" period=\"5\" "
        "departLane=\"1\"/></routes>\n");
    const CliResult net = test::run_program(
        dir_.path(), {"netconvert"},
        {"-n", "n.nod.xml", "-e", "n.edg.xml", "-x", "n.con.xml", "--no-turnarounds", "-o", "n.net.xml"});
    ASSERT_EQ(net.exit_code, 0) << net.err;
  }

  // The teleports of sumo and of lpsim with `extra` options.
  std::pair<std::vector<Teleport>, std::vector<Teleport>> run(const std::vector<std::string>& extra) {
    std::vector<std::string> common{"-n",          "n.net.xml",          "-r",   "r.rou.xml", "-a",
                                    "red.add.xml", "--time-to-teleport", "1000", "--end",     "700"};
    common.insert(common.end(), extra.begin(), extra.end());
    std::vector<std::string> sumo_args = common;
    sumo_args.push_back("--no-step-log");
    const CliResult sumo = test::run_program(dir_.path(), {"sumo"}, sumo_args);
    EXPECT_EQ(sumo.exit_code, 0) << sumo.err;
    std::vector<std::string> lpsim_args{"run"};
    lpsim_args.insert(lpsim_args.end(), common.begin(), common.end());
    const CliResult lpsim = test::run_lpsim(dir_.path(), lpsim_args);
    EXPECT_EQ(lpsim.exit_code, 0) << lpsim.err;
    return {teleports(sumo.err + sumo.out), teleports(lpsim.err + lpsim.out)};
  }

  TempDir dir_{"lpsim_teleport_highways"};
};

TEST_F(TeleportHighwaysTest, WrongLaneHeadsOfAFastRoadTeleportAsInSumo) {
  const auto [s, l] = run({"--time-to-teleport.highways", "60"});
  ASSERT_GE(s.size(), 5u);
  EXPECT_NEAR(static_cast<double>(l.size()), static_cast<double>(s.size()), 2.0);
  for (const auto* side : {&s, &l}) {
    for (const Teleport& t : *side) {
      EXPECT_EQ(t.cause, "wrong lane, highway") << t.id;
      EXPECT_EQ(t.id.rfind("left.", 0), 0u) << t.id;
      EXPECT_GE(t.time, 160.0) << t.id;  // the first left car came at 100 s and waits 60 s
    }
  }
}

TEST_F(TeleportHighwaysTest, AboveTheMinimumSpeedNobodyTeleports) {
  const auto [s, l] =
      run({"--time-to-teleport.highways", "60", "--time-to-teleport.highways.min-speed", "31"});
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(l.empty());
}

TEST_F(TeleportHighwaysTest, WithoutTheOptionNobodyTeleports) {
  const auto [s, l] = run({});
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(l.empty());
}

}  // namespace
}  // namespace lpsim

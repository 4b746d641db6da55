// SUMO's junction-blocking rule stops looking ahead at a red signal: two traffic lights 6.1 m apart (a
// split junction, as real nets have them) switch in opposite phases, so a driver leaving the first on green
// always meets red at the second and must wait on the 6.1 m edge between, which holds a car but not a car and
// its gap. SUMO's drivers enter (the red light ends MSVehicle::checkRewindLinkLanes' look-ahead without
// counting as a standing vehicle) and cross one per cycle; LPSim counted the red light as the end of the
// room, so its drivers never entered and stood at the first light until teleported.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::TempDir;

void write_scenario(const TempDir& dir) {
  // The one-way side road N -> S crosses at B, so the main road's link there has a foe and keeps clear.
  dir.write("n.nod.xml",
            "<nodes><node id=\"A\" x=\"0\" y=\"0\"/><node id=\"B\" x=\"100\" y=\"0\" type=\"traffic_light\"/>"
            "<node id=\"C\" x=\"106.1\" y=\"0\" type=\"traffic_light\"/><node id=\"D\" x=\"206.1\" y=\"0\"/>"
            "<node id=\"N\" x=\"100\" y=\"100\"/><node id=\"S\" x=\"100\" y=\"-100\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"in\" from=\"A\" to=\"B\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"mid\" from=\"B\" to=\"C\" numLanes=\"1\" speed=\"13.89\" length=\"6.1\"/>"
            "<edge id=\"out\" from=\"C\" to=\"D\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"side\" from=\"N\" to=\"B\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"sideout\" from=\"B\" to=\"S\" numLanes=\"1\" speed=\"13.89\"/></edges>\n");
  // Every link of B shows the same colour, so the program does not depend on netconvert's link order; C
  // has the one link mid -> out. C is red while B is green and green while B is red.
  dir.write("n.tll.xml",
            "<tlLogics><tlLogic id=\"B\" type=\"static\" programID=\"0\" offset=\"0\">"
            "<phase duration=\"30\" state=\"GGGG\"/><phase duration=\"3\" state=\"yyyy\"/>"
            "<phase duration=\"30\" state=\"rrrr\"/></tlLogic>"
            "<tlLogic id=\"C\" type=\"static\" programID=\"0\" offset=\"0\">"
            "<phase duration=\"30\" state=\"r\"/><phase duration=\"30\" state=\"G\"/>"
            "<phase duration=\"3\" state=\"y\"/></tlLogic></tlLogics>\n");
  dir.write("r.rou.xml",
            "<routes><flow id=\"m\" begin=\"0\" end=\"900\" vehsPerHour=\"40\"><route edges=\"in mid out\"/>"
            "</flow></routes>\n");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(
      dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-i", "n.tll.xml", "--no-turnarounds", "-o", "n.net.xml"}));
}

TEST(JunctionRoomAtSignalTest, EntersTheJunctionWhenOnlyARedLightLiesAheadAsSumoDoes) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_junction_room_signal");
  ASSERT_NO_FATAL_FAILURE(write_scenario(dir));
  for (const char* model : {"Krauss", "IDM"}) {
    const test::SumoAndLpsim r = test::run_sumo_and_lpsim(
        dir, {"-n", "n.net.xml", "-r", "r.rou.xml", "--default.carfollowmodel", model});
    ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
    ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
    EXPECT_EQ(r.sumo.err.find("Teleporting"), std::string::npos) << r.sumo.err;
    EXPECT_EQ(r.lpsim.err.find("Teleporting"), std::string::npos) << model << ": " << r.lpsim.err;
    const test::FlowTrips sumo = test::flow_trips(r.sumo_tripinfo, "m");
    const test::FlowTrips lpsim = test::flow_trips(r.lpsim_tripinfo, "m");
    EXPECT_EQ(lpsim.count, sumo.count) << model;
    EXPECT_NEAR(lpsim.mean_duration, sumo.mean_duration, 0.15 * sumo.mean_duration)
        << model << ": SUMO " << sumo.mean_duration << " s";
  }
}

}  // namespace
}  // namespace lpsim

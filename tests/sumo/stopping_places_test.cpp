// Stopping places and stops that SUMO accepts load as SUMO places them, against the real sumo on a road made
// with netconvert beside a rail track: a bus stop 0.1 m long at the very end of an 11.95 m lane and one
// reaching past its lane's end (friendlyPos), one given from the lane's end (negative positions), a car's
// lane stop beyond the lane (friendlyPos) on its last edge, and a train stop on the rail track, which LPSim
// leaves out with the train that uses it (one warning). Every stop is made as in SUMO, before arriving at
// the lane's end. A road vehicle that would stop on the rail track is refused naming it, as SUMO refuses it.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::TempDir;

void write_scenario(const TempDir& dir) {
  dir.write("n.nod.xml",
            "<nodes><node id=\"a\" x=\"0\" y=\"0\"/><node id=\"b\" x=\"500\" y=\"0\"/>"
            "<node id=\"c\" x=\"511.95\" y=\"0\"/><node id=\"d\" x=\"1000\" y=\"0\"/>"
            "<node id=\"r1\" x=\"0\" y=\"100\"/><node id=\"r2\" x=\"1000\" y=\"100\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"ab\" from=\"a\" to=\"b\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"bc\" from=\"b\" to=\"c\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"cd\" from=\"c\" to=\"d\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"rail\" from=\"r1\" to=\"r2\" numLanes=\"1\" speed=\"30\" allow=\"rail\"/></edges>\n");
  dir.write("s.add.xml", R"X(<additional>
  <busStop id="short" lane="bc_0" startPos="11.85" endPos="11.95" friendlyPos="1"/>
  <busStop id="beyond" lane="cd_0" startPos="480" endPos="520" friendlyPos="true"/>
  <busStop id="fromEnd" lane="ab_0" startPos="-60" endPos="-40"/>
  <trainStop id="station" lane="rail_0" startPos="400" endPos="600"/>
</additional>
)X");
  dir.write("r.rou.xml", R"X(<routes>
  <vType id="bus" vClass="bus" length="12" sigma="0"/>
  <vType id="train" vClass="rail" length="100"/>
  <vehicle id="train0" type="train" depart="0"><route edges="rail"/><stop trainStop="station" duration="30"/></vehicle>
  <vehicle id="bus0" type="bus" depart="0"><route edges="ab bc cd"/>
    <stop busStop="fromEnd" duration="10"/><stop busStop="short" duration="10"/><stop busStop="beyond" duration="10"/>
  </vehicle>
  <vehicle id="car0" depart="5"><route edges="ab bc cd"/><stop lane="cd_0" endPos="600" friendlyPos="true" duration="5"/></vehicle>
</routes>
)X");
  dir.write("bad.rou.xml",
            "<routes>\n<vehicle id=\"car1\" depart=\"0\"><route edges=\"ab bc cd\"/>"
            "<stop trainStop=\"station\" duration=\"5\"/></vehicle>\n</routes>\n");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
}

struct Trip {
  double arrival = -1, stop_time = -1;
};

Trip trip_of(const std::string& tripinfo, const std::string& id) {
  const std::regex line("<tripinfo id=\"" + id +
                        R"re("[^>]* arrival="([0-9.]+)"[^>]* stopTime="([0-9.]+)")re");
  std::smatch m;
  if (!std::regex_search(tripinfo, m, line)) return {};
  return Trip{std::stod(m[1]), std::stod(m[2])};
}

TEST(StoppingPlacesTest, PlacesSumoAcceptsAreUsedWhereSumoPutsThem) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_stopping_places");
  ASSERT_NO_FATAL_FAILURE(write_scenario(dir));
  const test::SumoAndLpsim r =
      test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-a", "s.add.xml", "-r", "r.rou.xml"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  EXPECT_NE(r.lpsim.err.find("stopping place on a lane no road vehicle may use 1"), std::string::npos)
      << r.lpsim.err;
  EXPECT_NE(r.lpsim.err.find("1 vehicles skipped"), std::string::npos) << r.lpsim.err;  // the train
  for (const char* id : {"bus0", "car0"}) {
    SCOPED_TRACE(id);
    const Trip s = trip_of(r.sumo_tripinfo, id), l = trip_of(r.lpsim_tripinfo, id);
    ASSERT_GE(s.arrival, 0);
    ASSERT_GE(l.arrival, 0);
    EXPECT_EQ(l.stop_time, s.stop_time);  // bus0: 30 s at three stops, car0: 5 s
    EXPECT_NEAR(l.arrival, s.arrival, 0.05 * s.arrival);
  }
  const CliResult bad =
      test::run_lpsim(dir.path(), {"run", "-n", "n.net.xml", "-a", "s.add.xml", "-r", "bad.rou.xml"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("vehicle 'car1': may not stop at 'station'"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace lpsim

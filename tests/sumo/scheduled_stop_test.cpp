// Scheduled stops (<stop>, <busStop>) as SUMO makes them, against the real sumo on a road made with
// netconvert (a 2-lane edge, then a 1-lane edge): buses stopping at bus stops for a duration, on a lane
// position, until a time; a second bus queueing behind the first at the same stop; a trip routed through its
// stop's edge; a named route's stops made before the vehicle's own; a flow whose `until` is later for each
// of its vehicles by its depart offset; cars passing the stopped buses. Each vehicle's stop time, waiting
// time (stops are not waiting) and arrival agree with SUMO's. Before LPSim made stops it counted them as
// unsupported and drove through: every stopTime 0 and the buses 20-70 s early.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::TempDir;

void write_scenario(const TempDir& dir) {
  dir.write("n.nod.xml",
            "<nodes><node id=\"a\" x=\"0\" y=\"0\"/><node id=\"b\" x=\"500\" y=\"0\"/>"
            "<node id=\"c\" x=\"1000\" y=\"0\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"ab\" from=\"a\" to=\"b\" numLanes=\"2\" speed=\"13.89\"/>"
            "<edge id=\"bc\" from=\"b\" to=\"c\" numLanes=\"1\" speed=\"13.89\"/></edges>\n");
  dir.write("s.add.xml",
            "<additional><busStop id=\"bs1\" lane=\"ab_0\" startPos=\"200\" endPos=\"220\"/>"
            "<busStop id=\"bs2\" lane=\"bc_0\" startPos=\"300\" endPos=\"330\"/></additional>\n");
  dir.write("r.rou.xml", R"X(<routes>
  <vType id="bus" vClass="bus" length="12" accel="1.2" decel="4" sigma="0"/>
  <vType id="car" sigma="0"/>
  <route id="R" edges="ab bc"><stop lane="bc_0" endPos="200" duration="7"/></route>
  <vehicle id="bus0" type="bus" depart="0" departLane="1"><route edges="ab bc"/>
    <stop busStop="bs1" duration="20"/>
    <stop lane="bc_0" endPos="100" duration="5"/>
    <stop busStop="bs2" until="150"/>
  </vehicle>
  <vehicle id="bus1" type="bus" depart="3" departLane="0"><route edges="ab bc"/>
    <stop busStop="bs1" duration="20"/>
  </vehicle>
  <flow id="car" type="car" begin="5" end="60" period="4" departLane="0"><route edges="ab bc"/></flow>
  <trip id="trip" type="bus" depart="200" from="ab" to="bc"><stop lane="bc_0" endPos="100" duration="5"/></trip>
  <vehicle id="named" type="bus" depart="300" route="R"><stop lane="bc_0" endPos="300" duration="3"/></vehicle>
  <flow id="f" type="bus" begin="400" end="430" period="10" route="R"><stop lane="bc_0" endPos="300" until="450"/></flow>
</routes>
)X");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
}

struct Trip {
  double arrival = 0, waiting = 0, stop_time = 0;
};

std::map<std::string, Trip> trips_of(const std::string& tripinfo) {
  std::map<std::string, Trip> out;
  const std::regex line(R"re(<tripinfo id="([^"]+)"[^>]* arrival="([0-9.]+)"[^>]* waitingTime="([0-9.]+)")re"
                        R"re([^>]* stopTime="([0-9.]+)")re");
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), line); it != std::sregex_iterator();
       ++it)
    out[(*it)[1]] = Trip{std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4])};
  return out;
}

TEST(ScheduledStopTest, BusesStopAsInSumo) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_scheduled_stop");
  ASSERT_NO_FATAL_FAILURE(write_scenario(dir));
  const test::SumoAndLpsim r =
      test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-r", "r.rou.xml", "-a", "s.add.xml"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  EXPECT_EQ(r.lpsim.err.find("stop"), std::string::npos) << "no stop is skipped: " << r.lpsim.err;

  const auto s = trips_of(r.sumo_tripinfo);
  const auto l = trips_of(r.lpsim_tripinfo);
  for (const char* id : {"bus0", "bus1", "trip", "named", "f.0", "f.1", "f.2"}) {
    ASSERT_TRUE(s.count(id) && l.count(id)) << id;
    const Trip& a = s.at(id);
    const Trip& b = l.at(id);
    EXPECT_GT(a.stop_time, 0) << id;
    EXPECT_NEAR(b.stop_time, a.stop_time, 5.0) << id;
    EXPECT_NEAR(b.waiting, a.waiting, 5.0) << id;
    EXPECT_NEAR(b.arrival, a.arrival, 5.0) << id;
  }
  // Stops whose times do not depend on how the bus got there are made exactly as SUMO makes them.
  for (const char* id : {"trip", "named", "f.0", "f.1", "f.2"})
    EXPECT_EQ(l.at(id).stop_time, s.at(id).stop_time) << id;
  EXPECT_EQ(l.at("bus0").waiting, 0);  // standing at a stop is not waiting
}

}  // namespace
}  // namespace lpsim

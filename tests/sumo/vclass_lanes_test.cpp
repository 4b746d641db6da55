// Vehicle classes per lane, on a net netconvert makes from plain XML (below): edge "in" (3 lanes; lane 0 a
// bus lane, allow="bus") splits at n1 into "out" (2 lanes) and "busway" (2 lanes; lane 0 allow="bus"), and
// the only connection onto busway is in_0 -> busway_0, between bus lanes. Flows: cars and buses on in-out,
// buses on in-busway (the bus-only connection), vClass "ignoring" on both routes.
// Checked against LPSim's outputs and, where SUMO is installed, against sumo 1.15 on the same files: every
// flow's arrivals equal SUMO's (150/10/20/10/10), no car is ever on a bus lane (FCD), buses drive the
// bus-only connection, "ignoring" vehicles are inserted and drive both routes. A car whose route needs the
// bus-only connection is an error naming it (SUMO: "has no valid route"), skipped with
// --ignore-route-errors; so is a car given departLane 0 (the bus lane). Routing (trips) finds a path per
// class. Needs netconvert (skipped without it); the SUMO comparison also needs sumo.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
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

const char* kNodes = R"(<nodes>
  <node id="n0" x="0" y="0" type="priority"/>
  <node id="n1" x="300" y="0" type="priority"/>
  <node id="n2" x="600" y="0" type="priority"/>
  <node id="n3" x="300" y="-300" type="priority"/>
</nodes>
)";
const char* kEdges = R"(<edges>
  <edge id="in" from="n0" to="n1" numLanes="3" speed="13.89"><lane index="0" allow="bus"/></edge>
  <edge id="out" from="n1" to="n2" numLanes="2" speed="13.89"/>
  <edge id="busway" from="n1" to="n3" numLanes="2" speed="13.89"><lane index="0" allow="bus"/></edge>
</edges>
)";
const char* kConnections = R"(<connections>
  <connection from="in" to="out" fromLane="1" toLane="0"/>
  <connection from="in" to="out" fromLane="2" toLane="1"/>
  <connection from="in" to="busway" fromLane="0" toLane="0"/>
</connections>
)";
const char* kVTypes = R"(  <vType id="car" vClass="passenger"/>
  <vType id="bus" vClass="bus" length="12"/>
  <vType id="ign" vClass="ignoring"/>
  <route id="straight" edges="in out"/>
  <route id="busonly" edges="in busway"/>
)";
const char* kFlows = R"(  <flow id="cars" type="car" route="straight" begin="0" end="600" vehsPerHour="900"/>
  <flow id="buses" type="bus" route="busonly" begin="0" end="600" vehsPerHour="120"/>
  <flow id="busstraight" type="bus" route="straight" begin="0" end="600" vehsPerHour="60"/>
  <flow id="ignb" type="ign" route="busonly" begin="0" end="600" vehsPerHour="60"/>
  <flow id="igns" type="ign" route="straight" begin="0" end="600" vehsPerHour="60"/>
)";

const std::vector<std::string> kFlowIds = {"cars", "buses", "busstraight", "ignb", "igns"};

size_t count(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<size_t>(std::distance(std::sregex_iterator(text.begin(), text.end(), re), {}));
}

// Arrivals per flow in a tripinfo file.
std::map<std::string, size_t> arrivals(const std::string& tripinfo) {
  std::map<std::string, size_t> n;
  for (const auto& f : kFlowIds) n[f] = count(tripinfo, "<tripinfo id=\"" + f + "\\.[0-9]+\"");
  return n;
}

// Lanes the vehicles of flow `flow` stood on in an FCD file (one entry per lane id seen).
std::map<std::string, size_t> fcd_lanes(const std::string& fcd, const std::string& flow) {
  std::map<std::string, size_t> lanes;
  const std::regex re("<vehicle id=\"" + flow + "\\.[0-9]+\"[^>]*lane=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(fcd.begin(), fcd.end(), re); it != std::sregex_iterator(); ++it)
    ++lanes[(*it)[1].str()];
  return lanes;
}

class VClassLanesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("netconvert")) GTEST_SKIP() << "netconvert not found (SUMO not installed)";
    dir_.write("n.nod.xml", kNodes);
    dir_.write("n.edg.xml", kEdges);
    dir_.write("n.con.xml", kConnections);
    const std::string cmd = "cd '" + dir_.path().string() +
                            "' && netconvert -n n.nod.xml -e n.edg.xml -x n.con.xml --no-turnarounds "
                            "-o net.net.xml > netconvert.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir_.path() / "netconvert.txt");
  }

  // A config over net.net.xml and a route file holding the vTypes, routes and `body`.
  std::string scenario(const std::string& name, const std::string& body) {
    dir_.write(name + ".rou.xml", std::string("<routes>\n") + kVTypes + body + "</routes>\n");
    dir_.write(name + ".sumocfg",
               "<configuration><input><net-file value=\"net.net.xml\"/><route-files value=\"" + name +
                   ".rou.xml\"/></input><time><begin value=\"0\"/><end value=\"900\"/>"
                   "</time></configuration>\n");
    return name + ".sumocfg";
  }

  TempDir dir_{"lpsim_vclass"};
};

TEST_F(VClassLanesTest, ClassesUseTheirLanesAndArriveAsInSumo) {
  const std::string cfg = scenario("flows", kFlows);
  const CliResult r = run_lpsim(dir_.path(), {"run", "-c", cfg, "--tripinfo-output", "lpsim_trips.xml",
                                              "--fcd-output", "lpsim_fcd.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string fcd = read_file(dir_.path() / "lpsim_fcd.xml");
  const auto ours = arrivals(read_file(dir_.path() / "lpsim_trips.xml"));
  // Every vehicle of every flow arrives (the base refused the whole scenario over the bus-only connection).
  EXPECT_EQ(ours.at("cars"), 150u);
  EXPECT_EQ(ours.at("buses"), 20u);
  EXPECT_EQ(ours.at("busstraight"), 10u);
  EXPECT_EQ(ours.at("ignb"), 10u);
  EXPECT_EQ(ours.at("igns"), 10u);
  // Cars never on a bus lane, and on busway never at all.
  const auto car_lanes = fcd_lanes(fcd, "cars");
  EXPECT_FALSE(car_lanes.empty());
  for (const auto& [lane, n] : car_lanes) {
    EXPECT_NE(lane, "in_0") << n << " car positions on the bus lane";
    EXPECT_EQ(lane.rfind("busway", 0), std::string::npos) << lane;
  }
  // Buses take the bus-only connection onto busway's bus lane, and only bus lanes on that route.
  const auto bus_lanes = fcd_lanes(fcd, "buses");
  EXPECT_GT(bus_lanes.count("busway_0") ? bus_lanes.at("busway_0") : 0u, 0u);
  EXPECT_EQ(bus_lanes.count("busway_1"), 0u);
  EXPECT_EQ(bus_lanes.count("in_1") + bus_lanes.count("in_2"), 0u);
  // Buses going straight leave the bus lane for a lane with a connection to out.
  const auto straight = fcd_lanes(fcd, "busstraight");
  EXPECT_GT(straight.count("out_0") + straight.count("out_1"), 0u);
  // "ignoring" vehicles drive the bus-only connection too.
  EXPECT_GT(fcd_lanes(fcd, "ignb").count("busway_0"), 0u);

  if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "sumo not found: LPSim checked alone";
  const std::string cmd = "cd '" + dir_.path().string() + "' && sumo -c " + cfg +
                          " --tripinfo-output sumo_trips.xml --fcd-output sumo_fcd.xml --no-step-log"
                          " > sumo.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir_.path() / "sumo.txt");
  const auto theirs = arrivals(read_file(dir_.path() / "sumo_trips.xml"));
  for (const auto& f : kFlowIds) EXPECT_EQ(ours.at(f), theirs.at(f)) << "flow " << f;
  for (const auto& [lane, n] : fcd_lanes(read_file(dir_.path() / "sumo_fcd.xml"), "cars"))
    EXPECT_NE(lane, "in_0") << "SUMO's cars on the bus lane: the net is not what this test assumes";
}

TEST_F(VClassLanesTest, CarOnBusOnlyConnectionIsAnErrorNamingIt) {
  const std::string body = R"(  <vehicle id="c0" type="car" route="busonly" depart="0"/>
  <vehicle id="c1" type="car" route="straight" depart="5"/>
)";
  const std::string cfg = scenario("carbus", body);
  const CliResult r = run_lpsim(dir_.path(), {"run", "-c", cfg});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'c0'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no connection between edge 'in' and edge 'busway'"), std::string::npos) << r.err;
  // As SUMO with --ignore-route-errors: the car is skipped, the other one drives.
  const CliResult ok =
      run_lpsim(dir_.path(), {"run", "-c", cfg, "--ignore-route-errors", "--tripinfo-output", "t.xml"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string trips = read_file(dir_.path() / "t.xml");
  EXPECT_EQ(count(trips, "<tripinfo id=\"c1\""), 1u);
  EXPECT_EQ(count(trips, "<tripinfo id=\"c0\""), 0u);
}

TEST_F(VClassLanesTest, CarGivenTheBusLaneIsAnError) {
  const std::string cfg =
      scenario("lane0", R"(  <vehicle id="c3" type="car" route="straight" depart="0" departLane="0"/>
  <vehicle id="b3" type="bus" route="straight" depart="1" departLane="0"/>
)");
  const CliResult r = run_lpsim(dir_.path(), {"run", "-c", cfg});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'c3'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("departLane 0"), std::string::npos) << r.err;
  const CliResult ok =
      run_lpsim(dir_.path(), {"run", "-c", cfg, "--ignore-route-errors", "--tripinfo-output", "t.xml"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string trips = read_file(dir_.path() / "t.xml");
  EXPECT_EQ(count(trips, "<tripinfo id=\"b3\""), 1u);  // the bus may depart on the bus lane
  EXPECT_EQ(count(trips, "<tripinfo id=\"c3\""), 0u);
}

TEST_F(VClassLanesTest, TripsAreRoutedPerClass) {
  // A bus trip to busway finds the bus-only connection; a car trip there has no route (SUMO: "No route for
  // vehicle"), and is skipped with --ignore-route-errors.
  const std::string cfg = scenario("trips", R"(  <trip id="bt" type="bus" depart="0" from="in" to="busway"/>
  <trip id="it" type="ign" depart="1" from="in" to="busway"/>
  <trip id="ct" type="car" depart="2" from="in" to="busway"/>
)");
  const CliResult r = run_lpsim(dir_.path(), {"run", "-c", cfg});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'ct'"), std::string::npos) << r.err;
  const CliResult ok =
      run_lpsim(dir_.path(), {"run", "-c", cfg, "--ignore-route-errors", "--tripinfo-output", "t.xml"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string trips = read_file(dir_.path() / "t.xml");
  EXPECT_EQ(count(trips, "<tripinfo id=\"bt\""), 1u);
  EXPECT_EQ(count(trips, "<tripinfo id=\"it\""), 1u);
  EXPECT_EQ(count(trips, "<tripinfo id=\"ct\""), 0u);
}

}  // namespace
}  // namespace lpsim

// Settings real scenarios use, implemented as SUMO defines them, each run by the real sumo and by lpsim on
// the same small scenario: --tls.all-off (SUMO's game scenarios), --max-depart-delay (the DLR bus network),
// --weights.random-factor (SUMO's grid game), --tripinfo-output.write-undeparted / write-unfinished,
// --ignore-junction-blocker (the DLR bus network).
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;
using test::TempDir;

const std::string kGridDir = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls";

// The bundled 5x5 signalised grid copied into `dir`.
void copy_grid(const TempDir& dir) {
  for (const char* f : {"grid_tls.net.xml", "grid_tls.rou.xml", "grid_tls.sumocfg"})
    dir.write(f, read_file(kGridDir + "/" + f));
}

int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

double mean_duration(const std::string& tripinfo) {
  const std::regex duration(R"re(<tripinfo [^>]* duration="([0-9.]+)")re");
  double sum = 0;
  int n = 0;
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), duration);
       it != std::sregex_iterator(); ++it, ++n)
    sum += std::stod((*it)[1]);
  return n > 0 ? sum / n : 0.0;
}

// Every traffic light off: the junctions give way as netconvert's off-states say ('o' yield, 'O' priority),
// as at priority junctions. On the bundled grid SUMO's mean trip falls from 129.4 s to 88.7 s; LPSim's must
// fall alike and stay within 5 % of SUMO's.
TEST(SumoSettingsTest, TrafficLightsSwitchedOffGiveWayAsInSumo) {
  if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_tls_off");
  copy_grid(dir);
  const test::SumoAndLpsim on = test::run_sumo_and_lpsim(dir, {"-c", "grid_tls.sumocfg"});
  ASSERT_EQ(on.lpsim.exit_code, 0) << on.lpsim.err;
  const double lpsim_on = mean_duration(on.lpsim_tripinfo);
  const test::SumoAndLpsim off = test::run_sumo_and_lpsim(dir, {"-c", "grid_tls.sumocfg", "--tls.all-off"});
  ASSERT_EQ(off.sumo.exit_code, 0) << off.sumo.err;
  ASSERT_EQ(off.lpsim.exit_code, 0) << off.lpsim.err;
  EXPECT_EQ(count_of(off.lpsim_tripinfo, "<tripinfo "), count_of(off.sumo_tripinfo, "<tripinfo "));
  const double sumo_off = mean_duration(off.sumo_tripinfo), lpsim_off = mean_duration(off.lpsim_tripinfo);
  EXPECT_NEAR(lpsim_off, sumo_off, 0.05 * sumo_off) << "SUMO " << sumo_off << " s, LPSim " << lpsim_off;
  EXPECT_LT(lpsim_off, 0.8 * lpsim_on) << "switching the lights off changed nothing";
}

// A single-lane road offered 3600 veh/h for 10 minutes with --max-depart-delay 10: SUMO inserts 204 and drops
// the others silently; dropped vehicles end (summary's ended) without arriving and have no tripinfo line.
TEST(SumoSettingsTest, VehiclesNotInsertedInTimeAreDroppedAsInSumo) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_max_depart_delay");
  dir.write("n.nod.xml",
            "<nodes><node id=\"A\" x=\"0\" y=\"0\"/><node id=\"B\" x=\"500\" y=\"0\"/>"
            "<node id=\"C\" x=\"1000\" y=\"0\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"AB\" from=\"A\" to=\"B\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"BC\" from=\"B\" to=\"C\" numLanes=\"1\" speed=\"13.89\"/></edges>\n");
  dir.write("r.rou.xml",
            "<routes><route id=\"r\" edges=\"AB BC\"/>"
            "<flow id=\"f\" begin=\"0\" end=\"600\" vehsPerHour=\"3600\" route=\"r\"/></routes>\n");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
  for (const std::string model : {"Krauss", "IDM"}) {
    SCOPED_TRACE(model);
    const test::SumoAndLpsim r =
        test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-r", "r.rou.xml", "--max-depart-delay", "10",
                                       "--default.carfollowmodel", model, "--summary-output", "sum.xml"});
    ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
    ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
    const int sumo_trips = count_of(r.sumo_tripinfo, "<tripinfo "),
              lpsim_trips = count_of(r.lpsim_tripinfo, "<tripinfo ");
    EXPECT_GT(sumo_trips, 150);
    EXPECT_LT(sumo_trips, 300);
    EXPECT_NEAR(lpsim_trips, sumo_trips, 0.03 * sumo_trips);
    EXPECT_NE(r.lpsim.out.find(" Discarded (not inserted within --max-depart-delay): " +
                               std::to_string(600 - lpsim_trips)),
              std::string::npos)
        << r.lpsim.out;
    // lpsim wrote the summary last: every vehicle ended, only the inserted ones arrived.
    const std::string summary = read_file(dir.path() / "sum.xml");
    EXPECT_NE(summary.find("ended=\"600\" arrived=\"" + std::to_string(lpsim_trips) + "\""),
              std::string::npos);
    // The delays of those inserted stay within the limit plus a step, as in SUMO.
    const std::regex delay(R"re(departDelay="([0-9.]+)")re");
    for (auto it = std::sregex_iterator(r.lpsim_tripinfo.begin(), r.lpsim_tripinfo.end(), delay);
         it != std::sregex_iterator(); ++it)
      EXPECT_LE(std::stod((*it)[1]), 11.0);
  }
  // The default (-1) drops nobody.
  const test::SumoAndLpsim all = test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-r", "r.rou.xml"});
  EXPECT_EQ(count_of(all.lpsim_tripinfo, "<tripinfo "), 600);
}

// Trips routed with random edge-cost factors: on two ways from O to D, the upper 4.4 % longer, everyone takes
// the lower without them (all at the speed limit, so that the rerouting device's averaged speeds, which route
// the trips at insertion, stay free-flow ones); with F = 1.5 SUMO sends 27-40 of 100 vehicles up (seeds 1-3),
// LPSim must send a comparable share (within 15), the same routes for the same seed and other routes for
// another.
TEST(SumoSettingsTest, RandomWeightsSpreadTripsOverRoutesAsInSumo) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_random_weights");
  dir.write("n.nod.xml",
            "<nodes><node id=\"O\" x=\"-200\" y=\"0\"/><node id=\"A\" x=\"0\" y=\"0\" type=\"priority\"/>"
            "<node id=\"M\" x=\"500\" y=\"0\" type=\"priority\"/><node id=\"U\" x=\"500\" y=\"150\" "
            "type=\"priority\"/><node id=\"B\" x=\"1000\" y=\"0\" type=\"priority\"/>"
            "<node id=\"D\" x=\"1200\" y=\"0\"/></nodes>\n");
  std::string edges = "<edges>";
  for (const char* e : {"OA", "AM", "MB", "AU", "UB", "BD"})
    edges += std::string("<edge id=\"") + e + "\" from=\"" + e[0] + "\" to=\"" + e[1] +
             "\" numLanes=\"1\" speed=\"13.89\"/>";
  dir.write("n.edg.xml", edges + "</edges>\n");
  dir.write(
      "r.rou.xml",
      "<routes><vType id=\"t\" sigma=\"0\" speedDev=\"0\"/>"
      "<flow id=\"f\" type=\"t\" begin=\"0\" end=\"1000\" period=\"10\" from=\"OA\" to=\"BD\"/></routes>\n");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
  // Upper-route trips: 1438.90 m driven against 1395.00 m.
  auto upper = [](const std::string& tripinfo) { return count_of(tripinfo, "routeLength=\"1438.90\""); };
  const test::SumoAndLpsim plain = test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-r", "r.rou.xml"});
  EXPECT_EQ(upper(plain.sumo_tripinfo), 0);
  EXPECT_EQ(upper(plain.lpsim_tripinfo), 0);
  std::set<std::string> by_seed;
  for (const std::string seed : {"1", "2", "3"}) {
    SCOPED_TRACE("seed " + seed);
    const test::SumoAndLpsim r = test::run_sumo_and_lpsim(
        dir, {"-n", "n.net.xml", "-r", "r.rou.xml", "--weights.random-factor", "1.5", "--seed", seed});
    ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
    ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
    EXPECT_EQ(count_of(r.lpsim_tripinfo, "<tripinfo "), 100);
    EXPECT_NEAR(upper(r.lpsim_tripinfo), upper(r.sumo_tripinfo), 15);
    EXPECT_GT(upper(r.lpsim_tripinfo), 0);
    by_seed.insert(r.lpsim_tripinfo);
    const CliResult again = test::run_lpsim(
        dir.path(), {"run", "-n", "n.net.xml", "-r", "r.rou.xml", "--weights.random-factor", "1.5", "--seed",
                     seed, "--threads", "2", "--tripinfo-output", "again.xml"});
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read_file(dir.path() / "again.xml"), r.lpsim_tripinfo);
  }
  EXPECT_EQ(by_seed.size(), 3u) << "three seeds gave the same routes";
  EXPECT_EQ(
      test::run_lpsim(dir.path(), {"info", "-n", "n.net.xml", "--weights.random-factor", "0.9"}).exit_code,
      2);
}

// SUMO's tripinfo of the trips still running at the end (write-unfinished) and, with write-undeparted, of
// those due that never departed: the same vehicles as SUMO's, in SUMO's format, and counted in the
// statistics as SUMO counts them.
TEST(SumoSettingsTest, UnfinishedAndUndepartedTripsAreWrittenAsInSumo) {
  if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_write_undeparted");
  copy_grid(dir);
  // With a 1 s flow start of one vehicle per second, the grid holds about 120 running vehicles at 150 s and
  // the vehicle due at 150 s has not departed.
  const test::SumoAndLpsim r =
      test::run_sumo_and_lpsim(dir, {"-c", "grid_tls.sumocfg", "--end", "150",
                                     "--tripinfo-output.write-undeparted", "--statistic-output", "st.xml"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  auto undeparted = [](const std::string& tripinfo) {
    std::set<std::string> ids;
    const std::regex line(R"re(<tripinfo id="([^"]+)" depart="-1" departLane="" departPos="-1.00" )re"
                          R"re(departSpeed="-1.00" departDelay="[0-9.]+" arrival="-1.00" arrivalLane="" )re"
                          R"re(arrivalPos="-1.00" arrivalSpeed="-1.00" duration="0.00")re");
    for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), line); it != std::sregex_iterator();
         ++it)
      ids.insert((*it)[1]);
    return ids;
  };
  EXPECT_EQ(undeparted(r.lpsim_tripinfo), undeparted(r.sumo_tripinfo));
  EXPECT_FALSE(undeparted(r.lpsim_tripinfo).empty());
  const int sumo_running =
      count_of(r.sumo_tripinfo, "arrival=\"-1.00\"") - static_cast<int>(undeparted(r.sumo_tripinfo).size());
  const int lpsim_running =
      count_of(r.lpsim_tripinfo, "arrival=\"-1.00\"") - static_cast<int>(undeparted(r.lpsim_tripinfo).size());
  EXPECT_NEAR(lpsim_running, sumo_running, 0.05 * sumo_running);
  EXPECT_EQ(count_of(r.lpsim_tripinfo, "vaporized=\"end\""),
            lpsim_running + static_cast<int>(undeparted(r.lpsim_tripinfo).size()));
  // Every inserted trip counts in the statistics, finished or not (lpsim wrote st.xml last).
  const std::string stats = read_file(dir.path() / "st.xml");
  const std::regex inserted(R"re(inserted="([0-9]+)")re"),
      count(R"re(vehicleTripStatistics count="([0-9]+)")re");
  std::smatch a, b;
  ASSERT_TRUE(std::regex_search(stats, a, inserted)) << stats;
  ASSERT_TRUE(std::regex_search(stats, b, count)) << stats;
  EXPECT_EQ(a[1], b[1]);
  EXPECT_NE(stats.find("departDelayWaiting=\"0.00\""), std::string::npos) << stats;
  // write-unfinished alone: the running ones, no undeparted ones.
  const CliResult unfinished =
      test::run_lpsim(dir.path(), {"run", "-c", "grid_tls.sumocfg", "--end", "150", "--tripinfo-output",
                                   "u.xml", "--tripinfo-output.write-unfinished"});
  ASSERT_EQ(unfinished.exit_code, 0) << unfinished.err;
  const std::string u = read_file(dir.path() / "u.xml");
  EXPECT_TRUE(undeparted(u).empty());
  EXPECT_EQ(count_of(u, "vaporized=\"end\""), lpsim_running);
}

// A vehicle A on the major road stands on the junction (keepClear off) behind a car parked at the start of
// the next edge; B on the minor road must cross A's path. Without --ignore-junction-blocker B waits for ever,
// as in SUMO; with T it goes once A has stood T seconds on the junction: SUMO's B arrives at 56 s (T 20) and
// 66 s (T 30); LPSim's within 3 s.
TEST(SumoSettingsTest, VehiclesStandingOnAJunctionAreIgnoredAfterTheGivenTimeAsInSumo) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_junction_blocker");
  dir.write("n.nod.xml",
            "<nodes><node id=\"C\" x=\"0\" y=\"0\" type=\"priority\" keepClear=\"false\"/>"
            "<node id=\"W\" x=\"-200\" y=\"0\"/><node id=\"E\" x=\"200\" y=\"0\"/>"
            "<node id=\"S\" x=\"0\" y=\"-200\"/><node id=\"N\" x=\"0\" y=\"200\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"WC\" from=\"W\" to=\"C\" numLanes=\"1\" speed=\"13.89\" priority=\"3\"/>"
            "<edge id=\"CE\" from=\"C\" to=\"E\" numLanes=\"1\" speed=\"13.89\" priority=\"3\"/>"
            "<edge id=\"SC\" from=\"S\" to=\"C\" numLanes=\"1\" speed=\"13.89\" priority=\"1\"/>"
            "<edge id=\"CN\" from=\"C\" to=\"N\" numLanes=\"1\" speed=\"13.89\" priority=\"1\"/></edges>\n");
  dir.write("r.rou.xml", R"X(<routes>
  <vType id="t" sigma="0"/>
  <vehicle id="blk" type="t" depart="0" departPos="5" departSpeed="0"><route edges="CE"/>
    <stop lane="CE_0" startPos="0" endPos="5" duration="1000"/></vehicle>
  <vehicle id="A" type="t" depart="0"><route edges="WC CE"/></vehicle>
  <vehicle id="B" type="t" depart="20"><route edges="SC CN"/></vehicle>
</routes>
)X");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
  const std::regex b_arrival(R"re(<tripinfo id="B"[^>]* arrival="([0-9.]+)")re");
  auto arrival = [&](const std::string& tripinfo) {
    std::smatch m;
    return std::regex_search(tripinfo, m, b_arrival) ? std::stod(m[1]) : -1.0;
  };
  for (const std::string t : {"-1", "20", "30"}) {
    SCOPED_TRACE("--ignore-junction-blocker " + t);
    const test::SumoAndLpsim r = test::run_sumo_and_lpsim(
        dir, {"-n", "n.net.xml", "-r", "r.rou.xml", "--end", "300", "--ignore-junction-blocker", t});
    ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
    ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
    const double sumo = arrival(r.sumo_tripinfo), lpsim = arrival(r.lpsim_tripinfo);
    if (t == "-1") {
      EXPECT_EQ(sumo, -1.0);  // never arrives
      EXPECT_EQ(lpsim, -1.0);
    } else {
      ASSERT_GT(sumo, 0);
      EXPECT_NEAR(lpsim, sumo, 3.0);
    }
  }
}

// SUMO 1.15's desiredMaxSpeed: a default bicycle rides at 20 km/h (its maxSpeed is 50 km/h), one with a
// desiredMaxSpeed at that, one given a maxSpeed at that. On a 3.2 km road at 100 km/h (speedDev 0): SUMO's
// trips take 579.9 / 801.0 / 324.0 s; LPSim's, which took 236 s for the first two, within 1 %.
TEST(SumoSettingsTest, BicyclesRideAtTheirDesiredMaxSpeedAsInSumo) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_desired_max_speed");
  dir.write("n.nod.xml",
            "<nodes><node id=\"a\" x=\"0\" y=\"0\"/><node id=\"b\" x=\"1200\" y=\"0\"/>"
            "<node id=\"c\" x=\"3200\" y=\"0\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"ab\" from=\"a\" to=\"b\" numLanes=\"3\" speed=\"27.78\"/>"
            "<edge id=\"bc\" from=\"b\" to=\"c\" numLanes=\"3\" speed=\"27.78\"/></edges>\n");
  dir.write("r.rou.xml", R"X(<routes><route id="r" edges="ab bc"/>
  <vType id="b" vClass="bicycle" sigma="0" speedDev="0"/>
  <vType id="bd" vClass="bicycle" desiredMaxSpeed="4" sigma="0" speedDev="0"/>
  <vType id="m" vClass="bicycle" maxSpeed="10" sigma="0" speedDev="0"/>
  <flow id="b" type="b" begin="0" end="100" period="10" route="r"/>
  <flow id="bd" type="bd" begin="1" end="100" period="10" route="r" departLane="1"/>
  <flow id="m" type="m" begin="2" end="100" period="10" route="r" departLane="2"/>
</routes>
)X");
  ASSERT_NO_FATAL_FAILURE(test::netconvert(dir, {"-n", "n.nod.xml", "-e", "n.edg.xml", "-o", "n.net.xml"}));
  const test::SumoAndLpsim r = test::run_sumo_and_lpsim(dir, {"-n", "n.net.xml", "-r", "r.rou.xml"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  for (const char* flow : {"b", "bd", "m"}) {
    SCOPED_TRACE(flow);
    const double sumo = test::flow_mean_duration(r.sumo_tripinfo, flow, 10);
    EXPECT_NEAR(test::flow_mean_duration(r.lpsim_tripinfo, flow, 10), sumo, 0.01 * sumo);
  }
}

}  // namespace
}  // namespace lpsim

// SUMO's rerouting device against the real sumo on scenarios/reroute_block: a vehicle stands on the short way
// from `in` to `out` for 600 s and the traffic behind it stops; a flow of trips from `in` to `out` departs
// every 5 s. As the short way's averaged speed falls, trips routed at insertion (every trip has the device)
// and equipped vehicles on `in` (every period) take the long way round. The routes each took are told apart
// by their length.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

struct Detours {
  int trips = 0, detours = 0;
  double first_detour_depart = -1;  // s; -1: none
  double mean_duration = 0;
};

// The long way is 2378.64 m, the short one 2081.10 m (with the junctions).
Detours detours_of(const std::string& tripinfo) {
  static const std::regex trip(
      "<tripinfo id=\"([^\"]+)\" depart=\"([0-9.]+)\"[^>]* duration=\"([0-9.]+)\"[^>]* "
      "routeLength=\"([0-9.]+)\"");
  Detours d;
  double duration_sum = 0;
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), trip); it != std::sregex_iterator();
       ++it) {
    ++d.trips;
    const double depart = std::stod((*it)[2]);
    duration_sum += std::stod((*it)[3]);
    if (std::stod((*it)[4]) > 2200) {
      ++d.detours;
      if (d.first_detour_depart < 0 || depart < d.first_detour_depart) d.first_detour_depart = depart;
    }
  }
  if (d.trips > 0) d.mean_duration = duration_sum / d.trips;
  return d;
}

class ReroutingDeviceTest : public ::testing::TestWithParam<const char*> {};

// Period 30 s (the scenario's) and 0 (no en-route re-routing: trips only choose when inserted). Measured:
// SUMO sends 87 and 80 trips the long way, the first departing at 170 s and 200 s; LPSim 88 and 82, from
// 165 s and 195 s.
TEST_P(ReroutingDeviceTest, TripsTakeTheLongWayWhenSumoDoes) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  test::TempDir dir("lpsim_rerouting_device");
  const std::string cfg = std::string(LPSIM_SCENARIOS_DIR) + "/reroute_block/reroute_block.sumocfg";
  const test::SumoAndLpsim r =
      test::run_sumo_and_lpsim(dir, {"-c", cfg, "--device.rerouting.period", GetParam()});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  const Detours sumo = detours_of(r.sumo_tripinfo), lpsim = detours_of(r.lpsim_tripinfo);
  ASSERT_EQ(sumo.trips, 121);
  EXPECT_EQ(lpsim.trips, 121);
  EXPECT_GT(sumo.detours, 60);
  EXPECT_NEAR(lpsim.detours, sumo.detours, 5);
  // The first detour within one departure headway of SUMO's.
  EXPECT_NEAR(lpsim.first_detour_depart, sumo.first_detour_depart, 5.0);
  EXPECT_NEAR(lpsim.mean_duration, sumo.mean_duration, 0.05 * sumo.mean_duration);
}

INSTANTIATE_TEST_SUITE_P(Periods, ReroutingDeviceTest, ::testing::Values("30", "0"));

// Without speed samples the averaged speeds stay free-flow ones: nobody takes the long way, and the trips
// queue behind the standing vehicle (SUMO alike).
TEST(ReroutingDeviceNoSamplesTest, FreeFlowTimesKeepEveryTripOnTheShortWay) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  test::TempDir dir("lpsim_rerouting_no_samples");
  const std::string cfg = std::string(LPSIM_SCENARIOS_DIR) + "/reroute_block/reroute_block.sumocfg";
  const test::SumoAndLpsim r =
      test::run_sumo_and_lpsim(dir, {"-c", cfg, "--device.rerouting.adaptation-interval", "0"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  EXPECT_EQ(detours_of(r.sumo_tripinfo).detours, 0);
  EXPECT_EQ(detours_of(r.lpsim_tripinfo).detours, 0);
  EXPECT_EQ(detours_of(r.lpsim_tripinfo).trips, 121);
}

// A truck whose route skips an edge (`in short2`, not connected) with a stop on short2. With
// --ignore-route-errors SUMO keeps the route, and routing a vehicle with the rerouting device when due
// repairs it, through its stop's edge; without that option the route is an error in both.
TEST(ReroutingDeviceRepairTest, AnEquippedVehiclesDisconnectedRouteIsRepairedAtInsertion) {
  if (!test::have_sumo_and_netconvert()) GTEST_SKIP() << "SUMO not installed";
  test::TempDir dir("lpsim_rerouting_repair");
  const std::string net = std::string(LPSIM_SCENARIOS_DIR) + "/reroute_block/reroute_block.net.xml";
  dir.write("r.rou.xml",
            "<routes>\n<vehicle id=\"truck\" depart=\"0\"><route edges=\"in short2\"/>"
            "<stop lane=\"short2_0\" endPos=\"300\" duration=\"30\"/></vehicle>\n</routes>\n");
  const test::SumoAndLpsim r = test::run_sumo_and_lpsim(
      dir, {"-n", net, "-r", "r.rou.xml", "--device.rerouting.probability", "1", "--ignore-route-errors"});
  ASSERT_EQ(r.sumo.exit_code, 0) << r.sumo.err;
  ASSERT_EQ(r.lpsim.exit_code, 0) << r.lpsim.err;
  static const std::regex trip("routeLength=\"([0-9.]+)\"[^>]*stopTime=\"([0-9.]+)\"");
  std::smatch s, l;
  ASSERT_TRUE(std::regex_search(r.sumo_tripinfo, s, trip)) << r.sumo_tripinfo;
  ASSERT_TRUE(std::regex_search(r.lpsim_tripinfo, l, trip)) << r.lpsim_tripinfo;
  EXPECT_EQ(s[1], "1785.62");  // in, short1 and short2 with the junctions between them
  EXPECT_EQ(l[1], s[1]);
  EXPECT_EQ(l[2], "30.00");
  const test::SumoAndLpsim strict =
      test::run_sumo_and_lpsim(dir, {"-n", net, "-r", "r.rou.xml", "--device.rerouting.probability", "1"});
  EXPECT_NE(strict.sumo.exit_code, 0);
  EXPECT_EQ(strict.lpsim.exit_code, 2) << strict.lpsim.err;
  EXPECT_NE(strict.lpsim.err.find("no connection from edge 'in' to edge 'short2'"), std::string::npos)
      << strict.lpsim.err;
}

}  // namespace
}  // namespace lpsim

// Values past what LPSim can represent or what SUMO accepts, refused at load with exit status 2 and one line
// naming file:line, the value and the element: times beyond the int64 millisecond clock, tau 0, a numeric
// departSpeed above the vType's maxSpeed or (with speedDev 0) the first edge's limit, and lane lengths that
// need more lane map than --max-lane-map-gb.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "cli_scenario_fixture.hpp"

namespace lpsim {
namespace {

using test::CliScenarioTest;
using test::expect_input_error;
using test::read_file;

using CliValueRangeTest = CliScenarioTest;

const char* kRoute = "<route edges=\"A0A1 A1A2\"/>";

std::string vehicle(const std::string& attrs) {
  return std::string("<vehicle id=\"v\" ") + attrs + ">" + kRoute + "</vehicle>";
}

// depart 1e17 s overflowed the millisecond clock and was inserted at once with a negative departDelay.
TEST_F(CliValueRangeTest, DepartBeyondTheMillisecondClockIsRefused) {
  write_routes("far.rou.xml", vehicle("depart=\"1e17\""));
  expect_input_error(info_with_routes("far.rou.xml"), "far.rou.xml:3",
                     {"<vehicle id=\"v\">", "'depart'", "'1e17'", "1e12 s"});
  write_routes("edge.rou.xml", vehicle("depart=\"1000000000000.001\""));
  expect_input_error(info_with_routes("edge.rou.xml"), "edge.rou.xml:3", {"'1000000000000.001'"});
  // The largest time still loads (SUMO takes up to 9.2e15 s; LPSim compares times as doubles, exact to the
  // millisecond only below 2^53 ms).
  write_routes("last.rou.xml", vehicle("depart=\"1e12\""));
  EXPECT_EQ(info_with_routes("last.rou.xml").exit_code, 0);
}

TEST_F(CliValueRangeTest, FlowTimesBeyondTheClockAreRefused) {
  const std::string route = kRoute;
  write_routes("end.rou.xml", "<flow id=\"f\" begin=\"0\" end=\"1e17\" period=\"1\">" + route + "</flow>");
  expect_input_error(info_with_routes("end.rou.xml"), "end.rou.xml:3",
                     {"<flow id=\"f\">", "'end'", "'1e17'"});
  write_routes("begin.rou.xml",
               "<flow id=\"f\" begin=\"2e16\" number=\"2\" period=\"1\">" + route + "</flow>");
  expect_input_error(info_with_routes("begin.rou.xml"), "begin.rou.xml:3", {"'begin'", "'2e16'"});
  write_routes("period.rou.xml",
               "<flow id=\"f\" begin=\"0\" number=\"2\" period=\"1e18\">" + route + "</flow>");
  expect_input_error(info_with_routes("period.rou.xml"), "period.rou.xml:3", {"'period'", "'1e18'"});
  write_routes("rate.rou.xml",
               "<flow id=\"f\" begin=\"0\" number=\"2\" vehsPerHour=\"1e-300\">" + route + "</flow>");
  expect_input_error(info_with_routes("rate.rou.xml"), "rate.rou.xml:3", {"'vehsPerHour'", "'1e-300'"});
  write_routes("interval.rou.xml", "<interval begin=\"0\" end=\"1e20\">\n<flow id=\"f\" number=\"2\">" +
                                       route + "</flow>\n</interval>");
  expect_input_error(info_with_routes("interval.rou.xml"), "interval.rou.xml:3", {"<interval", "'1e20'"});
}

TEST_F(CliValueRangeTest, EdgeDataTimesBeyondTheClockAreRefused) {
  write("data.add.xml",
        "<additional>\n<!-- test input -->\n<edgeData id=\"d\" file=\"out.xml\" "
        "period=\"1e17\"/>\n</additional>\n");
  const auto r = run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"});
  expect_input_error(r, "data.add.xml:3", {"<edgeData id=\"d\">", "'period'", "'1e17'"});
}

// SUMO: "Invalid Car-Following-Model Attribute tau. Must be greater than 0".
TEST_F(CliValueRangeTest, TauZeroIsRefused) {
  write_routes("tau.rou.xml", "<vType id=\"t\" tau=\"0\"/>");
  expect_input_error(info_with_routes("tau.rou.xml"), "tau.rou.xml:3",
                     {"<vType id=\"t\">", "'tau'", "positive", "'0'"});
  write_routes("cf.rou.xml", "<vType id=\"t\">\n<carFollowing-IDM tau=\"0\"/>\n</vType>");
  expect_input_error(info_with_routes("cf.rou.xml"), "cf.rou.xml:4", {"'tau'", "'0'"});
}

// SUMO: "Departure speed for vehicle 'v' is too high for the vehicle type 't'." (maxSpeed + 0.01 is the
// largest it takes).
TEST_F(CliValueRangeTest, DepartSpeedAboveTheVTypeMaxSpeedIsRefused) {
  write_routes("type.rou.xml", "<vType id=\"t\" maxSpeed=\"10\"/>\n" +
                                   vehicle("type=\"t\" depart=\"0\" departSpeed=\"10.02\""));
  expect_input_error(info_with_routes("type.rou.xml"), "type.rou.xml:4",
                     {"departSpeed 10.02", "vehicle 'v'", "vType 't'", "maxSpeed 10"});
  write_routes("ok.rou.xml", "<vType id=\"t\" maxSpeed=\"10\"/>\n" +
                                 vehicle("type=\"t\" depart=\"0\" departSpeed=\"10.005\""));
  EXPECT_EQ(info_with_routes("ok.rou.xml").exit_code, 0);
}

// SUMO: "Departure speed for vehicle 'v' is too high for the departure edge 'A0A1'." when the type's speed
// factor cannot vary; A0A1's lanes allow 13.89 m/s.
TEST_F(CliValueRangeTest, DepartSpeedAboveTheEdgeLimitIsRefusedWithoutSpeedDev) {
  write_routes("edge.rou.xml",
               "<vType id=\"t\" speedDev=\"0\"/>\n" + vehicle("type=\"t\" depart=\"0\" departSpeed=\"14\""));
  expect_input_error(info_with_routes("edge.rou.xml"), "edge.rou.xml:4",
                     {"departSpeed 14", "vehicle 'v'", "edge 'A0A1'", "13.89"});
  // A flow is blamed on its own line and names its vehicle.
  write_routes("flow.rou.xml",
               "<vType id=\"t\" speedDev=\"0\" speedFactor=\"1.2\"/>\n<flow id=\"f\" type=\"t\" "
               "begin=\"0\" number=\"1\" departSpeed=\"16.7\">" +
                   std::string(kRoute) + "</flow>");
  expect_input_error(info_with_routes("flow.rou.xml"), "flow.rou.xml:4",
                     {"departSpeed 16.7", "vehicle 'f.0'"});
  write_routes("ok.rou.xml", "<vType id=\"t\" speedDev=\"0\" speedFactor=\"1.2\"/>\n" +
                                 vehicle("type=\"t\" depart=\"0\" departSpeed=\"16.6\""));
  EXPECT_EQ(info_with_routes("ok.rou.xml").exit_code, 0);
}

// With speedDev > 0 SUMO gives the vehicle the speed factor its departSpeed needs (50 / 13.89 = 3.60) and
// drives it at that speed; the keywords keep working.
TEST_F(CliValueRangeTest, DepartSpeedAboveTheEdgeLimitRaisesTheSpeedFactor) {
  write_routes(
      "fast.rou.xml",
      vehicle("depart=\"0\" departSpeed=\"50\"") + "\n<vehicle id=\"m\" depart=\"1\" departSpeed=\"max\">" +
          kRoute + "</vehicle>\n<vehicle id=\"d\" depart=\"2\" departSpeed=\"desired\">" + kRoute +
          "</vehicle>\n<vehicle id=\"s\" depart=\"3\" departSpeed=\"speedLimit\">" + kRoute + "</vehicle>");
  const auto r =
      run({"run", "-n", test::kGridTlsNet, "-r", "fast.rou.xml", "--tripinfo-output", "trips.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(test::has_line(r,
                             "lpsim: warning: departSpeed above the first edge's speed limit times the drawn "
                             "speed factor: as SUMO does, the speed factor was raised to match for 1 "
                             "vehicle: 'v'"))
      << r.err;
  const std::string trips = read_file(tmp_.path() / "trips.xml");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(trips, m, std::regex("<tripinfo id=\"v\"[^>]* speedFactor=\"([0-9.]+)\"")))
      << trips;
  EXPECT_EQ(m[1].str(), "3.60");
  for (const char* id : {"m", "d", "s"})
    EXPECT_NE(trips.find(std::string("<tripinfo id=\"") + id + "\""), std::string::npos) << id;
}

// A 50 KB net with a lane of 1e9 m asked for 1.86 GiB of lane map; --max-lane-map-gb caps it.
TEST_F(CliValueRangeTest, LaneMapAboveTheBudgetIsRefused) {
  write_grid_net_with("long.net.xml", "length=\"183.20\"", "length=\"1e9\"");
  const std::string lane_line = "long.net.xml:1229";
  expect_input_error(run({"info", "-n", "long.net.xml", "--max-lane-map-gb", "1"}), lane_line,
                     {"1.86 GiB", "--max-lane-map-gb 1", "'A0A1_0'", "1000000000 m"});
  EXPECT_EQ(run({"info", "-n", "long.net.xml", "--max-lane-map-gb", "2"}).exit_code, 0);
}

}  // namespace
}  // namespace lpsim

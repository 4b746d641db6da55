// SUMO options that act only on something a scenario may lack are decided against the loaded scenario, both
// ways: refused (exit 2, at the option's file:line, saying what makes it act) where the scenario has it, and
// named in one warning, with why, where it cannot act. The real binary on real files in a temp dir.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;

const std::string kGridNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";

// A fully routed vehicle (no rerouting device in SUMO) and, in trips.rou.xml, a trip SUMO routes itself.
const char* kRouted =
    "<routes>\n<vehicle id=\"v0\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n</routes>\n";
const char* kTrip = "<routes>\n<trip id=\"t0\" depart=\"0\" from=\"A0A1\" to=\"A1A2\"/>\n</routes>\n";

class OptionScopesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_.write("net.net.xml", read_file(kGridNet));
    tmp_.write("routed.rou.xml", kRouted);
    tmp_.write("trips.rou.xml", kTrip);
  }

  // A .sumocfg on net.net.xml and `routes`, its option elements from line 5 on, one per line.
  void write_cfg(const std::string& routes, const std::vector<std::string>& options) const {
    std::string text =
        "<configuration>\n  <input>\n    <net-file value=\"net.net.xml\"/>\n    <route-files value=\"" +
        routes + "\"/>\n";
    for (const auto& o : options) text += "    " + o + "\n";
    text += "  </input>\n</configuration>\n";
    tmp_.write("s.sumocfg", text);
  }

  CliResult info(const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args{"info", "-c", "s.sumocfg"};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run_lpsim(tmp_.path(), args);
  }

  test::TempDir tmp_{"lpsim_option_scopes"};
};

void expect_refused(const CliResult& r, const std::string& where, const std::vector<std::string>& words) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("lpsim: error: " + where + ": ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  for (const auto& w : words)
    EXPECT_NE(r.err.find(w), std::string::npos) << "'" << w << "' missing: " << r.err;
}

void expect_accepted(const CliResult& r, const std::vector<std::string>& words) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto at = r.err.find("lpsim: warning: SUMO options accepted that cannot act in this scenario: ");
  ASSERT_NE(at, std::string::npos) << r.err;
  for (const auto& w : words)
    EXPECT_NE(r.err.find(w, at), std::string::npos) << "'" << w << "' missing: " << r.err;
}

// The rerouting device's options LPSim implements are taken as given (osmWebWizard's own settings, and an
// equipped fleet); those it lacks are decided by the scenario.
TEST_F(OptionScopesTest, ReroutingOptionsLpsimImplementsAreAcceptedSilently) {
  write_cfg("trips.rou.xml",
            {"<device.rerouting.adaptation-steps value=\"18\"/>",
             "<device.rerouting.adaptation-interval value=\"10\"/>",
             "<device.rerouting.probability value=\"1\"/>", "<device.rerouting.period value=\"300\"/>"});
  const CliResult r = info({"--device.rerouting.explicit", "t0", "--device.rerouting.pre-period", "30"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("device.rerouting"), std::string::npos) << r.err;
}

TEST_F(OptionScopesTest, ReroutingOptionsLpsimLacksActOnlyWhereTheScenarioHasWhatTheyActOn) {
  write_cfg("trips.rou.xml", {"<device.rerouting.with-taz value=\"true\"/>",
                              "<device.rerouting.bike-speeds value=\"true\"/>"});
  expect_accepted(info(), {"device.rerouting.with-taz (LPSim leaves out trips between TAZ)",
                           "device.rerouting.bike-speeds (no bicycles)"});
  tmp_.write("bikes.rou.xml",
             "<routes>\n<vType id=\"b\" vClass=\"bicycle\"/>\n"
             "<trip id=\"t0\" type=\"b\" depart=\"0\" from=\"A0A1\" to=\"A1A2\"/>\n</routes>\n");
  write_cfg("bikes.rou.xml", {"<device.rerouting.bike-speeds value=\"true\"/>"});
  expect_refused(info(), "s.sumocfg:5", {"<device.rerouting.bike-speeds>", "bicycles"});
}

TEST_F(OptionScopesTest, ALaterDefaultValueWithdrawsAnOption) {
  write_cfg("routed.rou.xml", {"<device.rerouting.with-taz value=\"true\"/>"});
  const CliResult r = info({"--device.rerouting.with-taz", "false"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("device.rerouting"), std::string::npos) << r.err;
}

TEST_F(OptionScopesTest, BidiTeleportTimeActsOnlyWithBidirectionalRoads) {
  write_cfg("routed.rou.xml", {"<time-to-teleport.bidi value=\"70\"/>"});
  expect_accepted(info(), {"time-to-teleport.bidi (no bidirectional road edges)"});
  // The same network with one road edge declared the partner of its opposite.
  std::string net = read_file(kGridNet);
  const std::string edge = "<edge id=\"A0A1\"";
  const auto at = net.find(edge);
  ASSERT_NE(at, std::string::npos);
  net.insert(at + edge.size(), " bidi=\"A1A0\"");
  tmp_.write("net.net.xml", net);
  expect_refused(info(), "s.sumocfg:5", {"<time-to-teleport.bidi>", "bidirectional road edges"});
}

TEST_F(OptionScopesTest, PersonOptionsActOnlyWherePersonsAre) {
  write_cfg("routed.rou.xml",
            {"<ride.stop-tolerance value=\"25\"/>", "<pedestrian.model value=\"nonInteracting\"/>"});
  expect_accepted(info(), {"ride.stop-tolerance (no persons)", "pedestrian.model (persons never meet"});
  tmp_.write("persons.rou.xml",
             "<routes>\n<vehicle id=\"v0\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
             "<person id=\"p\" depart=\"0\"><walk edges=\"A0A1 A1A2\"/></person>\n</routes>\n");
  write_cfg("persons.rou.xml", {"<pedestrian.model value=\"nonInteracting\"/>"});
  expect_accepted(info(), {"pedestrian.model (persons never meet"});
  write_cfg("persons.rou.xml", {"<ride.stop-tolerance value=\"25\"/>"});
  expect_refused(info(), "s.sumocfg:5", {"<ride.stop-tolerance>", "1 persons"});
}

TEST_F(OptionScopesTest, ParkingManeuverActsOnlyWithParkingAreaStops) {
  write_cfg("routed.rou.xml", {"<parking.maneuver value=\"true\"/>"});
  expect_accepted(info(), {"parking.maneuver (no stop at a parking area)"});
  tmp_.write("parking.rou.xml",
             "<routes>\n<vehicle id=\"v0\" depart=\"0\"><route edges=\"A0A1 A1A2\"/>"
             "<stop parkingArea=\"pa\" duration=\"10\"/></vehicle>\n</routes>\n");
  write_cfg("parking.rou.xml", {"<parking.maneuver value=\"true\"/>"});
  expect_refused(info(), "s.sumocfg:5", {"<parking.maneuver>", "stops are made at parking areas"});
}

TEST_F(OptionScopesTest, ScopedOptionsBesideASnapshotAreRefused) {
  write_cfg("routed.rou.xml", {});
  ASSERT_EQ(test::run_lpsim(tmp_.path(), {"convert", "-c", "s.sumocfg", "-o", "s.lpsim"}).exit_code, 0);
  expect_refused(test::run_lpsim(tmp_.path(), {"run", "s.lpsim", "--device.rerouting.with-taz", "true"}),
                 "command line", {"--device.rerouting.with-taz", "give it to lpsim convert"});
  // Which vehicles get the rerouting device is decided while loading; how they use it, while running.
  expect_refused(test::run_lpsim(tmp_.path(), {"run", "s.lpsim", "--device.rerouting.probability", "1"}),
                 "command line", {"--device.rerouting.probability", "it acts while loading"});
  const CliResult period =
      test::run_lpsim(tmp_.path(), {"run", "s.lpsim", "--device.rerouting.period", "60", "--end", "10"});
  EXPECT_EQ(period.exit_code, 0) << period.err;
}

}  // namespace
}  // namespace lpsim

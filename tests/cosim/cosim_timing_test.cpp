// The co-simulation's clocks with the real SUMO (label cosim): a vehicle crossing the corridor keeps its
// time and its distance on both sides, whatever the two step lengths, and vehicles SUMO removes without
// reporting an arrival (teleported beyond their route's end, as its long steps make them) are accounted for.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::string kScenarios = LPSIM_SCENARIOS_DIR;

// One trip's tripinfo values.
struct Trip {
  double depart = -1, duration = -1, route_length = -1;
};

Trip trip_of(const fs::path& tripinfo, const std::string& id) {
  const std::string text = test::read_file(tripinfo);
  const std::regex line("<tripinfo id=\"" + id + "\"[^\n]*");
  std::smatch m;
  if (!std::regex_search(text, m, line)) return {};
  const std::string l = m.str();
  const auto value = [&](const std::string& name) {
    std::smatch v;
    const std::regex re(" " + name + "=\"([-0-9.]+)\"");
    return std::regex_search(l, v, re) ? std::stod(v[1]) : -1.0;
  };
  return Trip{value("depart"), value("duration"), value("routeLength")};
}

int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// One vehicle without dawdling or speed deviation on cosim_line's first three edges (no signal on the way),
// the middle one driven by SUMO. It crosses the corridor in SUMO and is taken back by LPSim on the third.
// Before, SUMO inserted it a step early where LPSim had it a step later (it gained a step), LPSim took it
// back at the start of the third edge (the metres SUMO had driven on it counted twice), and with a coupling
// period of 24 s (LPSim's 3 s steps, SUMO's 8 s) it lost 15 s and gained 61 m.
TEST(CosimulationTimingTest, AFreeFlowVehicleKeepsItsDepartDurationAndRouteLength) {
  test::TempDir dir("cosim_timing");
  fs::copy_file(kScenarios + "/cosim_line/cosim_line.net.xml", fs::path(dir.path()) / "line.net.xml");
  dir.write("one.rou.xml",
            "<routes>\n"
            "    <vType id=\"t\" sigma=\"0\" speedDev=\"0\"/>\n"
            "    <vehicle id=\"v\" type=\"t\" depart=\"3\" departLane=\"best\" departSpeed=\"max\">\n"
            "        <route edges=\"AB BC CD\"/>\n"
            "    </vehicle>\n"
            "</routes>\n");
  dir.write("corridor.txt", "edge:BC\n");
  struct Steps {
    std::string lpsim, sumo;
  };
  for (const Steps& s : {Steps{"1", "1"}, Steps{"0.5", "1"}, Steps{"1", "8"}, Steps{"3", "8"}}) {
    SCOPED_TRACE("LPSim step " + s.lpsim + " s, SUMO step " + s.sumo + " s");
    const std::vector<std::string> scenario{"-n", "line.net.xml", "-r", "one.rou.xml", "--no-step-log"};
    std::vector<std::string> alone{"run", "--step-length", s.lpsim, "--tripinfo-output", "alone.xml"};
    alone.insert(alone.end(), scenario.begin(), scenario.end());
    const test::CliResult a = test::run_lpsim(dir.path(), alone);
    ASSERT_EQ(a.exit_code, 0) << a.err;
    std::vector<std::string> sumo{"--step-length", s.sumo, "--tripinfo-output", "sumo.xml"};
    sumo.insert(sumo.end(), scenario.begin(), scenario.end());
    const test::CliResult b = test::run_program(dir.path(), {"sumo"}, sumo);
    ASSERT_EQ(b.exit_code, 0) << b.err;
    std::vector<std::string> cosim{"cosim",
                                   "--corridor",
                                   "corridor.txt",
                                   "--step-length",
                                   s.lpsim,
                                   "--sumo-args",
                                   "--step-length " + s.sumo,
                                   "--tripinfo-output",
                                   "cosim.xml"};
    cosim.insert(cosim.end(), scenario.begin(), scenario.end());
    const test::CliResult c = test::run_lpsim(dir.path(), cosim);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    ASSERT_NE(c.out.find("Handed into SUMO: 1"), std::string::npos) << c.out;
    ASSERT_NE(c.out.find("Taken back from SUMO: 1"), std::string::npos) << c.out;

    const Trip l = trip_of(fs::path(dir.path()) / "alone.xml", "v");
    const Trip m = trip_of(fs::path(dir.path()) / "sumo.xml", "v");
    const Trip t = trip_of(fs::path(dir.path()) / "cosim.xml", "v");
    ASSERT_GT(t.duration, 0);
    EXPECT_DOUBLE_EQ(t.depart, l.depart);
    EXPECT_NEAR(t.route_length, l.route_length, 0.011);
    EXPECT_NEAR(t.route_length, m.route_length, 0.011);
    EXPECT_NEAR(t.duration, l.duration, std::stod(s.lpsim) + 1e-9);
    EXPECT_NEAR(t.duration, m.duration, std::stod(s.sumo) + 1e-9);
  }
}

// With SUMO's steps of 8 s on grid_tls's middle row, SUMO's own collisions teleport vehicles, some beyond
// their route's last edge: SUMO 1.15 removes those without listing them among its arrivals, and over TraCI
// answers their subscription with an error. Before, the run failed ("Vehicle '16' is not known",
// "Subscription response error"); now each of them counts as arrived in SUMO and every trip has its tripinfo
// line.
TEST(CosimulationTimingTest, VehiclesSumoRemovesWithoutAnArrivalAreArrivedThere) {
  test::TempDir dir("cosim_gone");
  const std::string corridor = dir.write(
      "row.txt", "edge:A2B2\nedge:B2C2\nedge:C2D2\nedge:D2E2\nedge:E2D2\nedge:D2C2\nedge:C2B2\nedge:B2A2\n");
  const std::string grid = kScenarios + "/grid_tls/grid_tls.sumocfg";
  std::string first;
  for (const bool traci : {false, true}) {
    SCOPED_TRACE(traci ? "over TraCI" : "libsumo");
    std::vector<std::string> args{"cosim",
                                  "-c",
                                  grid,
                                  "--corridor",
                                  corridor,
                                  "--step-length",
                                  "3",
                                  "--sumo-args",
                                  "--step-length 8",
                                  "--tripinfo-output",
                                  "t.xml",
                                  "--no-step-log"};
    if (traci) args.insert(args.end(), {"--sumo-binary", "sumo"});
    const test::CliResult r = test::run_lpsim(dir.path(), args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("teleports beyond arrival edge"), std::string::npos) << "no such vehicle: no test";
    const std::string trips = test::read_file(fs::path(dir.path()) / "t.xml");
    EXPECT_EQ(count_of(trips, "<tripinfo "), 1000);
    if (first.empty())
      first = trips;
    else
      EXPECT_EQ(trips, first) << "libsumo and TraCI differ";
  }
}

// SUMO's side outputs cover the whole run, as LPSim's do (before, SUMO's clock ran a step behind and its FCD
// and summary ended a step early); with SUMO's step longer than LPSim's and an end between SUMO's steps, the
// merged edgeData's last interval is named in a warning.
TEST(CosimulationTimingTest, SumosSideOutputsEndWithLpsims) {
  test::TempDir dir("cosim_side_end");
  const std::string corridor = dir.write("row.txt", "edge:A2B2\nedge:B2C2\nedge:C2D2\nedge:D2E2\n");
  const std::string grid = kScenarios + "/grid_tls/grid_tls.sumocfg";
  const auto last_step = [&](const std::string& file, const std::string& tag) {
    const std::string text = test::read_file(fs::path(dir.path()) / file);
    const size_t at = text.rfind("<" + tag + " time=\"");
    return at == std::string::npos ? std::string()
                                   : text.substr(at, text.find('"', at + tag.size() + 8) - at);
  };
  const test::CliResult r = test::run_lpsim(
      dir.path(), {"cosim", "-c", grid, "--corridor", corridor, "--end", "250", "--fcd-output", "f.xml",
                   "--summary-output", "s.xml", "--edgedata-output", "e.xml", "--no-step-log"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_step("f.xml", "timestep"), "<timestep time=\"249.00");
  EXPECT_EQ(last_step("sumo.f.xml", "timestep"), "<timestep time=\"249.00");
  EXPECT_EQ(last_step("s.xml", "step"), "<step time=\"249.00");
  EXPECT_EQ(last_step("sumo.s.xml", "step"), "<step time=\"249.00");
  EXPECT_EQ(r.err.find("Warning: e.xml"), std::string::npos) << r.err;

  const test::CliResult eight =
      test::run_lpsim(dir.path(), {"cosim", "-c", grid, "--corridor", corridor, "--end", "250", "--sumo-args",
                                   "--step-length 8", "--edgedata-output", "e.xml", "--no-step-log"});
  ASSERT_EQ(eight.exit_code, 0) << eight.err;
  EXPECT_NE(
      eight.err.find("the interval from 0 s ends at 250 s in LPSim's measurements and at 256 s in SUMO's"),
      std::string::npos)
      << eight.err;
}

// SUMO 1.15's LC2013 lane-change model aborts the process on an assertion at action steps of 10 s or more: a
// SUMO step that long is refused up front, not a crash of LPSim's own process (libsumo).
TEST(CosimulationTimingTest, SumoStepsLcTwentyThirteenCannotTakeAreRefused) {
  test::TempDir dir("cosim_long_step");
  const std::string corridor = dir.write("row.txt", "edge:A2B2\nedge:B2C2\n");
  const test::CliResult r = test::run_lpsim(
      dir.path(), {"cosim", "-c", kScenarios + "/grid_tls/grid_tls.sumocfg", "--corridor", corridor,
                   "--sumo-args", "--step-length 12", "--tripinfo-output", "t.xml", "--no-step-log"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("lpsim: error: SUMO's step length 12 s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lpsim

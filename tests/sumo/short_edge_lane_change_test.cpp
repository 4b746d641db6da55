// A mandatory lane change on an edge shorter than the vehicle (real nets split junction approaches into
// edges of a few metres): a one-lane road leads only onto the left lane of a 2-lane edge of a few metres,
// whose right lane alone turns right (netconvert, explicit connections). SUMO changes the front's lane and
// leaves the back on the lanes before; LPSim did not change lanes while the rear was not on the lane, so its
// right-turners stood at the short edge until teleported (mean trip 1778 s against SUMO's 22.9 s). Now the
// right-turners' mean trip is SUMO's within 25 % and nobody teleports.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;
using test::TempDir;

void write_scenario(const TempDir& dir) {
  dir.write("n.nod.xml",
            "<nodes><node id=\"A\" x=\"0\" y=\"0\"/><node id=\"B\" x=\"100\" y=\"0\" type=\"priority\"/>"
            "<node id=\"C\" x=\"103.6\" y=\"0\" type=\"priority\"/><node id=\"R\" x=\"103.6\" y=\"-100\"/>"
            "<node id=\"E\" x=\"203.6\" y=\"0\"/></nodes>\n");
  dir.write("n.edg.xml",
            "<edges><edge id=\"in\" from=\"A\" to=\"B\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"short\" from=\"B\" to=\"C\" numLanes=\"2\" speed=\"13.89\"/>"
            "<edge id=\"right\" from=\"C\" to=\"R\" numLanes=\"1\" speed=\"13.89\"/>"
            "<edge id=\"straight\" from=\"C\" to=\"E\" numLanes=\"1\" speed=\"13.89\"/></edges>\n");
  dir.write("n.con.xml",
            "<connections><connection from=\"in\" to=\"short\" fromLane=\"0\" toLane=\"1\"/>"
            "<connection from=\"short\" to=\"right\" fromLane=\"0\" toLane=\"0\"/>"
            "<connection from=\"short\" to=\"straight\" fromLane=\"1\" toLane=\"0\"/></connections>\n");
  dir.write("r.rou.xml",
            "<routes><flow id=\"r\" begin=\"0\" end=\"900\" vehsPerHour=\"300\"><route edges=\"in short "
            "right\"/></flow><flow id=\"s\" begin=\"0\" end=\"900\" vehsPerHour=\"300\"><route edges=\"in "
            "short straight\"/></flow></routes>\n");
  const CliResult net = test::run_program(
      dir.path(), {"netconvert"},
      {"-n", "n.nod.xml", "-e", "n.edg.xml", "-x", "n.con.xml", "--no-turnarounds", "-o", "n.net.xml"});
  ASSERT_EQ(net.exit_code, 0) << net.err;
}

// Mean duration and count of the trips of flow `id`.
std::pair<double, int> trips_of(const std::string& tripinfo, const std::string& id) {
  const std::regex trip("<tripinfo id=\"" + id + R"re(\.[0-9]+"[^>]* duration="([0-9.]+)")re");
  double sum = 0;
  int n = 0;
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), trip); it != std::sregex_iterator();
       ++it, ++n)
    sum += std::stod((*it)[1]);
  return {n > 0 ? sum / n : 0, n};
}

TEST(ShortEdgeLaneChangeTest, ChangesOnAnEdgeShorterThanTheVehicleAsInSumo) {
  if (!test::have_sumo_tool("sumo") || !test::have_sumo_tool("netconvert"))
    GTEST_SKIP() << "SUMO not installed";
  TempDir dir("lpsim_short_edge_lc");
  ASSERT_NO_FATAL_FAILURE(write_scenario(dir));
  const CliResult sumo = test::run_program(
      dir.path(), {"sumo"},
      {"-n", "n.net.xml", "-r", "r.rou.xml", "--tripinfo-output", "s.xml", "--no-step-log"});
  ASSERT_EQ(sumo.exit_code, 0) << sumo.err;
  const CliResult lpsim = test::run_lpsim(
      dir.path(), {"run", "-n", "n.net.xml", "-r", "r.rou.xml", "--tripinfo-output", "l.xml"});
  ASSERT_EQ(lpsim.exit_code, 0) << lpsim.err;
  EXPECT_EQ(lpsim.err.find("Teleporting"), std::string::npos) << lpsim.err;

  const std::string s = read_file(dir.path() / "s.xml"), l = read_file(dir.path() / "l.xml");
  for (const char* flow : {"r", "s"}) {
    const auto [sumo_mean, sumo_n] = trips_of(s, flow);
    const auto [lpsim_mean, lpsim_n] = trips_of(l, flow);
    EXPECT_EQ(lpsim_n, sumo_n) << flow;
    EXPECT_NEAR(lpsim_mean, sumo_mean, 0.25 * sumo_mean) << flow << ": SUMO " << sumo_mean << " s";
  }
}

}  // namespace
}  // namespace lpsim

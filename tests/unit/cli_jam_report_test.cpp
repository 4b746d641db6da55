// `lpsim run --jam-report FILE`: one <jam> record per teleport and per vehicle standing at least
// --jam-report.stop-time s, naming what bounded its speed and the chain of vehicles blocking it; a chain that
// comes back is a <deadlock>. The real binary on two nets made with netconvert (commands below): a queue at a
// light that never turns green, and a one-lane ring filled until nobody can move. A run's SUMO outputs are
// the same bytes with and without the report. The ring runs the IDM (--default.carfollowmodel IDM).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;

// netconvert -n red.nod.xml -e red.edg.xml --no-turnarounds: nodes a (0,0), b (100,0, traffic_light),
// c (200,0); one-lane edges ab and bc at 13.89 m/s.
constexpr const char* kRedNet = R"NET(<?xml version="1.0" encoding="UTF-8"?>

<net version="1.9" junctionCornerDetail="5" limitTurnSpeed="5.50" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/net_file.xsd">

    <location netOffset="0.00,0.00" convBoundary="0.00,0.00,200.00,0.00" origBoundary="0.00,0.00,200.00,0.00" projParameter="!"/>

    <edge id=":b_0" function="internal">
        <lane id=":b_0_0" index="0" speed="13.89" length="0.10" shape="100.00,-1.60 100.00,-1.60"/>
    </edge>

    <edge id="ab" from="a" to="b" priority="-1">
        <lane id="ab_0" index="0" speed="13.89" length="100.00" shape="0.00,-1.60 100.00,-1.60"/>
    </edge>
    <edge id="bc" from="b" to="c" priority="-1">
        <lane id="bc_0" index="0" speed="13.89" length="100.00" shape="100.00,-1.60 200.00,-1.60"/>
    </edge>

    <tlLogic id="b" type="static" programID="0" offset="0">
        <phase duration="82" state="G"/>
        <phase duration="3"  state="y"/>
        <phase duration="5"  state="r"/>
    </tlLogic>

    <junction id="a" type="dead_end" x="0.00" y="0.00" incLanes="" intLanes="" shape="0.00,0.00 0.00,-3.20"/>
    <junction id="b" type="traffic_light" x="100.00" y="0.00" incLanes="ab_0" intLanes=":b_0_0" shape="100.00,0.00 100.00,-3.20 100.00,0.00">
        <request index="0" response="0" foes="0" cont="0"/>
    </junction>
    <junction id="c" type="dead_end" x="200.00" y="0.00" incLanes="bc_0" intLanes="" shape="200.00,-3.20 200.00,0.00"/>

    <connection from="ab" to="bc" fromLane="0" toLane="0" via=":b_0_0" tl="b" linkIndex="0" dir="s" state="O"/>

    <connection from=":b_0" to="bc" fromLane="0" toLane="0" dir="s" state="M"/>

</net>
)NET";

// The light at b red for the whole run (an add-file program replaces the net's).
constexpr const char* kAlwaysRed = R"(<additional>
    <tlLogic id="b" type="static" programID="red" offset="0">
        <phase duration="10000" state="r"/>
    </tlLogic>
</additional>
)";

constexpr const char* kQueue = R"(<routes>
    <vType id="car" sigma="0"/>
    <vehicle id="q0" type="car" depart="0"><route edges="ab bc"/></vehicle>
    <vehicle id="q1" type="car" depart="5"><route edges="ab bc"/></vehicle>
    <vehicle id="q2" type="car" depart="10"><route edges="ab bc"/></vehicle>
</routes>
)";

// netconvert -n ring.nod.xml -e ring.edg.xml --no-turnarounds: priority nodes n0 (0,0), n1 (40,0), n2
// (40,40), n3 (0,40) joined by the one-lane edges e0 n0->n1, e1 n1->n2, e2 n2->n3, e3 n3->n0 (13.89 m/s).
// Edited by hand: n0 is a traffic light red for the first 40 s, and the junctions' <request> rows are
// removed, so that (as for nets without them, e.g. from CSV) every link keeps its keepClear and a vehicle
// enters a junction only with room behind it. The ring fills behind the red light; once it turns green every
// head waits for room on a full, standing edge: a real deadlock (with the rows, whose links have no foes,
// the vehicles would follow each other round the ring and never lock, in SUMO as in LPSim).
constexpr const char* kRingNet = R"NET(<?xml version="1.0" encoding="UTF-8"?>

<net version="1.9" junctionCornerDetail="5" limitTurnSpeed="5.50" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/net_file.xsd">

    <location netOffset="0.00,0.00" convBoundary="0.00,0.00,40.00,40.00" origBoundary="0.00,0.00,40.00,40.00" projParameter="!"/>

    <edge id=":n0_0" function="internal">
        <lane id=":n0_0_0" index="0" speed="3.90" length="2.58" shape="-1.60,0.00 -1.50,-0.70 -1.20,-1.20 -0.70,-1.50 0.00,-1.60"/>
    </edge>
    <edge id=":n1_0" function="internal">
        <lane id=":n1_0_0" index="0" speed="3.90" length="2.58" shape="40.00,-1.60 40.70,-1.50 41.20,-1.20 41.50,-0.70 41.60,0.00"/>
    </edge>
    <edge id=":n2_0" function="internal">
        <lane id=":n2_0_0" index="0" speed="3.90" length="2.58" shape="41.60,40.00 41.50,40.70 41.20,41.20 40.70,41.50 40.00,41.60"/>
    </edge>
    <edge id=":n3_0" function="internal">
        <lane id=":n3_0_0" index="0" speed="3.90" length="2.58" shape="0.00,41.60 -0.70,41.50 -1.20,41.20 -1.50,40.70 -1.60,40.00"/>
    </edge>

    <tlLogic id="n0" type="static" programID="0" offset="0">
        <phase duration="40" state="r"/>
        <phase duration="1000" state="G"/>
    </tlLogic>

    <edge id="e0" from="n0" to="n1" priority="-1">
        <lane id="e0_0" index="0" speed="13.89" length="40.00" shape="0.00,-1.60 40.00,-1.60"/>
    </edge>
    <edge id="e1" from="n1" to="n2" priority="-1">
        <lane id="e1_0" index="0" speed="13.89" length="40.00" shape="41.60,0.00 41.60,40.00"/>
    </edge>
    <edge id="e2" from="n2" to="n3" priority="-1">
        <lane id="e2_0" index="0" speed="13.89" length="40.00" shape="40.00,41.60 0.00,41.60"/>
    </edge>
    <edge id="e3" from="n3" to="n0" priority="-1">
        <lane id="e3_0" index="0" speed="13.89" length="40.00" shape="-1.60,40.00 -1.60,0.00"/>
    </edge>

    <junction id="n0" type="traffic_light" x="0.00" y="0.00" incLanes="e3_0" intLanes=":n0_0_0" shape="-3.20,0.00 0.00,0.00 0.00,-3.20 -1.78,-2.84 -2.40,-2.40 -2.84,-1.78 -3.11,-0.98"/>
    <junction id="n1" type="priority" x="40.00" y="0.00" incLanes="e0_0" intLanes=":n1_0_0" shape="40.00,0.00 43.20,0.00 42.84,-1.78 42.40,-2.40 41.78,-2.84 40.98,-3.11 40.00,-3.20"/>
    <junction id="n2" type="priority" x="40.00" y="40.00" incLanes="e1_0" intLanes=":n2_0_0" shape="43.20,40.00 40.00,40.00 40.00,43.20 41.78,42.84 42.40,42.40 42.84,41.78 43.11,40.98"/>
    <junction id="n3" type="priority" x="0.00" y="40.00" incLanes="e2_0" intLanes=":n3_0_0" shape="0.00,43.20 0.00,40.00 -3.20,40.00 -2.84,41.78 -2.40,42.40 -1.78,42.84 -0.98,43.11"/>

    <connection from="e0" to="e1" fromLane="0" toLane="0" via=":n1_0_0" dir="l" state="M"/>
    <connection from="e1" to="e2" fromLane="0" toLane="0" via=":n2_0_0" dir="l" state="M"/>
    <connection from="e2" to="e3" fromLane="0" toLane="0" via=":n3_0_0" dir="l" state="M"/>
    <connection from="e3" to="e0" fromLane="0" toLane="0" via=":n0_0_0" tl="n0" linkIndex="0" dir="l" state="O"/>

    <connection from=":n0_0" to="e0" fromLane="0" toLane="0" dir="l" state="M"/>
    <connection from=":n1_0" to="e1" fromLane="0" toLane="0" dir="l" state="M"/>
    <connection from=":n2_0" to="e2" fromLane="0" toLane="0" dir="l" state="M"/>
    <connection from=":n3_0" to="e3" fromLane="0" toLane="0" dir="l" state="M"/>

</net>
)NET";

// More vehicles than the ring holds, each going round it many times: the ring fills and locks (see kRingNet).
std::string ring_routes() {
  const std::vector<std::string> edges{"e0", "e1", "e2", "e3"};
  std::string out = "<routes>\n    <vType id=\"car\" sigma=\"0\"/>\n";
  int id = 0;
  for (int t = 0; t < 40; t += 2)
    for (size_t k = 0; k < edges.size(); ++k) {
      std::string route;
      for (int lap = 0; lap < 25; ++lap)
        for (size_t e = 0; e < edges.size(); ++e) route += (route.empty() ? "" : " ") + edges[(k + e) % 4];
      out += "    <vehicle id=\"r" + std::to_string(id++) + "\" type=\"car\" depart=\"" + std::to_string(t) +
             "\"><route edges=\"" + route + "\"/></vehicle>\n";
    }
  return out + "</routes>\n";
}

// The <jam ...> element (up to its end) whose id attribute is `id`, "" if none.
std::string jam_of(const std::string& report, const std::string& id) {
  const size_t at = report.find("<jam id=\"" + id + "\"");
  if (at == std::string::npos) return "";
  const size_t self_closed = report.find("/>\n", at), open_end = report.find(">\n", at);
  if (self_closed != std::string::npos && self_closed < open_end)
    return report.substr(at, self_closed + 3 - at);
  return report.substr(at, report.find("</jam>", at) + 6 - at);
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class CliJamReportTest : public ::testing::Test {
 protected:
  CliResult run(const std::vector<std::string>& args) const { return test::run_lpsim(tmp_.path(), args); }

  test::TempDir tmp_{"lpsim_jam_report"};
};

TEST_F(CliJamReportTest, QueueAtARedLightNamesTheSignalAndTheChainOfLeaders) {
  tmp_.write("red.net.xml", kRedNet);
  tmp_.write("red.add.xml", kAlwaysRed);
  tmp_.write("q.rou.xml", kQueue);
  const CliResult r = run({"run", "-n", "red.net.xml", "-r", "q.rou.xml", "-a", "red.add.xml", "--end", "200",
                           "--jam-report", "jam.xml", "--jam-report.stop-time", "30"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(tmp_.path() / "jam.xml");
  EXPECT_NE(report.find("<jamReport stopTime=\"30.00\">"), std::string::npos) << report;
  EXPECT_NE(report.find("</jamReport>\n"), std::string::npos) << report;
  EXPECT_EQ(count(report, "<jam "), 3u) << report;
  EXPECT_EQ(count(report, "<deadlock"), 0u) << report;

  // The head of the queue stands at the stop line for the red light: no vehicle blocks it.
  const std::string q0 = jam_of(report, "q0");
  EXPECT_NE(q0.find("lane=\"ab_0\""), std::string::npos) << q0;
  EXPECT_NE(q0.find("reason=\"signal\""), std::string::npos) << q0;
  EXPECT_NE(q0.find("ended=\"running\""), std::string::npos) << q0;
  EXPECT_EQ(q0.find("<blocker"), std::string::npos) << q0;
  // The others stand behind their leader, the chain ending at the vehicle the light holds.
  const std::string q1 = jam_of(report, "q1");
  EXPECT_NE(q1.find("reason=\"leader\""), std::string::npos) << q1;
  EXPECT_NE(q1.find("<blocker id=\"q0\" lane=\"ab_0\""), std::string::npos) << q1;
  EXPECT_EQ(count(q1, "<blocker"), 1u) << q1;
  const std::string q2 = jam_of(report, "q2");
  EXPECT_NE(q2.find("reason=\"leader\""), std::string::npos) << q2;
  const size_t first = q2.find("<blocker id=\"q1\""), second = q2.find("<blocker id=\"q0\"");
  ASSERT_NE(first, std::string::npos) << q2;
  ASSERT_NE(second, std::string::npos) << q2;
  EXPECT_LT(first, second) << q2;
  EXPECT_NE(q2.find("reason=\"signal\"/>", second), std::string::npos) << q2;
}

TEST_F(CliJamReportTest, ShortStopsAreNotReported) {
  tmp_.write("red.net.xml", kRedNet);
  tmp_.write("red.add.xml", kAlwaysRed);
  tmp_.write("q.rou.xml", kQueue);
  // q2 arrives at the queue last: by t=60 it has stood well under 55 s.
  const CliResult r = run({"run", "-n", "red.net.xml", "-r", "q.rou.xml", "-a", "red.add.xml", "--end", "60",
                           "--jam-report", "jam.xml", "--jam-report.stop-time", "55"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(tmp_.path() / "jam.xml");
  EXPECT_EQ(jam_of(report, "q2"), "") << report;
}

TEST_F(CliJamReportTest, AFullRingIsReportedAsADeadlockCycle) {
  tmp_.write("ring.net.xml", kRingNet);
  tmp_.write("ring.rou.xml", ring_routes());
  const CliResult r = run({"run", "-n", "ring.net.xml", "-r", "ring.rou.xml", "--end", "400", "--jam-report",
                           "jam.xml", "--time-to-teleport", "-1", "--default.carfollowmodel", "IDM"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(tmp_.path() / "jam.xml");
  const size_t at = report.find("<deadlock vehicles=\"");
  ASSERT_NE(at, std::string::npos) << report;
  // The cycle goes round the ring: its vehicles stand on all four edges.
  const std::string deadlock = report.substr(at, report.find("/>", at) - at);
  for (const char* lane : {"e0_0", "e1_0", "e2_0", "e3_0"})
    EXPECT_NE(deadlock.find(lane), std::string::npos) << lane << " missing: " << deadlock;
}

TEST_F(CliJamReportTest, ATeleportIsRecordedWithItsCause) {
  tmp_.write("red.net.xml", kRedNet);
  tmp_.write("red.add.xml", kAlwaysRed);
  tmp_.write("q.rou.xml", kQueue);
  const CliResult r = run({"run", "-n", "red.net.xml", "-r", "q.rou.xml", "-a", "red.add.xml", "--end", "200",
                           "--jam-report", "jam.xml", "--time-to-teleport", "40", "--no-warnings"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(tmp_.path() / "jam.xml");
  const std::string q0 = jam_of(report, "q0");
  EXPECT_NE(q0.find("ended=\"teleported\""), std::string::npos) << report;
  EXPECT_NE(q0.find("teleport=\""), std::string::npos) << q0;
}

TEST_F(CliJamReportTest, OutputsAreTheSameWithAndWithoutTheReport) {
  tmp_.write("ring.net.xml", kRingNet);
  tmp_.write("ring.rou.xml", ring_routes());
  // The ring locks (see kRingNet): the report has stops to record.
  const std::vector<std::string> base{"run",
                                      "-n",
                                      "ring.net.xml",
                                      "-r",
                                      "ring.rou.xml",
                                      "--end",
                                      "300",
                                      "--time-to-teleport",
                                      "100",
                                      "--no-warnings",
                                      "--default.carfollowmodel",
                                      "IDM"};
  const std::vector<std::string> outputs_a{"--fcd-output", "a.fcd.xml",        "--tripinfo-output",
                                           "a.trip.xml",   "--summary-output", "a.sum.xml"};
  const std::vector<std::string> outputs_b{"--fcd-output",     "b.fcd.xml", "--tripinfo-output", "b.trip.xml",
                                           "--summary-output", "b.sum.xml", "--jam-report",      "jam.xml"};
  std::vector<std::string> without = base, with = base;
  without.insert(without.end(), outputs_a.begin(), outputs_a.end());
  with.insert(with.end(), outputs_b.begin(), outputs_b.end());
  ASSERT_EQ(run(without).exit_code, 0);
  ASSERT_EQ(run(with).exit_code, 0);
  ASSERT_NE(read_file(tmp_.path() / "jam.xml").find("<jam "), std::string::npos);
  for (const char* kind : {".fcd.xml", ".trip.xml", ".sum.xml"}) {
    const std::string a = read_file(tmp_.path() / (std::string("a") + kind));
    EXPECT_FALSE(a.empty()) << kind;
    EXPECT_EQ(a, read_file(tmp_.path() / (std::string("b") + kind))) << kind;
  }
}

TEST_F(CliJamReportTest, TheReportMayNotOverwriteAnInputOrAnotherOutput) {
  tmp_.write("red.net.xml", kRedNet);
  tmp_.write("q.rou.xml", kQueue);
  const CliResult r = run({"run", "-n", "red.net.xml", "-r", "q.rou.xml", "--jam-report", "q.rou.xml"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--jam-report 'q.rou.xml'"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(tmp_.path() / "q.rou.xml"), kQueue);
  const CliResult t = run({"run", "-n", "red.net.xml", "-r", "q.rou.xml", "--jam-report", "j.xml",
                           "--jam-report.stop-time", "0"});
  EXPECT_EQ(t.exit_code, 2) << t.err;
  EXPECT_NE(t.err.find("--jam-report.stop-time"), std::string::npos) << t.err;
}

}  // namespace
}  // namespace lpsim

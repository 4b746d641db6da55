#include "converters/lpsim_csv_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "converters/csv_table.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

class LpsimCsvReaderTest : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) const { return tmp_.write(name, text); }

  test::TempDir tmp_{"lpsim_csv"};
};

// A cross: C (id 2) in the middle, W (1), E (3), N (4), S (5) about 0.001 degrees away. The east-west road
// has 2 lanes at 35 mph, the north-south road 1 lane (with empty / zero lanes and speeds on two edges).
std::string cross_nodes(bool signal_at_centre) {
  return std::string("osmid,x,y,ref,highway\n") + "1,-122.001,37.0,,\n" + "2,-122.0,37.0,," +
         (signal_at_centre ? "traffic_signals" : "") + "\n" + "3,-121.999,37.0,,\n" +
         "4,-122.0,37.001,,stop\n" + "5,-122.0,36.999,,\n";
}

const char* kCrossEdgesByOsmid =
    "uniqueid,u,v,length,lanes,speed_mph\n"
    "10,1,2,88.8,2,35\n"
    "11,2,1,88.8,2,35\n"
    "12,2,3,88.8,2,35\n"
    "13,3,2,88.8,2,35\n"
    "14,4,2,111.2,1,25\n"
    "15,2,4,111.2,,\n"
    "16,5,2,111.2,0,0\n"
    "17,2,5,111.2,1,25\n";

const EdgeSpec& edge(const NetSpec& net, const std::string& id) {
  for (const auto& e : net.edges)
    if (e.id == id) return e;
  throw std::runtime_error("no edge " + id);
}

const JunctionSpec& junction(const NetSpec& net, const std::string& id) {
  for (const auto& j : net.junctions)
    if (j.id == id) return j;
  throw std::runtime_error("no junction " + id);
}

std::vector<ConnectionSpec> connections(const NetSpec& net, const std::string& from, const std::string& to) {
  std::vector<ConnectionSpec> out;
  for (const auto& c : net.connections)
    if (c.from == from && c.to == to) out.push_back(c);
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(CsvTable, ParsesQuotedFieldsAndTracksLines) {
  const CsvTable t = CsvTable::parse(
      "a, b ,c\r\n1,\"x,y\",\"say \"\"hi\"\"\"\r\n\n2,\"two\nlines\",\n3,, 4.5 \n", "mem.csv");
  ASSERT_EQ(t.num_columns(), 3u);
  ASSERT_EQ(t.num_rows(), 3u);
  EXPECT_EQ(t.column("b"), 1u);
  EXPECT_EQ(t.field(0, 1), "x,y");
  EXPECT_EQ(t.field(0, 2), "say \"hi\"");
  EXPECT_EQ(t.field(1, 1), "two\nlines");
  EXPECT_EQ(t.field(1, 2), "");
  EXPECT_EQ(t.loc(0).line, 2);
  EXPECT_EQ(t.loc(1).line, 4);
  EXPECT_EQ(t.loc(2).line, 6);
  EXPECT_DOUBLE_EQ(t.number(2, 2), 4.5);
  EXPECT_FALSE(t.optional_number(2, 1).has_value());
  EXPECT_EQ(t.integer(0, 0), 1);
}

TEST(CsvTable, RejectsMalformedInput) {
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n1,2\n3\n", "f.csv"); }).find("f.csv:3:"), std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n1,\"2\n", "f.csv"); }).find("unterminated"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n1,2\"x\n", "f.csv"); }).find("f.csv:2:"), std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("", "f.csv"); }).find("empty"), std::string::npos);
  const CsvTable t = CsvTable::parse("a,b\n1,abc\n2,nan\n2.5,1e3x\n", "f.csv");
  EXPECT_EQ(error_of([&] { t.number(0, 1); }), "f.csv:2: column 'b' value 'abc': not a number");
  EXPECT_NE(error_of([&] { t.number(1, 1); }).find("not a finite number"), std::string::npos);
  EXPECT_NE(error_of([&] { t.integer(2, 0); }).find("f.csv:4: column 'a' value '2.5'"), std::string::npos);
  EXPECT_NE(error_of([&] { t.column("zz"); }).find("missing CSV column 'zz'"), std::string::npos);
}

TEST_F(LpsimCsvReaderTest, ReadsLanesSpeedsLengthsAndProjectsDegrees) {
  const NetSpec net =
      read_lpsim_csv_net(write("nodes.csv", cross_nodes(false)), write("edges.csv", kCrossEdgesByOsmid));
  ASSERT_EQ(net.edges.size(), 8u);
  ASSERT_EQ(net.junctions.size(), 5u);
  // Junctions keep the nodes.csv order (OD indices depend on it).
  EXPECT_EQ(net.junctions[0].id, "1");
  EXPECT_EQ(net.junctions[4].id, "5");

  const EdgeSpec& we = edge(net, "10");
  EXPECT_EQ(we.from, "1");
  EXPECT_EQ(we.to, "2");
  ASSERT_EQ(we.lanes.size(), 2u);
  EXPECT_EQ(we.lanes[1].id, "10_1");
  EXPECT_EQ(we.lanes[1].index, 1);
  EXPECT_NEAR(we.lanes[0].speed, 35 * 0.44704, 1e-12);
  EXPECT_DOUBLE_EQ(we.lanes[0].length, 88.8);
  EXPECT_EQ(edge(net, "15").lanes.size(), 1u);              // empty lanes -> 1
  EXPECT_DOUBLE_EQ(edge(net, "15").lanes[0].speed, 13.89);  // empty speed -> default
  EXPECT_EQ(edge(net, "16").lanes.size(), 1u);              // 0 lanes -> 1
  EXPECT_DOUBLE_EQ(edge(net, "16").lanes[0].speed, 13.89);  // 0 mph -> default

  // Equirectangular around the mean latitude (37.0), south-west corner at the origin.
  const double metres_per_degree = 6371008.8 * std::numbers::pi / 180;
  const JunctionSpec& w = junction(net, "1");
  const JunctionSpec& c = junction(net, "2");
  const JunctionSpec& s = junction(net, "5");
  EXPECT_NEAR(w.x, 0, 1e-6);
  EXPECT_NEAR(s.y, 0, 1e-6);
  EXPECT_NEAR(c.x - w.x, 0.001 * metres_per_degree * std::cos(37.0 * std::numbers::pi / 180), 1e-6);
  EXPECT_NEAR(c.y - s.y, 0.001 * metres_per_degree, 1e-6);
  EXPECT_NEAR(c.x - w.x, 88.8, 0.1);
  // Lane shapes: straight from node to node.
  ASSERT_EQ(we.lanes[0].shape.size(), 2u);
  EXPECT_DOUBLE_EQ(we.lanes[0].shape[0].x, w.x);
  EXPECT_DOUBLE_EQ(we.lanes[0].shape[1].x, c.x);
  EXPECT_DOUBLE_EQ(we.lanes[0].shape[1].y, c.y);
  // Incoming lanes at the centre: 2 + 2 + 1 + 1.
  EXPECT_EQ(c.inc_lanes.size(), 6u);
  EXPECT_EQ(c.inc_lanes[0], "10_0");
  EXPECT_EQ(c.type, "priority");
}

TEST_F(LpsimCsvReaderTest, FullNetworkHeaderUsesOsmidColumns) {
  // u/v carry dense indices in this header; they are deliberately inconsistent to prove osmid_u/osmid_v win.
  const std::string edges =
      "uniqueid,osmid_u,osmid_v,length,lanes,speed_mph,u,v\n"
      "a,1,2,88.8,2,35,4,4\n"
      "b,2,1,88.8,1,30,4,4\n";
  const NetSpec net = read_lpsim_csv_net(write("nodes.csv", cross_nodes(false)), write("edges.csv", edges));
  ASSERT_EQ(net.edges.size(), 2u);
  EXPECT_EQ(edge(net, "a").from, "1");
  EXPECT_EQ(edge(net, "a").to, "2");
  EXPECT_EQ(edge(net, "b").lanes.size(), 1u);
  EXPECT_NEAR(edge(net, "b").lanes[0].speed, 30 * 0.44704, 1e-12);
}

TEST_F(LpsimCsvReaderTest, KeepsMetricCoordinates) {
  // Every coordinate also fits the degree ranges; the edge lengths show they are metres.
  const std::string nodes = "osmid,x,y\nA,0,0\nB,60,80\nC,60,0\n";
  const std::string edges = "uniqueid,u,v,length,lanes,speed_mph\ne1,A,B,100,1,30\ne2,B,C,80,1,30\n";
  const NetSpec net = read_lpsim_csv_net(write("nodes.csv", nodes), write("edges.csv", edges));
  EXPECT_DOUBLE_EQ(junction(net, "B").x, 60);
  EXPECT_DOUBLE_EQ(junction(net, "B").y, 80);
  EXPECT_EQ(junction(net, "A").type, "dead_end");  // no incoming edge
  EXPECT_EQ(junction(net, "C").type, "dead_end");  // no outgoing edge
  ASSERT_EQ(net.connections.size(), 1u);
  EXPECT_EQ(net.connections[0].from, "e1");
  EXPECT_EQ(net.connections[0].to, "e2");
  EXPECT_EQ(net.connections[0].dir, 'r');  // heading north-east, then south
}

TEST_F(LpsimCsvReaderTest, DerivesConnectionsDirectionsAndPriorities) {
  const NetSpec net =
      read_lpsim_csv_net(write("nodes.csv", cross_nodes(false)), write("edges.csv", kCrossEdgesByOsmid));
  // Centre: 2-lane approaches reach 3 edges with 2 lanes each, 1-lane approaches 3 edges: 6+6+3+3; each arm
  // end offers only the U-turn: 2 + 2 + 1 + 1.
  EXPECT_EQ(net.connections.size(), 24u);
  EXPECT_TRUE(connections(net, "10", "11").empty());  // U-turn at the centre is not derived

  const auto straight = connections(net, "10", "12");
  ASSERT_EQ(straight.size(), 2u);
  EXPECT_EQ(straight[0].from_lane, 0);
  EXPECT_EQ(straight[0].to_lane, 0);
  EXPECT_EQ(straight[1].from_lane, 1);
  EXPECT_EQ(straight[1].to_lane, 1);
  EXPECT_EQ(straight[0].dir, 's');
  EXPECT_EQ(straight[0].state, 'M');
  EXPECT_TRUE(straight[0].via.empty());
  EXPECT_TRUE(straight[0].tl.empty());
  EXPECT_EQ(straight[0].link_index, -1);

  const auto left = connections(net, "10", "15");  // eastbound, then north
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[1].from_lane, 1);
  EXPECT_EQ(left[1].to_lane, 0);  // 2 lanes onto 1
  EXPECT_EQ(left[0].dir, 'l');
  EXPECT_EQ(left[0].state, 'm');  // major road's left turn yields
  const auto right = connections(net, "10", "17");
  ASSERT_EQ(right.size(), 2u);
  EXPECT_EQ(right[0].dir, 'r');
  EXPECT_EQ(right[0].state, 'M');
  EXPECT_EQ(connections(net, "13", "15")[0].dir, 'r');  // westbound, then north
  EXPECT_EQ(connections(net, "13", "17")[0].dir, 'l');
  // Side road approaches are minor whatever the turn.
  const auto side = connections(net, "14", "17");
  ASSERT_EQ(side.size(), 1u);
  EXPECT_EQ(side[0].dir, 's');
  EXPECT_EQ(side[0].state, 'm');
  EXPECT_EQ(connections(net, "14", "11")[0].dir, 'r');
  EXPECT_EQ(connections(net, "16", "11")[0].dir, 'l');

  // The arm end's only exit is the U-turn.
  const auto turn = connections(net, "11", "10");
  ASSERT_EQ(turn.size(), 2u);
  EXPECT_EQ(turn[0].dir, 't');
}

TEST_F(LpsimCsvReaderTest, DerivesFixedTimeSignal) {
  const NetSpec net =
      read_lpsim_csv_net(write("nodes.csv", cross_nodes(true)), write("edges.csv", kCrossEdgesByOsmid));
  EXPECT_EQ(junction(net, "2").type, "traffic_light");
  ASSERT_EQ(net.tl_logics.size(), 1u);
  const TlLogicSpec& tl = net.tl_logics[0];
  EXPECT_EQ(tl.id, "2");
  EXPECT_EQ(tl.program_id, "0");
  EXPECT_EQ(tl.type, "static");
  ASSERT_EQ(tl.phases.size(), 4u);
  EXPECT_DOUBLE_EQ(tl.phases[0].duration, 30);
  EXPECT_DOUBLE_EQ(tl.phases[1].duration, 3);
  EXPECT_DOUBLE_EQ(tl.phases[2].duration, 30);
  EXPECT_DOUBLE_EQ(tl.phases[3].duration, 3);
  // Links: approach 10 (s s l l r r), 13 (s s r r l l), 14 (r l s), 16 (l r s). East-west is group A.
  EXPECT_EQ(tl.phases[0].state, "GGggGGGGGGggrrrrrr");
  EXPECT_EQ(tl.phases[1].state, "yyyyyyyyyyyyrrrrrr");
  EXPECT_EQ(tl.phases[2].state, "rrrrrrrrrrrrGgGgGG");
  EXPECT_EQ(tl.phases[3].state, "rrrrrrrrrrrryyyyyy");

  int link = 0;
  for (const auto& c : net.connections) {
    if (edge(net, c.from).to != "2") {
      EXPECT_TRUE(c.tl.empty());
      continue;
    }
    EXPECT_EQ(c.tl, "2");
    EXPECT_EQ(c.link_index, link++);
  }
  EXPECT_EQ(link, 18);
  EXPECT_EQ(connections(net, "10", "12")[0].state, 'O');
  EXPECT_EQ(connections(net, "10", "15")[0].state, 'o');
  EXPECT_EQ(connections(net, "14", "17")[0].state, 'o');
}

TEST_F(LpsimCsvReaderTest, NoSignalWithoutCrossingApproaches) {
  // A signalised node on a straight two-way road (e.g. a pedestrian light): both approaches share one axis.
  const std::string nodes = "osmid,x,y,highway\n1,0,0,\n2,100,0,traffic_signals\n3,200,0,\n";
  const std::string edges =
      "uniqueid,u,v,length,lanes,speed_mph\na,1,2,100,1,30\nb,2,3,100,1,30\nc,3,2,100,1,30\nd,2,1,100,1,30\n";
  const NetSpec net = read_lpsim_csv_net(write("nodes.csv", nodes), write("edges.csv", edges));
  EXPECT_EQ(junction(net, "2").type, "priority");
  EXPECT_TRUE(net.tl_logics.empty());
  EXPECT_EQ(connections(net, "a", "b")[0].state, 'M');
  EXPECT_EQ(connections(net, "c", "d")[0].state, 'M');
}

TEST_F(LpsimCsvReaderTest, RejectsBadNetworkInput) {
  const std::string nodes = write("nodes.csv", "osmid,x,y\n1,0,0\n2,100,0\n");
  auto net_error = [&](const std::string& edges) {
    const std::string path = write("edges.csv", edges);
    return error_of([&] { read_lpsim_csv_net(nodes, path); });
  };
  const std::string head = "uniqueid,u,v,length,lanes,speed_mph\n";
  const std::string edges_path = (tmp_.path() / "edges.csv").string();

  EXPECT_NE(error_of([&] {
              read_lpsim_csv_net((tmp_.path() / "missing.csv").string(), nodes);
            }).find("missing.csv"),
            std::string::npos);
  EXPECT_NE(net_error("uniqueid,u,v,lanes\ne,1,2,1\n").find("missing CSV column 'length'"),
            std::string::npos);
  EXPECT_EQ(net_error(head + "e,1,2,100,1,30\nf,2,1,abc,1,30\n"),
            edges_path + ":3: column 'length' value 'abc': not a number");
  EXPECT_EQ(net_error(head + "e,1,2,-5,1,30\n"),
            edges_path + ":2: column 'length' value '-5': negative length");
  EXPECT_NE(net_error(head + "e,1,2,NaN,1,30\n").find(":2: column 'length' value 'NaN'"), std::string::npos);
  EXPECT_EQ(net_error(head + "e,1,9,100,1,30\n"),
            edges_path + ":2: column 'v' value '9': unknown node (not in the nodes file)");
  EXPECT_EQ(net_error(head + "e,1,2,100,1,30\ne,2,1,100,1,30\n"),
            edges_path + ":3: column 'uniqueid' value 'e': duplicate edge id");
  EXPECT_NE(net_error(head + "e,1,2,100,-1,30\n").find("column 'lanes' value '-1'"), std::string::npos);
  EXPECT_NE(net_error(head + "e,1,2,100,1,-3\n").find("column 'speed_mph' value '-3'"), std::string::npos);

  const std::string bad_nodes = write("bad_nodes.csv", "osmid,x,y\n1,0,0\n1,5,x\n");
  EXPECT_NE(
      error_of([&] { read_lpsim_csv_net(bad_nodes, edges_path); }).find("bad_nodes.csv:3: column 'osmid'"),
      std::string::npos);
}

TEST_F(LpsimCsvReaderTest, ReadsOdDemand) {
  const NetSpec net =
      read_lpsim_csv_net(write("nodes.csv", cross_nodes(true)), write("edges.csv", kCrossEdgesByOsmid));
  DemandSpec demand;
  const std::string od = write("od.csv",
                               ",SAMPN,origin_osmid,dep_time,origin,destination\n"
                               "7,1,x,36.5,0,4\n"
                               "3,2,y,10,3.0,2\n");
  read_lpsim_od_csv(od, net, demand);
  ASSERT_EQ(demand.vehicles.size(), 2u);
  const VehicleSpec& v = demand.vehicles[0];
  EXPECT_EQ(v.id, "od0");
  EXPECT_EQ(v.source, DemandSource::OdCsv);
  EXPECT_DOUBLE_EQ(v.depart, 36.5);
  EXPECT_EQ(v.from_junction, "1");
  EXPECT_EQ(v.to_junction, "5");
  EXPECT_EQ(v.loc.line, 2);
  EXPECT_EQ(demand.vehicles[1].id, "od1");
  EXPECT_EQ(demand.vehicles[1].from_junction, "4");
  EXPECT_EQ(demand.vehicles[1].to_junction, "3");

  const std::string bad = write("bad_od.csv", "dep_time,origin,destination\n1,0,1\n2,0,5\n");
  EXPECT_EQ(error_of([&] { read_lpsim_od_csv(bad, net, demand); }),
            bad + ":3: column 'destination' value '5': not a node index (the network has 5 nodes, 0..4)");
  const std::string negative = write("neg_od.csv", "dep_time,origin,destination\n-1,0,1\n");
  EXPECT_NE(error_of([&] { read_lpsim_od_csv(negative, net, demand); }).find("negative departure time"),
            std::string::npos);
  const std::string no_column = write("nocol_od.csv", "dep_time,origin\n1,0\n");
  EXPECT_NE(error_of([&] { read_lpsim_od_csv(no_column, net, demand); }).find("'destination'"),
            std::string::npos);
}

TEST(LpsimCsvSmallScenario, LoadsInBothHeaders) {
  const std::string dir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small/";
  const NetSpec a = read_lpsim_csv_net(dir + "nodes.csv", dir + "edges.csv");
  const NetSpec b = read_lpsim_csv_net(dir + "nodes.csv", dir + "edges_full_header.csv");
  for (const NetSpec* net : {&a, &b}) {
    EXPECT_EQ(net->junctions.size(), 6u);
    ASSERT_EQ(net->edges.size(), 10u);
    size_t lanes = 0;
    for (const auto& e : net->edges) lanes += e.lanes.size();
    EXPECT_EQ(lanes, 14u);
    // Centre 6+6+3+3, west end U-turn 2, east node 2+1, the three other ends 1 each.
    EXPECT_EQ(net->connections.size(), 26u);
    ASSERT_EQ(net->tl_logics.size(), 1u);
    EXPECT_EQ(net->tl_logics[0].id, "1001");
    EXPECT_EQ(net->tl_logics[0].phases[0].state.size(), 18u);
  }
  for (size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].from, b.edges[i].from);
    EXPECT_EQ(a.edges[i].to, b.edges[i].to);
  }
  DemandSpec demand;
  read_lpsim_od_csv(dir + "od.csv", a, demand);
  ASSERT_EQ(demand.vehicles.size(), 8u);
  EXPECT_EQ(demand.vehicles[2].id, "od2");
  EXPECT_DOUBLE_EQ(demand.vehicles[2].depart, 10.5);
  EXPECT_EQ(demand.vehicles[2].from_junction, "1004");
  EXPECT_EQ(demand.vehicles[2].to_junction, "1005");
}

}  // namespace
}  // namespace lpsim

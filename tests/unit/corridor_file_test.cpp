// The corridor file of `lpsim cosim`: a sumo-gui selection (edge:, lane:, other kinds counted) or plain edge
// ids read in, every malformed line refused with file:line, and the edges resolved against a bundled
// network (unknown or internal ones refused with file:line).
#include "converters/corridor_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "app/corridor_resolution.hpp"
#include "app/scenario.hpp"
#include "converters/cli_options.hpp"
#include "core/error.hpp"
#include "net/network_builder.hpp"
#include "temp_dir.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

using test::TempDir;

const Scenario& grid() {
  static const Scenario sc = load_scenario(
      parse_cli_options({"-c", std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg"}));
  return sc;
}

class CorridorFileTest : public ::testing::Test {
 protected:
  TempDir dir{"lpsim_corridor_file"};
  std::string file(const std::string& text) {
    const std::string path = dir.path().string() + "/corridor.txt";
    std::ofstream(path) << text;
    return path;
  }
  // The message of the InputError that reading and resolving `text` raises ("" if none).
  std::string error(const std::string& text) {
    try {
      resolve_corridor(read_corridor_file(file(text)), grid().network);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(CorridorFileTest, ReadsASumoGuiSelectionAndPlainIds) {
  const CorridorSpec spec =
      read_corridor_file(file("# saved by sumo-gui\nedge:A0B0\n\n  lane:B0C0_1 \njunction:B0\njunction:C0\n"
                              "vehicle:x\nB1C1\n"));
  ASSERT_EQ(spec.items.size(), 3u);
  EXPECT_EQ(spec.items[0].id, "A0B0");
  EXPECT_FALSE(spec.items[0].lane);
  EXPECT_EQ(spec.items[0].line, 2);
  EXPECT_EQ(spec.items[1].id, "B0C0_1");
  EXPECT_TRUE(spec.items[1].lane);
  EXPECT_EQ(spec.items[1].line, 4);
  EXPECT_EQ(spec.items[2].id, "B1C1");
  EXPECT_EQ(spec.items[2].line, 8);
  const std::vector<std::pair<std::string, int>> others{{"junction", 2}, {"vehicle", 1}};
  EXPECT_EQ(spec.other_kinds, others);
  // A UTF-8 byte-order mark before the first line is not part of it (before, it hid that line's edge).
  const CorridorSpec bom =
      read_corridor_file(file("\xEF\xBB\xBF"
                              "edge:A0B0\n"));
  ASSERT_EQ(bom.items.size(), 1u);
  EXPECT_EQ(bom.items[0].id, "A0B0");

  const Network& net = grid().network;
  const std::vector<uint32_t> edges = resolve_corridor(spec, net);
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_EQ(net.edge_id[edges[0]], "A0B0");
  EXPECT_EQ(net.edge_id[edges[1]], "B0C0");
  EXPECT_EQ(net.edge_id[edges[2]], "B1C1");
  // An edge named twice (itself, and through a lane) is one corridor edge.
  EXPECT_EQ(resolve_corridor(read_corridor_file(file("edge:A0B0\nlane:A0B0_0\nA0B0\n")), net).size(), 1u);
}

TEST_F(CorridorFileTest, RefusesWhatIsNotACorridorWithFileAndLine) {
  const std::string at = dir.path().string() + "/corridor.txt:";
  EXPECT_EQ(error("edge:A0B0\nedge:NOPE\n"), at + "2: edge 'NOPE' is not in the network");
  EXPECT_EQ(error("lane:A0B0_9\n"), at + "1: lane 'A0B0_9' is not a vehicle lane of the network");
  EXPECT_EQ(error("A0B0 B0C0\n"),
            at + "1: one object per line expected (edge:ID or an edge id), got 'A0B0 B0C0'");
  EXPECT_EQ(error("\nedge:\n"), at + "2: no id after 'edge:'");
  EXPECT_EQ(error("# nothing\njunction:B0\n"),
            dir.path().string() + "/corridor.txt: the corridor file names no edge");
  EXPECT_NE(error(":B0_0\n").find("1: ':B0_0' is inside a junction"), std::string::npos) << error(":B0_0\n");
  EXPECT_NE(error("").find("names no edge"), std::string::npos);
  // A kind sumo-gui never writes is not a selection line (before, 'Edge:A0B0' was dropped silently).
  EXPECT_EQ(
      error("edge:A0B0\nEdge:B0C0\n"),
      at + "2: 'Edge:' is not a kind of object sumo-gui selects (a corridor line is edge:ID, lane:ID or an "
           "edge id), got 'Edge:B0C0'");
  EXPECT_NE(error("edge:A0B0\nj\x01x:B0\n").find(at + "2: "), std::string::npos);
  try {
    read_corridor_file(dir.path().string() + "/missing.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt: cannot open corridor file"), std::string::npos);
  }
}

// Ids in error messages come from files and may hold any byte: control bytes are written as \\xNN (a NUL
// used to end the message there, an escape sequence went to the terminal) and an id of megabytes is cut in
// its middle, so that the error stays one readable line.
TEST_F(CorridorFileTest, ErrorMessagesEscapeControlBytesAndCutHugeIds) {
  const std::string at = dir.path().string() + "/corridor.txt:";
  EXPECT_EQ(error(std::string("edge:A\0B\x1b[31m\n", 14)),
            at + "1: edge 'A\\x00B\\x1b[31m' is not in the network");
  const std::string huge = error("edge:" + std::string(3000000, 'x') + "\n");
  EXPECT_LT(huge.size(), 2100u);
  EXPECT_NE(huge.find(at + "1: edge 'xxx"), std::string::npos);
  EXPECT_NE(huge.find("bytes left out ...]"), std::string::npos) << huge.substr(0, 200);
  EXPECT_NE(huge.find("xxx' is not in the network"), std::string::npos);
}

// A road no vehicle may use (a footpath) has nothing of LPSim's for SUMO to drive: refused with file:line.
TEST_F(CorridorFileTest, RefusesAnEdgeWithoutVehicleLanes) {
  NetSpec spec = test::make_signal_spec();
  for (auto& e : spec.edges)
    if (e.id == "WtoC")
      for (auto& l : e.lanes) l.permissions = kVClassPedestrian;
  const Network net = build_network(spec);
  ASSERT_EQ(net.edge_num_lanes[net.edge_index.at("WtoC")], 0);
  try {
    resolve_corridor(read_corridor_file(file("edge:NtoC\nedge:WtoC\n")), net);
    FAIL() << "a footpath taken into the corridor";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("corridor.txt:2: edge 'WtoC' has no lane a road vehicle may use"),
              std::string::npos)
        << e.what();
  }
}

// Closed over its junctions: every road into a junction the corridor leads to joins it, nothing else.
TEST_F(CorridorFileTest, ClosingTakesInEveryApproachOfTheCorridorsJunctions) {
  const Network& net = grid().network;
  const std::vector<uint32_t> edges =
      resolve_corridor(read_corridor_file(file("edge:A2B2\nedge:B2C2\n")), net);
  const std::vector<uint32_t> closed = close_corridor(edges, net);
  std::vector<std::string> ids;
  for (const uint32_t e : closed) ids.push_back(net.edge_id[e]);
  std::sort(ids.begin(), ids.end());
  // The roads into B2 and into C2: from each of their four neighbours.
  EXPECT_EQ(ids, (std::vector<std::string>{"A2B2", "B1B2", "B2C2", "B3B2", "C1C2", "C2B2", "C3C2", "D2C2"}))
      << ::testing::PrintToString(ids);
  EXPECT_TRUE(std::is_sorted(closed.begin(), closed.end()));
  EXPECT_EQ(close_corridor(closed, net), closed);  // closed already
}

}  // namespace
}  // namespace lpsim

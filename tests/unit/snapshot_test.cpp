// Snapshots: load_scenario -> write_snapshot -> read_snapshot must give back every Network and Demand column
// unchanged, `lpsim info` on the snapshot must print what it prints for the XML (only the load time
// differs), and damaged or foreign-version snapshots must be refused.
#include "app/snapshot.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "converters/sumocfg_reader.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::string kScenarios = LPSIM_SCENARIOS_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Header layout (snapshot.hpp): 8-byte magic, uint32 version, uint64 payload size, uint32 CRC-32.
constexpr size_t kVersionOffset = 8;
constexpr size_t kHeaderSize = 8 + 4 + 8 + 4;

ConfigSpec csv_small_config() {
  const std::string dir = kScenarios + "/lpsim_csv_small";
  ConfigSpec c;
  c.lpsim_nodes_csv = dir + "/nodes.csv";
  c.lpsim_edges_csv = dir + "/edges.csv";
  c.lpsim_od_csv = dir + "/od.csv";
  return c;
}

ConfigSpec sumocfg(const std::string& name) {
  return read_sumocfg(kScenarios + "/" + name + "/" + name + ".sumocfg");
}

#define EXPECT_COLUMN(a, b, field) EXPECT_TRUE((a).field == (b).field) << #field " differs"

void expect_same_network(const Network& a, const Network& b) {
  EXPECT_COLUMN(a, b, edge_id);
  EXPECT_COLUMN(a, b, edge_first_lane);
  EXPECT_COLUMN(a, b, edge_num_lanes);
  EXPECT_COLUMN(a, b, edge_from_junction);
  EXPECT_COLUMN(a, b, edge_to_junction);
  EXPECT_COLUMN(a, b, edge_is_internal);
  EXPECT_COLUMN(a, b, edge_length);
  EXPECT_COLUMN(a, b, edge_speed);
  EXPECT_COLUMN(a, b, edge_priority);
  EXPECT_COLUMN(a, b, lane_id);
  EXPECT_COLUMN(a, b, lane_edge);
  EXPECT_COLUMN(a, b, lane_index);
  EXPECT_COLUMN(a, b, lane_length);
  EXPECT_COLUMN(a, b, lane_speed);
  EXPECT_COLUMN(a, b, lane_cell_begin);
  EXPECT_COLUMN(a, b, lane_conn_begin);
  EXPECT_COLUMN(a, b, lane_shape_begin);
  EXPECT_COLUMN(a, b, shape_x);
  EXPECT_COLUMN(a, b, shape_y);
  EXPECT_COLUMN(a, b, conn_from_lane);
  EXPECT_COLUMN(a, b, conn_to_lane);
  EXPECT_COLUMN(a, b, conn_via_lane);
  EXPECT_COLUMN(a, b, conn_to_edge);
  EXPECT_COLUMN(a, b, conn_signal);
  EXPECT_COLUMN(a, b, conn_link_index);
  EXPECT_COLUMN(a, b, conn_state);
  EXPECT_COLUMN(a, b, conn_dir);
  EXPECT_COLUMN(a, b, conn_junction);
  EXPECT_COLUMN(a, b, conn_foe_begin);
  EXPECT_COLUMN(a, b, conn_foe);
  EXPECT_COLUMN(a, b, conn_keep_clear);
  EXPECT_COLUMN(a, b, junction_id);
  EXPECT_COLUMN(a, b, junction_type);
  EXPECT_COLUMN(a, b, junction_x);
  EXPECT_COLUMN(a, b, junction_y);
  EXPECT_COLUMN(a, b, signal_id);
  EXPECT_COLUMN(a, b, signal_program);
  EXPECT_COLUMN(a, b, signal_actuated);
  EXPECT_COLUMN(a, b, signal_offset);
  EXPECT_COLUMN(a, b, signal_phase_begin);
  EXPECT_COLUMN(a, b, phase_duration);
  EXPECT_COLUMN(a, b, phase_min_dur);
  EXPECT_COLUMN(a, b, phase_max_dur);
  EXPECT_COLUMN(a, b, phase_state_begin);
  EXPECT_COLUMN(a, b, phase_state);
  EXPECT_COLUMN(a, b, signal_max_gap);
  EXPECT_COLUMN(a, b, signal_detector_gap);
  EXPECT_COLUMN(a, b, signal_passing_time);
  EXPECT_COLUMN(a, b, signal_det_begin);
  EXPECT_COLUMN(a, b, det_lane);
  EXPECT_COLUMN(a, b, det_pos);
  EXPECT_COLUMN(a, b, phase_det_begin);
  EXPECT_COLUMN(a, b, phase_det);
  EXPECT_COLUMN(a, b, roundabout_edges);
  EXPECT_COLUMN(a, b, skipped_non_car_lanes);
  EXPECT_COLUMN(a, b, skipped_connections);
  EXPECT_EQ(a.net_offset.x, b.net_offset.x);
  EXPECT_EQ(a.net_offset.y, b.net_offset.y);
  EXPECT_COLUMN(a, b, edge_index);
  EXPECT_COLUMN(a, b, lane_index_by_id);
  EXPECT_COLUMN(a, b, junction_index);
  EXPECT_COLUMN(a, b, signal_index);
  EXPECT_COLUMN(a, b, edge_succ_begin);
  EXPECT_COLUMN(a, b, edge_succ);
}

void expect_same_demand(const Demand& a, const Demand& b) {
  EXPECT_COLUMN(a, b, types.id);
  EXPECT_COLUMN(a, b, types.length);
  EXPECT_COLUMN(a, b, types.min_gap);
  EXPECT_COLUMN(a, b, types.accel);
  EXPECT_COLUMN(a, b, types.decel);
  EXPECT_COLUMN(a, b, types.emergency_decel);
  EXPECT_COLUMN(a, b, types.max_speed);
  EXPECT_COLUMN(a, b, types.desired_max_speed);
  EXPECT_COLUMN(a, b, types.speed_factor);
  EXPECT_COLUMN(a, b, types.speed_dev);
  EXPECT_COLUMN(a, b, types.tau);
  EXPECT_COLUMN(a, b, types.sigma);
  EXPECT_COLUMN(a, b, types.delta);
  EXPECT_COLUMN(a, b, types.vclass);
  EXPECT_COLUMN(a, b, types.car_follow_model);
  EXPECT_COLUMN(a, b, types.model);
  EXPECT_COLUMN(a, b, types.index);
  EXPECT_COLUMN(a, b, vehicle_id);
  EXPECT_COLUMN(a, b, vehicle_type);
  EXPECT_COLUMN(a, b, depart);
  EXPECT_COLUMN(a, b, route_begin);
  EXPECT_COLUMN(a, b, route_length);
  EXPECT_COLUMN(a, b, speed_factor);
  EXPECT_COLUMN(a, b, source);
  EXPECT_COLUMN(a, b, depart_lane_kind);
  EXPECT_COLUMN(a, b, depart_lane);
  EXPECT_COLUMN(a, b, depart_pos_kind);
  EXPECT_COLUMN(a, b, depart_pos);
  EXPECT_COLUMN(a, b, depart_speed_kind);
  EXPECT_COLUMN(a, b, depart_speed);
  EXPECT_COLUMN(a, b, arrival_pos_kind);
  EXPECT_COLUMN(a, b, arrival_pos);
  EXPECT_COLUMN(a, b, route_edges);
  ASSERT_EQ(a.unroutable.size(), b.unroutable.size());
  for (size_t i = 0; i < a.unroutable.size(); ++i) {
    EXPECT_EQ(a.unroutable[i].id, b.unroutable[i].id);
    EXPECT_EQ(a.unroutable[i].reason, b.unroutable[i].reason);
    EXPECT_EQ(a.unroutable[i].loc.str(), b.unroutable[i].loc.str());
  }
  EXPECT_COLUMN(a, b, unsupported);
}

void expect_same_mean_data(const std::vector<MeanDataSpec>& a, const std::vector<MeanDataSpec>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].file, b[i].file);
    EXPECT_EQ(a[i].lane_level, b[i].lane_level);
    EXPECT_EQ(a[i].period, b[i].period);
    EXPECT_EQ(a[i].begin, b[i].begin);
    EXPECT_EQ(a[i].end, b[i].end);
    EXPECT_EQ(a[i].exclude_empty, b[i].exclude_empty);
    EXPECT_EQ(a[i].with_internal, b[i].with_internal);
    EXPECT_EQ(a[i].loc.str(), b[i].loc.str());
  }
}

class SnapshotTest : public ::testing::Test {
 protected:
  void round_trip(const ConfigSpec& config) {
    const Scenario loaded = load_scenario(config);
    ASSERT_GT(loaded.network.num_lanes(), 0u);
    ASSERT_GT(loaded.demand.size(), 0u);
    const std::string path = (tmp_.path() / "s.lpsim").string();
    write_snapshot(loaded, path);
    EXPECT_TRUE(is_snapshot(path));
    const Scenario back = read_snapshot(path);
    expect_same_network(loaded.network, back.network);
    expect_same_demand(loaded.demand, back.demand);
    expect_same_mean_data(loaded.mean_data, back.mean_data);
  }

  // A valid snapshot of grid_tls, as bytes.
  std::string grid_snapshot() {
    const std::string path = (tmp_.path() / "grid.lpsim").string();
    write_snapshot(load_scenario(sumocfg("grid_tls")), path);
    return slurp(path);
  }

  std::string write(const std::string& name, const std::string& bytes) const {
    return tmp_.write(name, bytes);
  }

  // Runs the lpsim binary; returns its stdout, and its exit code in `code`.
  std::string lpsim(const std::string& args, int& code) {
    const std::string out = (tmp_.path() / "stdout.txt").string();
    const int status =
        std::system((std::string(LPSIM_BINARY) + " " + args + " > '" + out + "' 2> /dev/null").c_str());
    code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return slurp(out);
  }

  test::TempDir tmp_{"lpsim_snapshot"};
};

TEST_F(SnapshotTest, GridTlsRoundTripKeepsEveryColumn) { round_trip(sumocfg("grid_tls")); }
TEST_F(SnapshotTest, RandomNetRoundTripKeepsEveryColumn) { round_trip(sumocfg("random_net")); }
TEST_F(SnapshotTest, FlowsRoundTripKeepsEveryColumn) { round_trip(sumocfg("flows")); }
TEST_F(SnapshotTest, LpsimCsvRoundTripKeepsEveryColumn) { round_trip(csv_small_config()); }

// Skipped vehicles and unsupported-element counts travel too (they are what `lpsim info` reports).
TEST_F(SnapshotTest, RoundTripKeepsSkippedVehiclesAndUnsupportedElements) {
  const std::string routes =
      write("r.rou.xml",
            "<routes>\n"
            "<vehicle id=\"good\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
            "<vehicle id=\"broken\" depart=\"1\"><route edges=\"A0A1 C3C4\"/></vehicle>\n"
            "<person id=\"p\" depart=\"0\"><walk edges=\"A0A1\"/></person>\n"
            "</routes>\n");
  ConfigSpec config;
  config.net_file = kScenarios + "/grid_tls/grid_tls.net.xml";
  config.route_files = {routes};
  config.ignore_route_errors = true;
  const Scenario loaded = load_scenario(config);
  ASSERT_EQ(loaded.demand.unroutable.size(), 1u);
  ASSERT_FALSE(loaded.demand.unsupported.empty());
  const std::string path = (tmp_.path() / "s.lpsim").string();
  write_snapshot(loaded, path);
  const Scenario back = read_snapshot(path);
  expect_same_demand(loaded.demand, back.demand);
  EXPECT_EQ(back.demand.unroutable[0].id, "broken");
}

// `lpsim info` prints the same report for the XML and for its snapshot, but for the load-time line.
TEST_F(SnapshotTest, InfoOfSnapshotEqualsInfoOfXml) {
  for (const std::string name : {"grid_tls", "random_net", "flows"}) {
    const std::string cfg = kScenarios + "/" + name + "/" + name + ".sumocfg";
    const std::string snap = (tmp_.path() / (name + ".lpsim")).string();
    int code = -1;
    lpsim("convert -c '" + cfg + "' -o '" + snap + "'", code);
    ASSERT_EQ(code, 0) << name;
    std::string from_xml = lpsim("info -c '" + cfg + "'", code);
    ASSERT_EQ(code, 0) << name;
    std::string from_snapshot = lpsim("info '" + snap + "'", code);
    ASSERT_EQ(code, 0) << name;
    auto drop_load_time = [](std::string& text) {
      const auto at = text.find("load time: ");
      ASSERT_NE(at, std::string::npos);
      text.erase(at, text.find('\n', at) + 1 - at);
    };
    drop_load_time(from_xml);
    drop_load_time(from_snapshot);
    EXPECT_GT(from_xml.size(), 200u);
    EXPECT_EQ(from_xml, from_snapshot) << name;
  }
}

TEST_F(SnapshotTest, OneCorruptedByteAnywhereInThePayloadIsRefused) {
  const std::string good = grid_snapshot();
  ASSERT_GT(good.size(), kHeaderSize + 100);
  // First, middle and last payload byte: each flip must break the checksum.
  for (size_t at : {kHeaderSize, kHeaderSize + (good.size() - kHeaderSize) / 2, good.size() - 1}) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x01);
    const std::string path = write("bad.lpsim", bad);
    try {
      read_snapshot(path);
      ADD_FAILURE() << "corrupted byte at " << at << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, path);
    }
  }
}

TEST_F(SnapshotTest, CorruptedCrcFieldIsRefused) {
  std::string bad = grid_snapshot();
  bad[kHeaderSize - 1] = static_cast<char>(bad[kHeaderSize - 1] ^ 0x80);
  EXPECT_THROW(read_snapshot(write("bad.lpsim", bad)), InputError);
}

TEST_F(SnapshotTest, OtherVersionIsRefused) {
  for (uint32_t version : {kSnapshotVersion + 1, kSnapshotVersion - 1, 0xffffffffu}) {
    std::string other = grid_snapshot();
    std::memcpy(other.data() + kVersionOffset, &version, sizeof version);
    const std::string path = write("other.lpsim", other);
    EXPECT_TRUE(is_snapshot(path));
    try {
      read_snapshot(path);
      ADD_FAILURE() << "version " << version << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("version " + std::to_string(version)), std::string::npos)
          << e.what();
    }
  }
}

TEST_F(SnapshotTest, TruncatedOrExtendedSnapshotIsRefused) {
  const std::string good = grid_snapshot();
  for (size_t keep : {size_t{0}, size_t{5}, kHeaderSize, good.size() / 2, good.size() - 1}) {
    const std::string path = write("cut.lpsim", good.substr(0, keep));
    EXPECT_THROW(read_snapshot(path), InputError) << "kept " << keep << " bytes";
  }
  EXPECT_THROW(read_snapshot(write("long.lpsim", good + "x")), InputError);
}

TEST_F(SnapshotTest, NotASnapshot) {
  const std::string xml = kScenarios + "/grid_tls/grid_tls.net.xml";
  EXPECT_FALSE(is_snapshot(xml));
  EXPECT_THROW(read_snapshot(xml), InputError);
  EXPECT_THROW(read_snapshot((tmp_.path() / "missing.lpsim").string()), InputError);
}

}  // namespace
}  // namespace lpsim

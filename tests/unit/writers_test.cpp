// Output writers: exact values and formatting against a hand-built network, schema validity against
// SUMO's XSDs (when xmllint and the XSDs are installed), gzip output equal to plain output.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "converters/fcd_writer.hpp"
#include "converters/lane_geometry.hpp"
#include "converters/mean_data_writer.hpp"
#include "converters/output_file.hpp"
#include "converters/summary_writer.hpp"
#include "converters/tripinfo_writer.hpp"
#include "core/error.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const char* const kXsdDir = test::kSumoXsdDir;

// Edges: E1 (2 lanes: E1_0 runs west, E1_1 runs south), :J_0 (internal), E2 (one L-shaped lane whose
// shape is twice as long as the lane), W (no car lanes).
Network tiny_network() {
  Network net;
  net.edge_id = {"E1", ":J_0", "E2", "W"};
  net.edge_first_lane = {0, 2, 3, 4};
  net.edge_num_lanes = {2, 1, 1, 0};
  net.edge_is_internal = {0, 1, 0, 0};
  net.edge_length = {100, 8, 35, 50};
  net.edge_speed = {12.5f, 10, 20, 5};
  net.lane_id = {"E1_0", "E1_1", ":J_0_0", "E2_0"};
  net.lane_edge = {0, 0, 1, 2};
  net.lane_length = {100, 10, 8, 35};
  net.lane_speed = {12.5f, 8, 10, 20};
  net.lane_shape_begin = {0, 2, 4, 6, 9};
  net.shape_x = {100, 0, /*E1_1*/ 0, 0, /*:J_0_0*/ 0, 8, /*E2_0*/ 0, 0, 40};
  net.shape_y = {0, 0, /*E1_1*/ -3, -13, /*:J_0_0*/ 5, 5, /*E2_0*/ 0, 30, 30};
  for (uint32_t e = 0; e < net.num_edges(); ++e) net.edge_index[net.edge_id[e]] = e;
  for (uint32_t l = 0; l < net.num_lanes(); ++l) net.lane_index_by_id[net.lane_id[l]] = l;
  return net;
}

Demand tiny_demand() {
  Demand demand;
  demand.types.id = {"car"};
  demand.types.length = {5};
  demand.types.index["car"] = 0;
  demand.vehicle_id = {"v0", "v&1"};
  demand.vehicle_type = {0, 0};
  demand.depart = {0, 2};
  return demand;
}

class WritersTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (tmp_.path() / name).string(); }

  // Reads a plain or gzip file (gzread passes plain files through unchanged).
  static std::string read_all(const std::string& file) {
    gzFile gz = gzopen(file.c_str(), "rb");
    EXPECT_NE(gz, nullptr) << file;
    if (gz == nullptr) return {};
    std::string content;
    char chunk[4096];
    int n;
    while ((n = gzread(gz, chunk, sizeof chunk)) > 0) content.append(chunk, static_cast<size_t>(n));
    gzclose(gz);
    return content;
  }

  static bool is_gzip(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char magic[2] = {0, 0};
    in.read(reinterpret_cast<char*>(magic), 2);
    return magic[0] == 0x1f && magic[1] == 0x8b;
  }

  // The body lines between the root's opening and closing tags.
  static std::vector<std::string> body_lines(const std::string& content, const std::string& root) {
    std::vector<std::string> lines;
    std::istringstream in(content);
    std::string line;
    bool inside = false;
    while (std::getline(in, line)) {
      if (line.rfind("<" + root + " ", 0) == 0) {
        inside = true;
      } else if (line == "</" + root + ">") {
        inside = false;
      } else if (inside) {
        lines.push_back(line);
      }
    }
    return lines;
  }

  // Validates with xmllint against SUMO's XSD; skips the calling test when the tool or XSD is missing.
  void expect_schema_valid(const std::string& file, const std::string& xsd) {
    const std::string schema = std::string(kXsdDir) + "/" + xsd;
    if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
    if (!fs::exists(schema)) GTEST_SKIP() << schema << " not installed";
    const std::string log = path("xmllint.log");
    const std::string cmd = "xmllint --noout --schema " + test::usable_sumo_schema(schema, tmp_) + " " +
                            file + " > " + log + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << file << " fails " << xsd << ":\n" << read_all(log);
  }

  test::TempDir tmp_{"lpsim_writers"};
  Network net_ = tiny_network();
  Demand demand_ = tiny_demand();
};

// --- lane geometry -----------------------------------------------------------------------------

TEST(LaneGeometryTest, NavigationalAngleIsClockwiseFromNorth) {
  EXPECT_DOUBLE_EQ(navigational_degrees(0, 1), 0);
  EXPECT_DOUBLE_EQ(navigational_degrees(1, 0), 90);
  EXPECT_DOUBLE_EQ(navigational_degrees(0, -1), 180);
  EXPECT_DOUBLE_EQ(navigational_degrees(-1, 0), 270);
  EXPECT_DOUBLE_EQ(navigational_degrees(1, 1), 45);
  EXPECT_DOUBLE_EQ(navigational_degrees(-1, 1), 315);
}

TEST(LaneGeometryTest, LShapedLaneScalesPositionToShapeLength) {
  const Network net = tiny_network();
  const LaneGeometry geometry(net);
  const uint32_t e2 = 3;  // shape 70 m long, lane 35 m long: lane pos p lies at shape offset 2p
  EXPECT_DOUBLE_EQ(geometry.shape_length(e2), 70);

  LanePoint p = geometry.at(e2, 10);  // offset 20 on the northbound leg
  EXPECT_DOUBLE_EQ(p.x, 0);
  EXPECT_DOUBLE_EQ(p.y, 20);
  EXPECT_DOUBLE_EQ(p.angle, 0);

  p = geometry.at(e2, 15);  // the corner: heading of the incoming leg
  EXPECT_DOUBLE_EQ(p.x, 0);
  EXPECT_DOUBLE_EQ(p.y, 30);
  EXPECT_DOUBLE_EQ(p.angle, 0);

  p = geometry.at(e2, 25);  // offset 50: 20 m along the eastbound leg
  EXPECT_DOUBLE_EQ(p.x, 20);
  EXPECT_DOUBLE_EQ(p.y, 30);
  EXPECT_DOUBLE_EQ(p.angle, 90);

  p = geometry.at(e2, 40);  // past the end: clamped to the last point
  EXPECT_DOUBLE_EQ(p.x, 40);
  EXPECT_DOUBLE_EQ(p.y, 30);

  p = geometry.at(e2, 0);
  EXPECT_DOUBLE_EQ(p.x, 0);
  EXPECT_DOUBLE_EQ(p.y, 0);
  EXPECT_DOUBLE_EQ(p.angle, 0);

  p = geometry.at(0, 25);  // E1_0 runs west from x=100
  EXPECT_DOUBLE_EQ(p.x, 75);
  EXPECT_DOUBLE_EQ(p.angle, 270);
}

TEST(LaneGeometryTest, VehicleHeadingIsChordFromBackToFront) {
  const Network net = tiny_network();
  const LaneGeometry geometry(net);
  // E2_0 at pos 17 (shape offset 34: (4, 30)), back at pos 12 (offset 24: (0, 24)).
  EXPECT_NEAR(geometry.vehicle_heading(3, 17, 5), 90 - std::atan2(6.0, 4.0) * 180 / std::numbers::pi, 1e-9);
  // Fully on the northbound leg: the chord is the leg's heading.
  EXPECT_DOUBLE_EQ(geometry.vehicle_heading(3, 10, 5), 0);
  // Back before the lane start and no known previous lane: clamped to the start (0, 0) -> front (0, 2).
  EXPECT_DOUBLE_EQ(geometry.vehicle_heading(3, 1, 5), 0);
}

TEST(LaneGeometryTest, VehicleBackContinuesOnUniquePreviousLane) {
  Network net = tiny_network();
  // E1_0 -> E2_0 through :J_0_0; E1_1 -> E2_0 directly, which makes E2_0's predecessor ambiguous.
  net.conn_from_lane = {0, 1};
  net.conn_to_lane = {3, 3};
  net.conn_via_lane = {2, kNone};
  const LaneGeometry geometry(net);
  EXPECT_EQ(geometry.unique_predecessor(2), 0);
  EXPECT_EQ(geometry.unique_predecessor(3), kNone);
  EXPECT_EQ(geometry.unique_predecessor(0), kNone);
  // On :J_0_0 at pos 2 (front (2, 5)) a 5 m vehicle's back is 3 m before the end of E1_0: (3, 0).
  EXPECT_NEAR(geometry.vehicle_heading(2, 2, 5), 360 + 90 - std::atan2(5.0, -1.0) * 180 / std::numbers::pi,
              1e-9);
}

TEST(LaneGeometryTest, DuplicateShapePointsDoNotBreakHeading) {
  Network net;
  net.lane_id = {"L_0"};
  net.lane_length = {10};
  net.lane_shape_begin = {0, 3};
  net.shape_x = {0, 0, 10};
  net.shape_y = {0, 0, 0};
  const LaneGeometry geometry(net);
  const LanePoint p = geometry.at(0, 0);
  EXPECT_DOUBLE_EQ(p.x, 0);
  EXPECT_DOUBLE_EQ(p.angle, 90);
}

// --- output file -------------------------------------------------------------------------------

TEST_F(WritersTest, OutputFileFormatsNumbersAndEscapes) {
  const std::string file = path("numbers.txt");
  {
    OutputFile out(file);
    out.fixed(1.005);  // binary value just below 1.005
    out.put(' ');
    out.fixed(-1.6);
    out.put(' ');
    out.fixed(2.0 / 3.0, 4);
    out.put(' ');
    out.integer(-42);
    out.put(' ');
    out.unsigned_integer(18446744073709551615ull);
    out.attr("id", "a<b>&\"c'");
    out.close();
  }
  EXPECT_EQ(read_all(file), "1.00 -1.60 0.6667 -42 18446744073709551615 id=\"a&lt;b&gt;&amp;&quot;c&apos;\"");
}

TEST_F(WritersTest, OutputFileLargerThanItsBufferIsComplete) {
  const std::string plain = path("big.txt"), gz = path("big.txt.gz");
  std::string expected;
  for (int i = 0; i < 300000; ++i) expected += std::to_string(i) + ",";
  for (const std::string& file : {plain, gz}) {
    OutputFile out(file);
    for (int i = 0; i < 300000; ++i) {
      out.integer(i);
      out.put(',');
    }
    out.close();
  }
  EXPECT_FALSE(is_gzip(plain));
  EXPECT_TRUE(is_gzip(gz));
  EXPECT_EQ(read_all(plain), expected);
  EXPECT_EQ(read_all(gz), expected);
}

TEST_F(WritersTest, UncreatableOutputIsInputErrorNamingFile) {
  const std::string file = path("no/such/dir/out.xml");
  try {
    OutputFile out(file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
  EXPECT_THROW(SummaryWriter(path("missing/summary.xml.gz")), InputError);
}

// --- FCD ---------------------------------------------------------------------------------------

FcdFrame two_vehicle_frame() {
  FcdFrame frame;
  frame.time = 3;
  frame.vehicle = {0, 1};
  frame.lane = {3, 1};
  frame.pos = {25, 4};
  frame.speed = {12.5f, 0};
  return frame;
}

TEST_F(WritersTest, FcdWritesVehiclesAndEmptyTimesteps) {
  const std::string file = path("fcd.xml");
  {
    FcdWriter writer(file, net_, demand_);
    writer.write(two_vehicle_frame());
    FcdFrame empty;
    empty.time = 4;
    writer.write(empty);
    writer.close();
  }
  const std::string content = read_all(file);
  EXPECT_NE(content.find("<fcd-export xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
                         "xsi:noNamespaceSchemaLocation=\"http://sumo.dlr.de/xsd/fcd_file.xsd\">"),
            std::string::npos);
  const std::vector<std::string> expected = {
      "    <timestep time=\"3.00\">",
      "        <vehicle id=\"v0\" x=\"20.00\" y=\"30.00\" angle=\"90.00\" type=\"car\" speed=\"12.50\" "
      "pos=\"25.00\" lane=\"E2_0\" slope=\"0.00\"/>",
      "        <vehicle id=\"v&amp;1\" x=\"0.00\" y=\"-7.00\" angle=\"180.00\" type=\"car\" speed=\"0.00\" "
      "pos=\"4.00\" lane=\"E1_1\" slope=\"0.00\"/>",
      "    </timestep>",
      "    <timestep time=\"4.00\"/>",
  };
  EXPECT_EQ(body_lines(content, "fcd-export"), expected);
  EXPECT_EQ(content.substr(content.size() - 14), "</fcd-export>\n");
  expect_schema_valid(file, "fcd_file.xsd");
}

TEST_F(WritersTest, FcdGzipContentEqualsPlain) {
  const std::string plain = path("fcd.xml"), gz = path("fcd.xml.gz");
  for (const std::string& file : {plain, gz}) {
    FcdWriter writer(file, net_, demand_);
    writer.write(two_vehicle_frame());
    // no explicit close(): the destructor writes the closing tag
  }
  EXPECT_TRUE(is_gzip(gz));
  EXPECT_EQ(read_all(gz), read_all(plain));
  expect_schema_valid(gz, "fcd_file.xsd");
}

TEST_F(WritersTest, FcdRejectsInconsistentFrame) {
  FcdWriter writer(path("bad.xml"), net_, demand_);
  FcdFrame frame = two_vehicle_frame();
  frame.speed.pop_back();
  EXPECT_THROW(writer.write(frame), std::logic_error);
}

// --- edgeData / laneData -------------------------------------------------------------------------

// E1_0: 30 vehicle-s, 300 m; E1_1: 10 vehicle-s, 100 m; :J_0_0 sampled; E2_0 and W empty.
LaneCounters known_counters() {
  LaneCounters c;
  c.resize(4);
  c.sampled_steps = {30, 10, 2, 0};
  c.travelled_mm = {300000, 100000, 16000, 0};
  c.waiting_steps = {2, 0, 0, 0};
  c.time_loss_ms = {4500, 500, 0, 0};
  c.occupied_mm_steps = {150000, 50000, 10000, 0};
  c.departed = {1, 0, 0, 0};
  c.arrived = {0, 1, 0, 0};
  c.entered = {2, 1, 1, 0};
  c.left = {2, 0, 1, 0};
  return c;
}

MeanDataSpec spec_for(const std::string& file, bool lane_level) {
  MeanDataSpec spec;
  spec.id = "dump";
  spec.file = file;
  spec.lane_level = lane_level;
  return spec;
}

TEST(MeanDataValuesTest, EdgeMeasuresFollowTheirDefinitions) {
  const LaneCounters c = known_counters();
  const MeanDataTotals t = sum_lane_counters(c, 0, 2, 1.0);
  EXPECT_DOUBLE_EQ(t.sampled_seconds, 40);
  EXPECT_DOUBLE_EQ(t.travelled_m, 400);
  EXPECT_DOUBLE_EQ(t.waiting_seconds, 2);
  EXPECT_DOUBLE_EQ(t.time_loss_seconds, 5);
  EXPECT_DOUBLE_EQ(t.occupied_m_seconds, 200);
  EXPECT_EQ(t.entered, 3);
  const MeanDataMeasures m = derive_mean_data(t, 100, 2, 12.5, 60, 5);
  EXPECT_DOUBLE_EQ(m.speed, 10);            // 400 m / 40 s
  EXPECT_DOUBLE_EQ(m.speed_relative, 0.8);  // 10 / 12.5
  EXPECT_TRUE(m.has_traveltime);
  EXPECT_DOUBLE_EQ(m.traveltime, 10);                   // 100 m / 10 m/s
  EXPECT_DOUBLE_EQ(m.overlap_traveltime, 10.5);         // (100 + 200/40) m / 10 m/s
  EXPECT_DOUBLE_EQ(m.density, 40.0 / 60 * 1000 / 100);  // 6.67 veh/km
  EXPECT_DOUBLE_EQ(m.lane_density, m.density / 2);
  EXPECT_DOUBLE_EQ(m.occupancy, 200.0 / 60 / 100 / 2 * 100);  // 1.67 %
}

TEST(MeanDataValuesTest, StandingTrafficHasNoTraveltimeAndCappedDensity) {
  MeanDataTotals t;
  t.sampled_seconds = 600;  // 10 vehicles standing for 60 s on 10 m
  const MeanDataMeasures m = derive_mean_data(t, 10, 1, 10, 60, 5);
  EXPECT_FALSE(m.has_traveltime);
  EXPECT_DOUBLE_EQ(m.overlap_traveltime, 100000);
  EXPECT_DOUBLE_EQ(m.speed, 0);
  EXPECT_DOUBLE_EQ(m.density, 200);  // 1000 veh/km would exceed one 5 m vehicle per 5 m
}

TEST_F(WritersTest, EdgeDataWritesKnownValuesAndSkipsInternal) {
  const std::string file = path("edgedata.xml");
  const LaneCounters counters = known_counters();
  {
    MeanDataWriter writer(spec_for(file, false), net_, demand_);
    writer.write({0, 60, 1.0, &counters});
    writer.close();
  }
  const std::vector<std::string> expected = {
      "    <interval begin=\"0.00\" end=\"60.00\" id=\"dump\">",
      "        <edge id=\"E1\" sampledSeconds=\"40.00\" traveltime=\"10.00\" overlapTraveltime=\"10.50\" "
      "density=\"6.67\" laneDensity=\"3.33\" occupancy=\"1.67\" waitingTime=\"2.00\" timeLoss=\"5.00\" "
      "speed=\"10.00\" speedRelative=\"0.80\" departed=\"1\" arrived=\"1\" entered=\"3\" left=\"2\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>",
      "        <edge id=\"E2\" sampledSeconds=\"0.00\" departed=\"0\" arrived=\"0\" entered=\"0\" left=\"0\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>",
      "        <edge id=\"W\" sampledSeconds=\"0.00\" departed=\"0\" arrived=\"0\" entered=\"0\" left=\"0\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>",
      "    </interval>",
  };
  EXPECT_EQ(body_lines(read_all(file), "meandata"), expected);
  expect_schema_valid(file, "meandata_file.xsd");
}

TEST_F(WritersTest, EdgeDataExcludeEmptyAndWithInternal) {
  const std::string file = path("edgedata.xml.gz");
  const LaneCounters counters = known_counters();
  MeanDataSpec spec = spec_for(file, false);
  spec.exclude_empty = true;
  spec.with_internal = true;
  {
    MeanDataWriter writer(spec, net_, demand_);
    writer.write({0, 60, 1.0, &counters});
    writer.write({60, 120, 1.0, &counters});
  }
  const std::vector<std::string> lines = body_lines(read_all(file), "meandata");
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0], "    <interval begin=\"0.00\" end=\"60.00\" id=\"dump\">");
  EXPECT_EQ(lines[1].rfind("        <edge id=\"E1\" ", 0), 0u);
  // :J_0: 2 s, 16 m on an 8 m lane at 10 m/s: speed 8, traveltime 1, overlap (8 + 10/2) / 8
  EXPECT_EQ(
      lines[2],
      "        <edge id=\":J_0\" sampledSeconds=\"2.00\" traveltime=\"1.00\" overlapTraveltime=\"1.62\" "
      "density=\"4.17\" laneDensity=\"4.17\" occupancy=\"2.08\" waitingTime=\"0.00\" timeLoss=\"0.00\" "
      "speed=\"8.00\" speedRelative=\"0.80\" departed=\"0\" arrived=\"0\" entered=\"1\" left=\"1\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>");
  EXPECT_EQ(lines[3], "    </interval>");
  EXPECT_EQ(lines[4], "    <interval begin=\"60.00\" end=\"120.00\" id=\"dump\">");
  expect_schema_valid(file, "meandata_file.xsd");
}

TEST_F(WritersTest, LaneDataNestsLanesInEdges) {
  const std::string file = path("lanedata.xml");
  const LaneCounters counters = known_counters();
  MeanDataSpec spec = spec_for(file, true);
  spec.exclude_empty = true;
  {
    MeanDataWriter writer(spec, net_, demand_);
    writer.write({0, 60, 1.0, &counters});
  }
  const std::vector<std::string> expected = {
      "    <interval begin=\"0.00\" end=\"60.00\" id=\"dump\">",
      "        <edge id=\"E1\">",
      "            <lane id=\"E1_0\" sampledSeconds=\"30.00\" traveltime=\"10.00\" "
      "overlapTraveltime=\"10.50\" "
      "density=\"5.00\" laneDensity=\"5.00\" occupancy=\"2.50\" waitingTime=\"2.00\" timeLoss=\"4.50\" "
      "speed=\"10.00\" speedRelative=\"0.80\" departed=\"1\" arrived=\"0\" entered=\"2\" left=\"2\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>",
      "            <lane id=\"E1_1\" sampledSeconds=\"10.00\" traveltime=\"1.00\" overlapTraveltime=\"1.50\" "
      "density=\"16.67\" laneDensity=\"16.67\" occupancy=\"8.33\" waitingTime=\"0.00\" timeLoss=\"0.50\" "
      "speed=\"10.00\" speedRelative=\"1.25\" departed=\"0\" arrived=\"1\" entered=\"1\" left=\"0\" "
      "laneChangedFrom=\"0\" laneChangedTo=\"0\"/>",
      "        </edge>",
      "    </interval>",
  };
  EXPECT_EQ(body_lines(read_all(file), "meandata"), expected);
  expect_schema_valid(file, "meandata_file.xsd");
}

TEST_F(WritersTest, MeanDataStepLengthScalesSeconds) {
  const std::string file = path("edgedata_dt.xml");
  LaneCounters counters;
  counters.resize(4);
  counters.sampled_steps[3] = 40;  // 40 steps of 0.25 s on E2_0 = 10 vehicle-s
  counters.travelled_mm[3] = 100000;
  counters.waiting_steps[3] = 8;
  MeanDataSpec spec = spec_for(file, false);
  spec.exclude_empty = true;
  {
    MeanDataWriter writer(spec, net_, demand_);
    writer.write({0, 10, 0.25, &counters});
  }
  const std::vector<std::string> lines = body_lines(read_all(file), "meandata");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[1].find("id=\"E2\" sampledSeconds=\"10.00\" traveltime=\"3.50\""), std::string::npos)
      << lines[1];
  EXPECT_NE(lines[1].find("waitingTime=\"2.00\""), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("speed=\"10.00\" speedRelative=\"0.50\""), std::string::npos) << lines[1];
}

TEST_F(WritersTest, MeanDataRejectsCountersOfAnotherNetwork) {
  MeanDataWriter writer(spec_for(path("x.xml"), false), net_, demand_);
  LaneCounters counters;
  counters.resize(2);
  EXPECT_THROW(writer.write({0, 60, 1.0, &counters}), std::logic_error);
  EXPECT_THROW(writer.write({0, 60, 1.0, nullptr}), std::logic_error);
}

// --- tripinfo ------------------------------------------------------------------------------------

TEST_F(WritersTest, TripinfoWritesSumoAttributeOrder) {
  const std::string plain = path("tripinfo.xml"), gz = path("tripinfo.xml.gz");
  TripRecord trip;
  trip.vehicle = 1;
  trip.depart = 5;
  trip.depart_delay = 3;
  trip.arrival = 24;
  trip.depart_lane = 0;
  trip.arrival_lane = 3;
  trip.depart_pos = 5.1f;
  trip.depart_speed = 0;
  trip.arrival_pos = 35;
  trip.arrival_speed = 13.777f;
  trip.route_length = 184.3;
  trip.waiting_time = 2;
  trip.waiting_count = 1;
  trip.time_loss = 4.684;
  trip.speed_factor = 1.01f;
  TripRecord removed = trip;
  removed.vehicle = 0;
  removed.teleported = true;
  for (const std::string& file : {plain, gz}) {
    TripinfoWriter writer(file, net_, demand_, {"tripinfo", "fcd"});
    writer.write(trip);
    writer.write(removed);
  }
  const std::vector<std::string> expected = {
      "    <tripinfo id=\"v&amp;1\" depart=\"5.00\" departLane=\"E1_0\" departPos=\"5.10\" "
      "departSpeed=\"0.00\" "
      "departDelay=\"3.00\" arrival=\"24.00\" arrivalLane=\"E2_0\" arrivalPos=\"35.00\" "
      "arrivalSpeed=\"13.78\" "
      "duration=\"19.00\" routeLength=\"184.30\" waitingTime=\"2.00\" waitingCount=\"1\" stopTime=\"0.00\" "
      "timeLoss=\"4.68\" rerouteNo=\"0\" devices=\"tripinfo_v&amp;1 fcd_v&amp;1\" vType=\"car\" "
      "speedFactor=\"1.01\" vaporized=\"\"/>",
      "    <tripinfo id=\"v0\" depart=\"5.00\" departLane=\"E1_0\" departPos=\"5.10\" departSpeed=\"0.00\" "
      "departDelay=\"3.00\" arrival=\"24.00\" arrivalLane=\"E2_0\" arrivalPos=\"35.00\" "
      "arrivalSpeed=\"13.78\" "
      "duration=\"19.00\" routeLength=\"184.30\" waitingTime=\"2.00\" waitingCount=\"1\" stopTime=\"0.00\" "
      "timeLoss=\"4.68\" rerouteNo=\"0\" devices=\"tripinfo_v0 fcd_v0\" vType=\"car\" "
      "speedFactor=\"1.01\" vaporized=\"teleport\"/>",
  };
  EXPECT_EQ(body_lines(read_all(plain), "tripinfos"), expected);
  EXPECT_EQ(read_all(gz), read_all(plain));
  expect_schema_valid(plain, "tripinfo_file.xsd");
}

// --- summary -------------------------------------------------------------------------------------

TEST_F(WritersTest, SummaryWritesMinusOneForUndefinedMeans) {
  const std::string file = path("summary.xml");
  SummaryRow first;  // nothing inserted, running or ended yet
  first.time = 0;
  first.loaded = 2;
  first.waiting = 2;
  first.mean_speed = 0;
  first.duration_ms = 0.4;
  SummaryRow later;
  later.time = 7;
  later.loaded = 3;
  later.inserted = 3;
  later.running = 2;
  later.ended = 1;
  later.arrived = 1;
  later.halting = 1;
  later.mean_waiting_time = 2.0 / 3.0;
  later.mean_travel_time = 19;
  later.mean_speed = 6.826;
  later.mean_speed_relative = 0.4916;
  later.duration_ms = 12.6;
  {
    SummaryWriter writer(file);
    writer.write(first);
    writer.write(later);
  }
  const std::vector<std::string> expected = {
      "    <step time=\"0.00\" loaded=\"2\" inserted=\"0\" running=\"0\" waiting=\"2\" ended=\"0\" "
      "arrived=\"0\" "
      "collisions=\"0\" teleports=\"0\" halting=\"0\" stopped=\"0\" meanWaitingTime=\"-1.00\" "
      "meanTravelTime=\"-1.00\" meanSpeed=\"-1.00\" meanSpeedRelative=\"-1.00\" duration=\"0\"/>",
      "    <step time=\"7.00\" loaded=\"3\" inserted=\"3\" running=\"2\" waiting=\"0\" ended=\"1\" "
      "arrived=\"1\" "
      "collisions=\"0\" teleports=\"0\" halting=\"1\" stopped=\"0\" meanWaitingTime=\"0.67\" "
      "meanTravelTime=\"19.00\" meanSpeed=\"6.83\" meanSpeedRelative=\"0.49\" duration=\"13\"/>",
  };
  EXPECT_EQ(body_lines(read_all(file), "summary"), expected);
  expect_schema_valid(file, "summary_file.xsd");
}

}  // namespace
}  // namespace lpsim

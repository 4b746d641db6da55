// The real `lpsim` binary on bad input: every kind of broken file must end in exit status 2 and exactly one
// line on stderr, "lpsim: error: <file>[:<line>]: <message naming the offending value or id>". Inputs are
// written to a fresh temp dir at test time (a valid network where one is needed: scenarios/grid_tls) and the
// binary runs with that dir as working directory, so messages name files exactly as given.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::string kGridNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";
const std::string kCsvDir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small";

using test::CliResult;
using test::lines_of;
using test::read_file;

class CliBadInputTest : public ::testing::Test {
 protected:
  void write(const std::string& name, const std::string& text) const { tmp_.write(name, text); }

  // A route file whose first element sits on line 3 (line 2 is a comment), so a reported line 3 is the
  // element's own line and not the file's first lines by accident.
  void write_routes(const std::string& name, const std::string& elements) {
    write(name, "<routes>\n<!-- test input -->\n" + elements + "\n</routes>\n");
  }

  // The grid_tls network with the first occurrence of `from` replaced by `to`.
  void write_grid_net_with(const std::string& name, const std::string& from, const std::string& to) {
    std::string net = read_file(kGridNet);
    const auto at = net.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    net.replace(at, from.size(), to);
    write(name, net);
  }

  CliResult run(const std::vector<std::string>& args) const { return test::run_lpsim(tmp_.path(), args); }

  CliResult info_with_routes(const std::string& routes) const {
    return run({"info", "-n", kGridNet, "-r", routes});
  }

  test::TempDir tmp_{"lpsim_cli_bad"};
};

// Exit status 2; stderr exactly one line "lpsim: error: <where>: ..." containing every one of `names`.
void expect_input_error(const CliResult& r, const std::string& where, const std::vector<std::string>& names) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << r.err;
  EXPECT_EQ(r.err.back(), '\n');
  const std::string prefix = "lpsim: error: " + where + ": ";
  EXPECT_EQ(lines[0].rfind(prefix, 0), 0u) << "expected prefix '" << prefix << "' in: " << lines[0];
  for (const auto& n : names)
    EXPECT_NE(lines[0].find(n), std::string::npos) << "'" << n << "' missing in: " << lines[0];
}

// The line number in "lpsim: error: <file>:<line>: ...", or -1.
int reported_line(const std::string& err, const std::string& file) {
  const std::string prefix = "lpsim: error: " + file + ":";
  if (err.rfind(prefix, 0) != 0) return -1;
  return std::atoi(err.c_str() + prefix.size());
}

// Line 1227 of grid_tls.net.xml (between two <edge>s, at top level of <net>) becomes garbage.
const char* kGarbageLine = "    <junk a=\"1\" b=2 />";
constexpr int kGarbageLineNumber = 1227;

void write_net_with_garbage_line(const fs::path& path) {
  const auto lines = lines_of(read_file(kGridNet));
  std::ofstream out(path, std::ios::binary);
  for (size_t i = 0; i < lines.size(); ++i)
    out << (static_cast<int>(i) + 1 == kGarbageLineNumber ? std::string(kGarbageLine) : lines[i]) << "\n";
}

TEST_F(CliBadInputTest, MalformedXml) {
  write_net_with_garbage_line(tmp_.path() / "garbage.net.xml");
  const auto r = run({"info", "-n", "garbage.net.xml"});
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_GT(reported_line(r.err, "garbage.net.xml"), 0) << r.err;
  EXPECT_NE(r.err.find("malformed XML"), std::string::npos) << r.err;
}

// The line of a malformed-XML error is where the parser found the error (as xmllint reports it).
TEST_F(CliBadInputTest, MalformedXmlNamesTheLineOfTheError) {
  write_net_with_garbage_line(tmp_.path() / "garbage.net.xml");
  const auto r = run({"info", "-n", "garbage.net.xml"});
  expect_input_error(r, "garbage.net.xml:" + std::to_string(kGarbageLineNumber), {"malformed XML"});
}

TEST_F(CliBadInputTest, MalformedXmlInRouteFile) {
  write("broken.rou.xml",
        "<routes>\n<vehicle id=\"v1\" depart=\"0\">\n<route edges=\"A0A1 A1A2\"/>\n</routes>\n");
  const auto r = info_with_routes("broken.rou.xml");
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_GT(reported_line(r.err, "broken.rou.xml"), 0) << r.err;
  EXPECT_NE(r.err.find("malformed XML"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("vehicle"), std::string::npos) << r.err;  // libxml2 names the unclosed tag
}

TEST_F(CliBadInputTest, TruncatedXml) {
  const std::string net = read_file(kGridNet);
  write("half.net.xml", net.substr(0, net.size() / 2));
  const auto r = run({"info", "-n", "half.net.xml"});
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_GT(reported_line(r.err, "half.net.xml"), 0) << r.err;
  EXPECT_NE(r.err.find("malformed XML"), std::string::npos) << r.err;
}

// A file cut after a complete line is reported at its end, as truncated.
TEST_F(CliBadInputTest, TruncatedXmlNamesTheEndOfTheFile) {
  const auto lines = lines_of(read_file(kGridNet));
  std::string cut;
  for (size_t i = 0; i < lines.size() / 2; ++i) cut += lines[i] + "\n";
  write("cut.net.xml", cut);
  const int last_line = static_cast<int>(lines.size() / 2);
  const auto r = run({"info", "-n", "cut.net.xml"});
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
  const int line = reported_line(r.err, "cut.net.xml");
  EXPECT_TRUE(line == last_line || line == last_line + 1) << r.err;
  EXPECT_TRUE(r.err.find("end") != std::string::npos || r.err.find("truncated") != std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("Extra content"), std::string::npos) << r.err;
}

TEST_F(CliBadInputTest, MissingFile) {
  expect_input_error(run({"info", "-n", "no_such.net.xml"}), "no_such.net.xml", {"missing"});
}

TEST_F(CliBadInputTest, MissingRouteFileInSumocfg) {
  write("s.sumocfg", "<configuration>\n<input>\n<net-file value=\"" + kGridNet +
                         "\"/>\n<route-files value=\"gone.rou.xml\"/>\n</input>\n</configuration>\n");
  const auto r = run({"info", "-c", "s.sumocfg"});
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("lpsim: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("gone.rou.xml"), std::string::npos) << r.err;
}

TEST_F(CliBadInputTest, EmptyFile) {
  write("empty.net.xml", "");
  expect_input_error(run({"info", "-n", "empty.net.xml"}), "empty.net.xml", {"empty"});
  write("empty.rou.xml", "");
  expect_input_error(info_with_routes("empty.rou.xml"), "empty.rou.xml", {"empty"});
}

TEST_F(CliBadInputTest, UnknownEdgeInRoute) {
  write_routes("r.rou.xml", R"(<vehicle id="v_bad" depart="0"><route edges="A0A1 NO_SUCH_EDGE"/></vehicle>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"'NO_SUCH_EDGE'", "'v_bad'"});
}

TEST_F(CliBadInputTest, UnknownEdgeInNamedRouteNamesRouteAndVehicle) {
  write_routes("r.rou.xml",
               "<route id=\"r_bad\" edges=\"A0A1 NO_SUCH_EDGE\"/>\n"
               "<vehicle id=\"v_bad\" depart=\"0\" route=\"r_bad\"/>");
  const auto r = info_with_routes("r.rou.xml");
  EXPECT_EQ(r.exit_code, 2);
  for (const char* name : {"'NO_SUCH_EDGE'", "'r_bad'", "'v_bad'"})
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
}

TEST_F(CliBadInputTest, UnknownEdgeInTrip) {
  write_routes("r.rou.xml", R"(<trip id="t_bad" depart="0" from="NO_SUCH_EDGE" to="A1A2"/>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"'NO_SUCH_EDGE'", "'t_bad'"});
}

TEST_F(CliBadInputTest, UnknownVType) {
  write_routes("r.rou.xml",
               R"(<vehicle id="v_bad" type="no_such_type" depart="0"><route edges="A0A1 A1A2"/></vehicle>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"'no_such_type'", "'v_bad'"});
}

TEST_F(CliBadInputTest, UnknownRouteId) {
  write_routes("r.rou.xml", R"(<vehicle id="v_bad" route="no_such_route" depart="0"/>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"'no_such_route'", "'v_bad'"});
}

TEST_F(CliBadInputTest, DisconnectedRoute) {
  // A0A1 runs north on the west border; C3C4 is two columns east: no connection between them.
  write_routes("r.rou.xml", R"(<vehicle id="v_bad" depart="0"><route edges="A0A1 C3C4"/></vehicle>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"'A0A1'", "'C3C4'", "'v_bad'"});
}

TEST_F(CliBadInputTest, NegativeLaneLength) {
  // Line 8 of grid_tls.net.xml is the first lane, :A0_0_0, length 18.06.
  write_grid_net_with("neg.net.xml", "length=\"18.06\"", "length=\"-18.06\"");
  expect_input_error(run({"info", "-n", "neg.net.xml"}), "neg.net.xml:8", {"length", "-18.06", ":A0_0_0"});
}

TEST_F(CliBadInputTest, NegativeVTypeLength) {
  write_routes("r.rou.xml",
               "<vType id=\"t_bad\" length=\"-5\"/>\n"
               "<vehicle id=\"v1\" type=\"t_bad\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"length", "-5", "t_bad"});
}

TEST_F(CliBadInputTest, NanLaneSpeed) {
  write_grid_net_with("nan.net.xml", "speed=\"8.96\"", "speed=\"nan\"");
  expect_input_error(run({"info", "-n", "nan.net.xml"}), "nan.net.xml:8", {"speed", "'nan'", ":A0_0_0"});
}

TEST_F(CliBadInputTest, NanVTypeMaxSpeed) {
  write_routes("r.rou.xml",
               "<vType id=\"t_bad\" maxSpeed=\"NaN\"/>\n"
               "<vehicle id=\"v1\" type=\"t_bad\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"maxSpeed", "NaN", "t_bad"});
}

// vType values at LPSim's upper bounds (far beyond any vehicle) and an absurd lane speed must not overflow
// the step's float arithmetic or its distance-to-cell conversions: the run ends normally, every vehicle
// accounted for.
TEST_F(CliBadInputTest, ExtremeValuesRunToTheEnd) {
  write_grid_net_with("fast.net.xml", "speed=\"13.89\"", "speed=\"1e30\"");
  write_routes("r.rou.xml",
               "<vType id=\"gap\" minGap=\"10000\" tau=\"3600\"/>\n"
               "<vType id=\"accel\" accel=\"1000\" decel=\"1e-30\" emergencyDecel=\"1000\" maxSpeed=\"1000\" "
               "speedFactor=\"100\"/>\n"
               "<vType id=\"long\" length=\"10000\"/>\n"
               "<vehicle id=\"v0\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
               "<vehicle id=\"v1\" type=\"gap\" depart=\"1\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
               "<vehicle id=\"v2\" type=\"accel\" depart=\"2\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
               "<vehicle id=\"v3\" type=\"long\" depart=\"3\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
               "<vehicle id=\"v4\" depart=\"4\"><route edges=\"A0A1 A1A2\"/></vehicle>");
  const CliResult r = run({"run", "-n", "fast.net.xml", "-r", "r.rou.xml", "--end", "600"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Each goes in on an empty road (the long one with its body behind the lane start, as SUMO allows) and
  // arrives.
  EXPECT_NE(r.out.find("Inserted: 5 (Loaded: 5)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" Arrived: 5"), std::string::npos) << r.out;
}

TEST_F(CliBadInputTest, ValuesBeyondLpsimBounds) {
  for (const char* attr : {"accel=\"1001\"", "decel=\"1e300\"", "length=\"1e19\"", "maxSpeed=\"5000\"",
                           "tau=\"4000\"", "minGap=\"2e4\""}) {
    write_routes("r.rou.xml", std::string("<vType id=\"t_bad\" ") + attr +
                                  "/>\n<vehicle id=\"v1\" type=\"t_bad\" depart=\"0\"><route edges=\"A0A1 "
                                  "A1A2\"/></vehicle>");
    expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"t_bad", "up to"});
  }
  write_routes("r.rou.xml",
               "<vType id=\"t_bad\" speedFactor=\"4294967296\"/>\n"
               "<vehicle id=\"v1\" type=\"t_bad\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3",
                     {"speedFactor", "up to 100", "4294967296"});
  // Lane values: finite as doubles, infinite as the floats the engine keeps.
  write_grid_net_with("big.net.xml", "speed=\"8.96\"", "speed=\"1e300\"");
  expect_input_error(run({"info", "-n", "big.net.xml"}), "big.net.xml:8", {"speed", "'1e300'", "float"});
}

TEST_F(CliBadInputTest, NegativeDepart) {
  write_routes("r.rou.xml", R"(<vehicle id="v_bad" depart="-5"><route edges="A0A1 A1A2"/></vehicle>)");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3", {"depart", "-5", "v_bad"});
}

TEST_F(CliBadInputTest, NegativeDepartInOdCsv) {
  write("od.csv", ",dep_time,origin,destination\n0,0,1,5\n1,-3,5,1\n");
  const auto r = run({"info", "--lpsim-nodes", kCsvDir + "/nodes.csv", "--lpsim-edges",
                      kCsvDir + "/edges.csv", "--lpsim-od", "od.csv"});
  expect_input_error(r, "od.csv:3", {"-3", "dep_time"});
}

TEST_F(CliBadInputTest, CsvMissingColumn) {
  // edges.csv of lpsim_csv_small without its length column.
  write("edges.csv", "uniqueid,u,v,lanes,speed_mph\n0,1002,1001,2,35\n1,1001,1002,2,35\n");
  const auto r = run({"info", "--lpsim-nodes", kCsvDir + "/nodes.csv", "--lpsim-edges", "edges.csv"});
  expect_input_error(r, "edges.csv:1", {"'length'"});
}

// A snapshot of a one-vehicle grid_tls scenario, written by `lpsim convert` into the test dir.
class CliBadSnapshotTest : public CliBadInputTest {
 protected:
  void SetUp() override {
    write_routes("r.rou.xml", R"(<vehicle id="v1" depart="0"><route edges="A0A1 A1A2"/></vehicle>)");
    const auto r = run({"convert", "-n", kGridNet, "-r", "r.rou.xml", "-o", "good.lpsim"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    snapshot_ = read_file(tmp_.path() / "good.lpsim");
    ASSERT_GT(snapshot_.size(), 1000u);
  }
  std::string snapshot_;
};

TEST_F(CliBadSnapshotTest, GoodSnapshotLoads) {
  const auto r = run({"info", "good.lpsim"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("vehicles: 1\n"), std::string::npos) << r.out;
}

TEST_F(CliBadSnapshotTest, TruncatedSnapshot) {
  write("cut.lpsim", snapshot_.substr(0, snapshot_.size() / 2));
  expect_input_error(run({"info", "cut.lpsim"}), "cut.lpsim", {"truncated"});
}

TEST_F(CliBadSnapshotTest, WrongChecksum) {
  std::string bad = snapshot_;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x5a);
  write("bad.lpsim", bad);
  expect_input_error(run({"info", "bad.lpsim"}), "bad.lpsim", {"checksum"});
}

TEST_F(CliBadSnapshotTest, OtherFormatVersion) {
  std::string other = snapshot_;
  other[8] = static_cast<char>(other[8] + 1);  // the version follows the 8-byte magic
  write("other.lpsim", other);
  expect_input_error(run({"info", "other.lpsim"}), "other.lpsim", {"version"});
}

// --ignore-route-errors: the broken vehicle is left out and listed by id; the good one loads.
TEST_F(CliBadInputTest, IgnoreRouteErrorsSkipsUnknownEdgeAndDisconnectedRoute) {
  write_routes("r.rou.xml",
               "<vehicle id=\"v_good\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>\n"
               "<vehicle id=\"v_unknown_edge\" depart=\"1\"><route edges=\"A0A1 NO_SUCH_EDGE\"/></vehicle>\n"
               "<vehicle id=\"v_disconnected\" depart=\"2\"><route edges=\"A0A1 C3C4\"/></vehicle>");
  const auto strict = info_with_routes("r.rou.xml");
  EXPECT_EQ(strict.exit_code, 2);

  const auto r = run({"info", "-n", kGridNet, "-r", "r.rou.xml", "--ignore-route-errors"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("lpsim: error"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("vehicles: 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("unrouted or skipped vehicles: 2\n"), std::string::npos) << r.out;
  bool unknown_listed = false, disconnected_listed = false;
  for (const auto& line : lines_of(r.out)) {
    if (line.rfind("  v_unknown_edge: ", 0) == 0)
      unknown_listed =
          line.find("NO_SUCH_EDGE") != std::string::npos && line.find("r.rou.xml:4") != std::string::npos;
    if (line.rfind("  v_disconnected: ", 0) == 0)
      disconnected_listed =
          line.find("C3C4") != std::string::npos && line.find("r.rou.xml:5") != std::string::npos;
  }
  EXPECT_TRUE(unknown_listed) << r.out;
  EXPECT_TRUE(disconnected_listed) << r.out;
}

// Vehicles sharing a broken named route each get a reason naming themselves.
TEST_F(CliBadInputTest, IgnoreRouteErrorsReasonNamesEachVehicle) {
  write_routes("r.rou.xml",
               "<route id=\"r_bad\" edges=\"A0A1 NO_SUCH_EDGE\"/>\n"
               "<vehicle id=\"a\" depart=\"0\" route=\"r_bad\"/>\n"
               "<vehicle id=\"b\" depart=\"0\" route=\"r_bad\"/>\n"
               "<flow id=\"f\" begin=\"0\" end=\"2\" period=\"1\" route=\"r_bad\"/>");
  const auto r = run({"info", "-n", kGridNet, "-r", "r.rou.xml", "--ignore-route-errors"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("unrouted or skipped vehicles: 4\n"), std::string::npos) << r.out;
  for (const std::string id : {"a", "b", "f.0", "f.1"}) {
    bool own_name = false;
    for (const auto& line : lines_of(r.out))
      if (line.rfind("  " + id + ": ", 0) == 0)
        own_name = line.find("vehicle '" + id + "'") != std::string::npos;
    EXPECT_TRUE(own_name) << id << " in:\n" << r.out;
  }
}

TEST_F(CliBadInputTest, IgnoreRouteErrorsSkipsUnknownEdgeInTrip) {
  write_routes("r.rou.xml",
               "<trip id=\"t_good\" depart=\"0\" from=\"A0A1\" to=\"A1A2\"/>\n"
               "<trip id=\"t_bad\" depart=\"1\" from=\"NO_SUCH_EDGE\" to=\"A1A2\"/>");
  const auto r = run({"info", "-n", kGridNet, "-r", "r.rou.xml", "--ignore-route-errors"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("vehicles: 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  t_bad: "), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lpsim

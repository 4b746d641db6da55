// `lpsim assign` end to end on scenarios/reroute_block: a vehicle stands 600 s on the short way from `in` to
// `out` while 120 trips follow it. Routed on free flow they all queue behind it; the iterations learn the
// short way's travel times and send most the long way round.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

struct Line {
  int iteration = -1;
  double gap = 0, mean_trip = 0;
  long finished = 0, teleports = 0;
};

std::vector<Line> iteration_lines(const std::string& out) {
  std::vector<Line> lines;
  for (const std::string& text : test::lines_of(out)) {
    std::istringstream in(text);
    Line l;
    if (in >> l.iteration >> l.gap >> l.mean_trip >> l.finished >> l.teleports) lines.push_back(l);
  }
  return lines;
}

std::string scenario(const std::string& file) {
  return std::string(LPSIM_SCENARIOS_DIR) + "/reroute_block/" + file;
}

std::vector<std::string> assign_args(const std::string& out, int threads) {
  return {"assign",
          "-n",
          scenario("reroute_block.net.xml"),
          "-r",
          scenario("reroute_block.rou.xml"),
          "-o",
          out,
          "--iterations",
          "6",
          "--aggregation",
          "60",
          "--time-to-teleport",
          "-1",
          "--threads",
          std::to_string(threads)};
}

int long_way_routes(const std::string& routes) {
  static const std::regex route("<route edges=\"([^\"]*)\"");
  int n = 0;
  for (auto it = std::sregex_iterator(routes.begin(), routes.end(), route); it != std::sregex_iterator();
       ++it)
    n += (*it)[1].str().find("short") == std::string::npos;
  return n;
}

TEST(AssignCli, TripsLearnTheBlockAndTheGapFalls) {
  test::TempDir dir("lpsim_assign");
  std::vector<std::string> args = assign_args("assigned.rou.xml", 1);
  args.insert(args.end(), {"--plot", "gap.png"});
  const test::CliResult r = test::run_lpsim(dir.path(), args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Line> lines = iteration_lines(r.out);
  ASSERT_EQ(lines.size(), 6u) << r.out;
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(lines[i].iteration, i);
    EXPECT_EQ(lines[i].finished, 121);
    EXPECT_EQ(lines[i].teleports, 0);
  }
  // Measured: the gap from 45.6 to 0.29 and the mean trip from 572.8 s to 242.6 s.
  EXPECT_GT(lines[0].gap, 10);
  EXPECT_LT(lines[5].gap, lines[0].gap / 20);
  EXPECT_LT(lines[5].mean_trip, 0.6 * lines[0].mean_trip);
  const std::string routes = test::read_file(dir.path() / "assigned.rou.xml");
  const std::string alternatives = test::read_file(dir.path() / "assigned.rou.alt.xml");
  size_t vehicles = 0;
  for (size_t at = 0; (at = routes.find("<vehicle ", at)) != std::string::npos; ++at) ++vehicles;
  EXPECT_EQ(vehicles, 121u);
  EXPECT_GT(long_way_routes(routes), 60);  // measured 110 of 121
  EXPECT_NE(alternatives.find("<routeDistribution last=\""), std::string::npos);
  EXPECT_NE(alternatives.find("probability=\""), std::string::npos);
  EXPECT_EQ(test::read_file(dir.path() / "gap.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
}

// The contraction hierarchy, customized per interval, routes each vehicle on its depart interval's times
// (duarouter's CH): the trips learn the block as well.
TEST(AssignCli, ContractionHierarchyLearnsTheBlockToo) {
  test::TempDir dir("lpsim_assign_ch");
  std::vector<std::string> args = assign_args("assigned.rou.xml", 2);
  args.insert(args.end(), {"--routing-algorithm", "CH"});
  const test::CliResult r = test::run_lpsim(dir.path(), args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Line> lines = iteration_lines(r.out);
  ASSERT_EQ(lines.size(), 6u) << r.out;
  EXPECT_GT(lines[0].gap, 10);
  EXPECT_LT(lines[5].gap, lines[0].gap / 20);
  EXPECT_LT(lines[5].mean_trip, 0.6 * lines[0].mean_trip);
  EXPECT_GT(long_way_routes(test::read_file(dir.path() / "assigned.rou.xml")), 60);
}

// duarouter's C-logit in place of Gawron's model: the trips learn the block too. Logit takes each route's new
// cost whole (Gawron smooths), so the choices swing between iterations (measured: gaps 45.6, 4.7, 33.1, 1.1,
// 15.1, 2.9; mean trips 572.8 s to 331.5 s; 70 of 121 the long way at the end).
TEST(AssignCli, LogitLearnsTheBlockToo) {
  test::TempDir dir("lpsim_assign_logit");
  std::vector<std::string> args = assign_args("assigned.rou.xml", 1);
  args.insert(args.end(), {"--route-choice-method", "logit"});
  const test::CliResult r = test::run_lpsim(dir.path(), args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Line> lines = iteration_lines(r.out);
  ASSERT_EQ(lines.size(), 6u) << r.out;
  EXPECT_LT(lines[5].gap, lines[0].gap / 10);
  EXPECT_LT(lines[5].mean_trip, 0.7 * lines[0].mean_trip);
  EXPECT_GT(long_way_routes(test::read_file(dir.path() / "assigned.rou.xml")), 40);
}

TEST(AssignCli, RoutesFileReproducesTheLastIterationAndItsGap) {
  test::TempDir dir("lpsim_assign_replay");
  const test::CliResult a = test::run_lpsim(dir.path(), assign_args("assigned.rou.xml", 2));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::vector<Line> lines = iteration_lines(a.out);
  ASSERT_EQ(lines.size(), 6u);
  // The last iteration's routes, simulated again: the same trips (the mean of their durations), and its
  // travel times as duaIterate's dump records them give the same relative gap (up to the dump's 2 decimals).
  dir.write("dump.add.xml",
            "<additional><edgeData id=\"dump\" freq=\"60\" file=\"dump.xml\" excludeEmpty=\"true\" "
            "minSamples=\"1\"/></additional>\n");
  const test::CliResult run =
      test::run_lpsim(dir.path(), {"run", "-n", scenario("reroute_block.net.xml"), "-r", "assigned.rou.xml",
                                   "-a", "dump.add.xml", "--time-to-teleport", "-1", "--no-step-log"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.out, m, std::regex(" Duration: ([0-9.]+)\n")));
  EXPECT_NEAR(std::stod(m[1]), lines[5].mean_trip, 0.006);
  const test::CliResult gap =
      test::run_lpsim(dir.path(), {"assign", "-n", scenario("reroute_block.net.xml"), "-r",
                                   "assigned.rou.xml", "--weight-files", "dump.xml"});
  ASSERT_EQ(gap.exit_code, 0) << gap.err;
  ASSERT_TRUE(std::regex_search(gap.out, m, std::regex("vehicles 121, .* relative gap ([0-9.]+)")))
      << gap.out;
  EXPECT_NEAR(std::stod(m[1]), lines[5].gap, 1e-3 * lines[5].gap + 1e-5);
}

// The same routes, alternatives, gaps and mean trip times on 1 and 2 threads and with each iteration
// simulated in 3 parts.
TEST(AssignCli, SameRoutesOnAnyThreadAndPartCount) {
  test::TempDir dir("lpsim_assign_threads");
  const test::CliResult one = test::run_lpsim(dir.path(), assign_args("one.rou.xml", 1));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  std::vector<std::string> in_parts = assign_args("parts.rou.xml", 1);
  in_parts.insert(in_parts.end(), {"--parts", "3", "--parts.min-vehicles", "0"});
  for (const auto& [name, args] :
       {std::pair{"two", assign_args("two.rou.xml", 2)}, std::pair{"parts", in_parts}}) {
    SCOPED_TRACE(name);
    const test::CliResult other = test::run_lpsim(dir.path(), args);
    ASSERT_EQ(other.exit_code, 0) << other.err;
    EXPECT_EQ(test::read_file(dir.path() / "one.rou.xml"),
              test::read_file(dir.path() / (std::string(name) + ".rou.xml")));
    EXPECT_EQ(test::read_file(dir.path() / "one.rou.alt.xml"),
              test::read_file(dir.path() / (std::string(name) + ".rou.alt.xml")));
    const std::vector<Line> a = iteration_lines(one.out), b = iteration_lines(other.out);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].gap, b[i].gap);
      EXPECT_EQ(a[i].mean_trip, b[i].mean_trip);
    }
  }
}

// Three iterations, then three more from the alternatives the first three wrote: the same iterations and the
// same files as six in one go.
TEST(AssignCli, ResumedFromTheAlternativesAsIfUninterrupted) {
  test::TempDir dir("lpsim_assign_resume");
  const test::CliResult full = test::run_lpsim(dir.path(), assign_args("full.rou.xml", 1));
  ASSERT_EQ(full.exit_code, 0) << full.err;
  std::vector<std::string> half = assign_args("half.rou.xml", 1);
  half[std::find(half.begin(), half.end(), "--iterations") - half.begin() + 1] = "3";
  ASSERT_EQ(test::run_lpsim(dir.path(), half).exit_code, 0);
  std::vector<std::string> resumed = assign_args("resumed.rou.xml", 1);
  resumed[std::find(resumed.begin(), resumed.end(), "-r") - resumed.begin() + 1] = "half.rou.alt.xml";
  resumed.insert(resumed.end(), {"--first-iteration", "3"});
  const test::CliResult r = test::run_lpsim(dir.path(), resumed);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Line> all = iteration_lines(full.out), rest = iteration_lines(r.out);
  ASSERT_EQ(all.size(), 6u);
  ASSERT_EQ(rest.size(), 3u) << r.out;
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(rest[i].iteration, all[3 + i].iteration);
    EXPECT_EQ(rest[i].gap, all[3 + i].gap);
    EXPECT_EQ(rest[i].mean_trip, all[3 + i].mean_trip);
  }
  EXPECT_EQ(test::read_file(dir.path() / "full.rou.xml"), test::read_file(dir.path() / "resumed.rou.xml"));
  EXPECT_EQ(test::read_file(dir.path() / "full.rou.alt.xml"),
            test::read_file(dir.path() / "resumed.rou.alt.xml"));
  // Routes without alternatives cannot be resumed from.
  std::vector<std::string> no_alternatives = assign_args("x.rou.xml", 1);
  no_alternatives.insert(no_alternatives.end(), {"--first-iteration", "3"});
  const test::CliResult bad = test::run_lpsim(dir.path(), no_alternatives);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("routeDistribution"), std::string::npos) << bad.err;
}

// A snapshot's routing options were applied by `lpsim convert`; assign routes anew and takes its own.
TEST(AssignCli, RoutesASnapshotWithTheHierarchy) {
  test::TempDir dir("lpsim_assign_snapshot");
  const test::CliResult convert =
      test::run_lpsim(dir.path(), {"convert", "-n", scenario("reroute_block.net.xml"), "-r",
                                   scenario("reroute_block.rou.xml"), "-o", "block.lpsim"});
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  const test::CliResult a = test::run_lpsim(
      dir.path(), {"assign", "block.lpsim", "-o", "assigned.rou.xml", "--iterations", "2", "--aggregation",
                   "60", "--time-to-teleport", "-1", "--routing-algorithm", "CH"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(iteration_lines(a.out).size(), 2u);
  const test::CliResult run =
      test::run_lpsim(dir.path(), {"run", "block.lpsim", "--routing-algorithm", "CH"});
  EXPECT_EQ(run.exit_code, 2) << "run beside a snapshot: the routing option acts only while loading";
}

TEST(AssignCli, WithoutOutputOrOntoAnInputIsBadInput) {
  test::TempDir dir("lpsim_assign_bad");
  const test::CliResult no_output = test::run_lpsim(
      dir.path(),
      {"assign", "-n", scenario("reroute_block.net.xml"), "-r", scenario("reroute_block.rou.xml")});
  EXPECT_EQ(no_output.exit_code, 2);
  EXPECT_NE(no_output.err.find("give -o"), std::string::npos) << no_output.err;
  std::vector<std::string> onto_input = assign_args(scenario("reroute_block.rou.xml"), 1);
  const test::CliResult overwrite = test::run_lpsim(dir.path(), onto_input);
  EXPECT_EQ(overwrite.exit_code, 2);
  EXPECT_NE(overwrite.err.find("is the input"), std::string::npos) << overwrite.err;
}

}  // namespace
}  // namespace lpsim

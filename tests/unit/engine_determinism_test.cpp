// Determinism of `lpsim run`: the same scenario run with 1, 2 and 4 threads, run twice, and run with its
// network split into 2, 3, 4 and 8 parts, writes byte-identical FCD, tripinfo, edgeData and summary files
// (the summary's per-step wall time `duration` masked, the only value allowed to differ).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string mask_duration(const std::string& summary) {
  static const std::regex duration(" duration=\"[^\"]*\"");
  return std::regex_replace(summary, duration, " duration=\"masked\"");
}

// Position and the two lines around the first difference, for a readable failure.
std::string first_difference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  auto line_at = [](const std::string& s, size_t at) {
    if (at >= s.size()) return std::string("<end of file>");
    const size_t begin = s.rfind('\n', at) == std::string::npos ? 0 : s.rfind('\n', at) + 1;
    return s.substr(begin, s.find('\n', at) - begin);
  };
  return "byte " + std::to_string(i) + ":\n  " + line_at(a, i) + "\n  " + line_at(b, i);
}

class EngineDeterminismTest : public ::testing::Test {
 protected:
  struct Outputs {
    std::string fcd, tripinfo, edgedata, summary;
  };

  // Runs the binary on a bundled scenario with all four outputs in a run-specific folder.
  // Without edgeData the engine skips its per-lane counters (SimulationOptions::lane_counters).
  Outputs run(const std::string& scenario, int threads, const std::string& tag, bool edgedata = true,
              const std::string& extra = "") {
    const fs::path out = tmp_.path() / tag;
    fs::create_directories(out);
    const std::string cfg = std::string(LPSIM_SCENARIOS_DIR) + "/" + scenario + "/" + scenario + ".sumocfg";
    std::string cmd = std::string(LPSIM_BINARY) + " run " + cfg + " --threads " + std::to_string(threads) +
                      " --fcd-output " + (out / "fcd.xml").string() + " --tripinfo-output " +
                      (out / "tripinfo.xml").string() +
                      (edgedata ? " --edgedata-output " + (out / "edgedata.xml").string() : std::string()) +
                      " --summary-output " + (out / "summary.xml").string();
    cmd += ' ';
    cmd += extra;
    cmd += " > " + (out / "log.txt").string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    last_log_ = read_file(out / "log.txt");
    EXPECT_EQ(rc, 0) << cmd << "\n" << last_log_;
    return Outputs{read_file(out / "fcd.xml"), read_file(out / "tripinfo.xml"),
                   read_file(out / "edgedata.xml"), mask_duration(read_file(out / "summary.xml"))};
  }

  static void expect_same(const Outputs& a, const Outputs& b, const std::string& what) {
    EXPECT_TRUE(a.fcd == b.fcd) << what << ": fcd differs at " << first_difference(a.fcd, b.fcd);
    EXPECT_TRUE(a.tripinfo == b.tripinfo)
        << what << ": tripinfo differs at " << first_difference(a.tripinfo, b.tripinfo);
    EXPECT_TRUE(a.edgedata == b.edgedata)
        << what << ": edgedata differs at " << first_difference(a.edgedata, b.edgedata);
    EXPECT_TRUE(a.summary == b.summary)
        << what << ": summary differs at " << first_difference(a.summary, b.summary);
  }

  // The reference run must have produced real content, or identical empty files would pass.
  static void expect_content(const Outputs& o, size_t vehicles) {
    auto count = [](const std::string& s, const std::string& needle) {
      size_t n = 0;
      for (size_t at = s.find(needle); at != std::string::npos; at = s.find(needle, at + 1)) ++n;
      return n;
    };
    EXPECT_EQ(count(o.tripinfo, "<tripinfo "), vehicles);
    EXPECT_GT(count(o.fcd, "<vehicle "), vehicles * 10);
    EXPECT_GE(count(o.edgedata, "<edge "), 6u);  // reroute_block has six edges
    EXPECT_GT(count(o.summary, "<step "), 100u);
  }

  void check_scenario(const std::string& scenario, size_t vehicles) {
    const Outputs one = run(scenario, 1, "t1");
    expect_content(one, vehicles);
    expect_same(one, run(scenario, 2, "t2"), scenario + " threads 1 vs 2");
    const Outputs four = run(scenario, 4, "t4");
    expect_same(one, four, scenario + " threads 1 vs 4");
    expect_same(four, run(scenario, 4, "t4_again"), scenario + " threads 4, repeated");
  }

  // Vehicles that drove from one part into another in the last run, summed over its parts (the report's
  // "migrations out").
  uint64_t migrations() const {
    static const std::regex out("migrations out ([0-9]+)");
    uint64_t n = 0;
    for (auto it = std::sregex_iterator(last_log_.begin(), last_log_.end(), out);
         it != std::sregex_iterator(); ++it)
      n += std::stoull((*it)[1]);
    return n;
  }

  // K = 1 against the network split into K parts (METIS, one thread per part): the same bytes, with
  // vehicles crossing the cuts.
  void check_parts(const std::string& scenario, size_t vehicles, const std::vector<int>& part_counts) {
    const Outputs one = run(scenario, 1, "k1");
    expect_content(one, vehicles);
    for (const int k : part_counts) {
      const std::string count = std::to_string(k);
      const Outputs parts = run(scenario, 1, std::string("k").append(count), true,
                                std::string("--parts.min-vehicles 0 --parts ").append(count));
      expect_same(one, parts, scenario + " one part vs " + std::to_string(k));
      EXPECT_GT(migrations(), vehicles / 10) << scenario << " in " << k << " parts:\n" << last_log_;
    }
  }

  test::TempDir tmp_{"lpsim_determinism"};
  std::string last_log_;
};

TEST_F(EngineDeterminismTest, GridTlsSameOutputsForAnyThreadCount) { check_scenario("grid_tls", 1000); }

TEST_F(EngineDeterminismTest, RandomNetSameOutputsForAnyThreadCount) { check_scenario("random_net", 300); }

TEST_F(EngineDeterminismTest, GridTlsSameOutputsForAnyPartCount) {
  check_parts("grid_tls", 1000, {2, 3, 4, 8});
}

// Actuated signals: each runs in the part of its junction and sends its state to the parts that see it (the
// cross has five junctions).
TEST_F(EngineDeterminismTest, ActuatedCrossSameOutputsForAnyPartCount) {
  check_parts("actuated_cross", 660, {2, 3, 4});
}

TEST_F(EngineDeterminismTest, RandomNetSameOutputsForAnyPartCount) {
  check_parts("random_net", 300, {2, 3, 4, 8});
}

// The rerouting device: routes computed between steps on speeds sampled from the state, swapped between
// the parts.
TEST_F(EngineDeterminismTest, RerouteBlockSameOutputsForAnyThreadCount) {
  check_scenario("reroute_block", 121);
}

TEST_F(EngineDeterminismTest, RerouteBlockSameOutputsForAnyPartCount) {
  check_parts("reroute_block", 121, {2, 3});
}

// The device's routes from the contraction hierarchy (--routing-algorithm CH): the same in any number of
// parts, and the same trips sent the long way as with Dijkstra (no two routes of reroute_block cost alike).
TEST_F(EngineDeterminismTest, RerouteBlockWithTheContractionHierarchy) {
  const Outputs dijkstra = run("reroute_block", 1, "dijkstra");
  const Outputs ch = run("reroute_block", 1, "ch", true, "--routing-algorithm CH");
  expect_content(ch, 121);
  expect_same(dijkstra, ch, "reroute_block Dijkstra vs CH");
  expect_same(
      ch, run("reroute_block", 2, "ch_k3", true, "--routing-algorithm CH --parts 3 --parts.min-vehicles 0"),
      "reroute_block CH, one part vs 3");
}

TEST_F(EngineDeterminismTest, OutputsDoNotDependOnWhetherEdgeDataIsWritten) {
  Outputs with = run("grid_tls", 2, "with_edgedata");
  expect_content(with, 1000);
  Outputs without = run("grid_tls", 2, "without_edgedata", false);
  EXPECT_TRUE(without.edgedata.empty());
  without.edgedata = with.edgedata;  // the only output that may differ: it was not asked for
  expect_same(with, without, "grid_tls with vs without edgeData");
}

TEST(EngineDeterminismMaskTest, MasksOnlyTheDuration) {
  EXPECT_EQ(mask_duration("<step time=\"1.00\" halting=\"0\" duration=\"17\"/>"),
            "<step time=\"1.00\" halting=\"0\" duration=\"masked\"/>");
  EXPECT_NE(mask_duration("<step time=\"1.00\" duration=\"3\"/>"),
            mask_duration("<step time=\"2.00\" duration=\"3\"/>"));
}

}  // namespace
}  // namespace lpsim

// `lpsim run` and `lpsim convert` never write over an input or write two outputs to one file: such a path is
// refused with exit 2 and one line naming both options and paths, before anything is written, however the
// path is spelt (./x, a/../x, a symlink, a hard link). The real binary on real files in a temp dir.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::read_file;

const std::string kGridNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";
const std::string kCsvDir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small";

constexpr const char* kRoutes = R"(<routes>
    <vehicle id="v0" depart="0"><route edges="A0A1 A1A2"/></vehicle>
</routes>
)";

class CliOutputPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_.write("net.net.xml", read_file(kGridNet));
    tmp_.write("r.rou.xml", kRoutes);
    tmp_.write("s.sumocfg",
               "<configuration>\n  <input>\n    <net-file value=\"net.net.xml\"/>\n"
               "    <route-files value=\"r.rou.xml\"/>\n  </input>\n</configuration>\n");
    fs::create_directories(tmp_.path() / "sub");
  }

  CliResult run(std::vector<std::string> args) const { return test::run_lpsim(tmp_.path(), args); }

  // Exit 2, one line on stderr naming every one of `names`, and every file of `unchanged` as it was.
  void expect_refused(const CliResult& r, const std::vector<std::string>& names) const {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("lpsim: error: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    for (const auto& n : names)
      EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' missing: " << r.err;
    EXPECT_EQ(read_file(tmp_.path() / "r.rou.xml"), kRoutes);
    EXPECT_EQ(read_file(tmp_.path() / "net.net.xml"), read_file(kGridNet));
  }

  std::vector<std::string> base() const { return {"run", "-c", "s.sumocfg", "--end", "5"}; }

  test::TempDir tmp_{"lpsim_out_paths"};
};

TEST_F(CliOutputPathsTest, DistinctOutputsRun) {
  auto args = base();
  args.insert(args.end(), {"--tripinfo-output", "trips.xml", "--summary-output", "sum.xml"});
  const auto r = run(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(tmp_.path() / "trips.xml"));
  EXPECT_TRUE(fs::exists(tmp_.path() / "sum.xml"));
}

TEST_F(CliOutputPathsTest, OutputOnTheRouteFileIsRefusedInAnySpelling) {
  ASSERT_EQ(::symlink("r.rou.xml", (tmp_.path() / "link.xml").c_str()), 0);
  fs::create_hard_link(tmp_.path() / "r.rou.xml", tmp_.path() / "hard.xml");
  for (const std::string& spelling :
       std::vector<std::string>{"r.rou.xml", "./r.rou.xml", "sub/../r.rou.xml", "link.xml", "hard.xml",
                                (tmp_.path() / "r.rou.xml").string()}) {
    SCOPED_TRACE(spelling);
    auto args = base();
    args.insert(args.end(), {"--tripinfo-output", spelling});
    expect_refused(run(args),
                   {"--tripinfo-output", "'" + spelling + "'", "--route-files", "overwrite an input"});
  }
}

TEST_F(CliOutputPathsTest, OutputOnNetCfgOrAddFileIsRefused) {
  tmp_.write("a.add.xml", "<additional>\n</additional>\n");
  const std::string add = read_file(tmp_.path() / "a.add.xml");
  const std::string cfg = read_file(tmp_.path() / "s.sumocfg");
  auto args = base();
  args.insert(args.end(), {"--fcd-output", "./net.net.xml"});
  expect_refused(run(args), {"--fcd-output", "--net-file"});
  args = base();
  args.insert(args.end(), {"--summary-output", "s.sumocfg"});
  expect_refused(run(args), {"--summary-output", "configuration-file"});
  EXPECT_EQ(read_file(tmp_.path() / "s.sumocfg"), cfg);
  args = base();
  args.insert(args.end(), {"-a", "a.add.xml", "--edgedata-output", "a.add.xml"});
  expect_refused(run(args), {"--edgedata-output", "--additional-files"});
  EXPECT_EQ(read_file(tmp_.path() / "a.add.xml"), add);
}

TEST_F(CliOutputPathsTest, TwoOutputsOnOneFileAreRefusedBeforeEitherIsWritten) {
  auto args = base();
  args.insert(args.end(), {"--fcd-output", "out.xml", "--tripinfo-output", "sub/../out.xml"});
  expect_refused(run(args), {"--tripinfo-output", "--fcd-output", "two outputs"});
  EXPECT_FALSE(fs::exists(tmp_.path() / "out.xml"));
}

TEST_F(CliOutputPathsTest, AddFileEdgeDataOnAnInputOrAnOutputIsRefusedAtItsLine) {
  tmp_.write("sub/e.add.xml",
             "<additional>\n\n    <edgeData id=\"ed\" file=\"../r.rou.xml\"/>\n</additional>\n");
  auto args = base();
  args.insert(args.end(), {"-a", "sub/e.add.xml"});
  const auto r = run(args);
  expect_refused(r, {"sub/e.add.xml:3", "<edgeData id=\"ed\">", "--route-files"});

  tmp_.write("sub/l.add.xml",
             "<additional>\n    <laneData id=\"ld\" file=\"../lanes.xml\"/>\n</additional>\n");
  args = base();
  args.insert(args.end(), {"-a", "sub/l.add.xml", "--lanedata-output", "lanes.xml"});
  expect_refused(run(args), {"sub/l.add.xml:2", "<laneData id=\"ld\">", "--lanedata-output"});
  EXPECT_FALSE(fs::exists(tmp_.path() / "lanes.xml"));
}

TEST_F(CliOutputPathsTest, ConvertOutputOnAnInputIsRefused) {
  expect_refused(run({"convert", "-c", "s.sumocfg", "-o", "./r.rou.xml"}), {"-o", "--route-files"});
  expect_refused(run({"convert", "-n", "net.net.xml", "-o", "sub/../net.net.xml"}), {"-o", "--net-file"});
}

TEST_F(CliOutputPathsTest, OutputOnTheSnapshotOrACsvInputIsRefused) {
  ASSERT_EQ(run({"convert", "-c", "s.sumocfg", "-o", "s.lpsim"}).exit_code, 0);
  const std::string snapshot = read_file(tmp_.path() / "s.lpsim");
  expect_refused(run({"run", "s.lpsim", "--tripinfo-output", "./s.lpsim"}),
                 {"--tripinfo-output", "snapshot"});
  EXPECT_EQ(read_file(tmp_.path() / "s.lpsim"), snapshot);

  tmp_.write("od.csv", read_file(kCsvDir + "/od.csv"));
  const auto r = run({"run", "--lpsim-nodes", kCsvDir + "/nodes.csv", "--lpsim-edges", kCsvDir + "/edges.csv",
                      "--lpsim-od", "od.csv", "--end", "5", "--summary-output", "od.csv"});
  expect_refused(r, {"--summary-output", "--lpsim-od"});
  EXPECT_EQ(read_file(tmp_.path() / "od.csv"), read_file(kCsvDir + "/od.csv"));
}

}  // namespace
}  // namespace lpsim

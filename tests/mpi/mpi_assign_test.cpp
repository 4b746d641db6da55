// `mpirun -n K lpsim assign ... --parts K` (label mpi): each iteration simulated with one part per rank gives
// the routes, the alternatives and the iteration lines (but for CPU seconds) of the assignment in one
// process; rank 0 alone prints and writes. A rank count other than the part count is bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "mpi/mpi_job.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

using test::have_mpirun;

std::string scenario_file(const std::string& name, const std::string& file) {
  return (fs::path(LPSIM_SOURCE_DIR) / "scenarios" / name / file).string();
}

test::CliResult mpirun_lpsim(const fs::path& dir, int ranks, const std::vector<std::string>& args) {
  std::vector<std::string> all{"-n", std::to_string(ranks), "--allow-run-as-root", "--oversubscribe",
                               LPSIM_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  return test::run_program(dir, {LPSIM_MPIEXEC}, all);
}

// Each iteration line's iteration, gap, mean trip time, finished trips and teleports (the CPU seconds
// differ from run to run).
std::vector<std::string> iteration_lines(const std::string& out) {
  std::vector<std::string> lines;
  for (const std::string& text : test::lines_of(out)) {
    std::istringstream in(text);
    std::string iteration, gap, mean, finished, teleports;
    if (in >> iteration >> gap >> mean >> finished >> teleports && iteration != "iteration")
      lines.push_back(iteration + " " + gap + " " + mean + " " + finished + " " + teleports);
  }
  return lines;
}

struct Case {
  std::string name;
  std::vector<std::string> args;
};

std::vector<Case> cases() {
  return {{"reroute_block",
           {"assign", "-n", scenario_file("reroute_block", "reroute_block.net.xml"), "-r",
            scenario_file("reroute_block", "reroute_block.rou.xml"), "--iterations", "5", "--aggregation",
            "60", "--time-to-teleport", "-1", "--threads", "1"}},
          {"grid_tls",
           {"assign", "-c", scenario_file("grid_tls", "grid_tls.sumocfg"), "--iterations", "3", "--threads",
            "1"}}};
}

TEST(MpiAssignTest, RanksAssignAsOneProcess) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_assign");
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> one = c.args;
    one.insert(one.end(), {"-o", c.name + "_one.rou.xml"});
    const test::CliResult r1 = test::run_lpsim(tmp.path(), one);
    ASSERT_EQ(r1.exit_code, 0) << r1.err;
    const std::vector<std::string> lines = iteration_lines(r1.out);
    ASSERT_GE(lines.size(), 3u) << r1.out;
    for (const int ranks : {2, 3}) {
      const std::string out = c.name + "_" + std::to_string(ranks) + ".rou.xml";
      std::vector<std::string> args = c.args;
      args.insert(args.end(), {"--parts", std::to_string(ranks), "-o", out});
      const test::CliResult r = mpirun_lpsim(tmp.path(), ranks, args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(iteration_lines(r.out), lines) << r.out;  // printed once, by rank 0
      EXPECT_TRUE(test::read_file(tmp.path() / out) ==
                  test::read_file(tmp.path() / (c.name + "_one.rou.xml")))
          << ranks << " ranks: routes differ";
      const std::string alt = c.name + "_" + std::to_string(ranks) + ".rou.alt.xml";
      EXPECT_TRUE(test::read_file(tmp.path() / alt) ==
                  test::read_file(tmp.path() / (c.name + "_one.rou.alt.xml")))
          << ranks << " ranks: alternatives differ";
    }
  }
}

TEST(MpiAssignTest, PartsOtherThanRanksIsBadInput) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_assign_bad");
  std::vector<std::string> args = cases()[1].args;
  args.insert(args.end(), {"--parts", "3", "-o", "x.rou.xml"});
  const test::CliResult r = mpirun_lpsim(tmp.path(), 2, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("mpirun -n 2 runs one part per rank: give --parts 2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp.path() / "x.rou.xml"));
}

}  // namespace
}  // namespace lpsim

// `mpirun -n K lpsim run ... --parts K` (label mpi): one part per rank writes the outputs of the run in one
// part byte for byte, its emissions edgeData and laneData too; a rank count other than the part count is bad
// input; a rank killed mid-run ends the job with a non-zero status, never a hang. As root, OpenMPI needs
// --allow-run-as-root; --oversubscribe lets 4 ranks share 2 cores.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "mpi/mpi_job.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

using test::have_mpirun;
using test::scenario;

std::vector<std::string> output_args() {
  return {"--tripinfo-output", "trip.xml",         "--fcd-output", "fcd.xml",      "--edgedata-output",
          "edge.xml",          "--summary-output", "summary.xml",  "--no-step-log"};
}

struct Outputs {
  std::string trip, fcd, edge, summary;
};

Outputs read_outputs(const fs::path& dir) {
  static const std::regex duration(" duration=\"[^\"]*\"");
  return Outputs{test::read_file(dir / "trip.xml"), test::read_file(dir / "fcd.xml"),
                 test::read_file(dir / "edge.xml"),
                 std::regex_replace(test::read_file(dir / "summary.xml"), duration, "")};
}

test::CliResult mpirun_lpsim(const fs::path& dir, int ranks, std::vector<std::string> args) {
  std::vector<std::string> all{"-n", std::to_string(ranks), "--allow-run-as-root", "--oversubscribe",
                               LPSIM_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  return test::run_program(dir, {LPSIM_MPIEXEC}, all);
}

TEST(MpiPartitionedRunTest, RanksWriteTheOutputsOfOnePart) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_run");
  for (const std::string name : {"grid_tls", "actuated_cross"}) {
    const fs::path one = tmp.path() / (name + "_1");
    fs::create_directories(one);
    std::vector<std::string> args{"run", scenario(name)};
    for (const auto& a : output_args()) args.push_back(a);
    const test::CliResult r1 = test::run_lpsim(one, args);
    ASSERT_EQ(r1.exit_code, 0) << r1.err;
    const Outputs ref = read_outputs(one);
    ASSERT_GT(ref.trip.size(), 10000u);
    for (const int ranks : {2, 4}) {
      const fs::path dir = tmp.path() / (name + "_" + std::to_string(ranks));
      fs::create_directories(dir);
      std::vector<std::string> part_args = args;
      part_args.push_back("--parts");
      part_args.push_back(std::to_string(ranks));
      const test::CliResult r = mpirun_lpsim(dir, ranks, part_args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const Outputs got = read_outputs(dir);
      EXPECT_TRUE(got.trip == ref.trip) << name << " " << ranks << " ranks: tripinfo differs";
      EXPECT_TRUE(got.fcd == ref.fcd) << name << " " << ranks << " ranks: FCD differs";
      EXPECT_TRUE(got.edge == ref.edge) << name << " " << ranks << " ranks: edgeData differs";
      EXPECT_TRUE(got.summary == ref.summary) << name << " " << ranks << " ranks: summary differs";
      // Part 0 reports every part, and vehicles crossed the cuts.
      EXPECT_NE(r.out.find("Part " + std::to_string(ranks - 1) + ": vehicle updates"), std::string::npos)
          << r.out;
      static const std::regex migrations("migrations out ([0-9]+)");
      uint64_t crossed = 0;
      for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), migrations);
           it != std::sregex_iterator(); ++it)
        crossed += std::stoull((*it)[1]);
      EXPECT_GT(crossed, 100u) << r.out;
    }
  }
}

// The per-lane emission sums of every rank reach rank 0 as the traffic counters do.
TEST(MpiPartitionedRunTest, RanksWriteTheEmissionsOfOnePart) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_emissions");
  auto run_in = [&](const std::string& tag, int ranks) {
    const fs::path dir = tmp.path() / tag;
    fs::create_directories(dir);
    std::ofstream(dir / "em.add.xml")
        << "<additional>\n<edgeData id=\"e\" type=\"emissions\" file=\"edges.xml\" period=\"600\" "
           "withInternal=\"true\"/>\n<laneData id=\"l\" type=\"emissions\" file=\"lanes.xml\"/>\n"
           "</additional>\n";
    std::vector<std::string> args{"run",  scenario("grid_tls"), "-a", "em.add.xml", "--end",
                                  "1200", "--no-step-log"};
    if (ranks > 1) args.insert(args.end(), {"--parts", std::to_string(ranks)});
    const test::CliResult r = ranks > 1 ? mpirun_lpsim(dir, ranks, args) : test::run_lpsim(dir, args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::read_file(dir / "edges.xml") + test::read_file(dir / "lanes.xml");
  };
  const std::string one = run_in("one", 1);
  EXPECT_NE(one.find("CO2_perVeh"), std::string::npos);
  EXPECT_TRUE(run_in("three", 3) == one) << "3 ranks: emissions differ";
}

TEST(MpiPartitionedRunTest, PartsOtherThanRanksIsBadInput) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_parts");
  const test::CliResult r =
      mpirun_lpsim(tmp.path(), 2, {"run", scenario("grid_tls"), "--parts", "3", "--end", "10"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("mpirun -n 2 runs one part per rank: give --parts 2"), std::string::npos) << r.err;
}

// Bad input every rank meets while loading is printed once (by rank 0), and the ranks end together with
// status 2, none aborting the job: no MPI_ABORT report. With mpirun's --quiet nothing else is printed.
// Before, every rank printed the error and each called MPI_Abort.
TEST(MpiPartitionedRunTest, BadInputIsPrintedOnceAndEndsEveryRankWithoutAnAbort) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_bad_input");
  const std::string routes =
      "<routes>\n    <vehicle id=\"v\" type=\"nope\" depart=\"0\"><route "
      "edges=\"A0B0\"/></vehicle>\n</routes>\n";
  tmp.write("bad.rou.xml", routes);
  const std::string net = std::string(LPSIM_SOURCE_DIR) + "/scenarios/grid_tls/grid_tls.net.xml";
  for (const int ranks : {2, 3}) {
    const test::CliResult r =
        test::run_program(tmp.path(), {LPSIM_MPIEXEC},
                          {"--quiet", "-n", std::to_string(ranks), "--allow-run-as-root", "--oversubscribe",
                           LPSIM_BINARY, "run", "-n", net, "-r", "bad.rou.xml", "--parts",
                           std::to_string(ranks), "--tripinfo-output", "t.xml", "--no-step-log"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "lpsim: error: bad.rou.xml:2: unknown vType 'nope' for vehicle 'v'\n")
        << ranks << " ranks";
    EXPECT_FALSE(fs::exists(tmp.path() / "t.xml"));
  }
}

TEST(MpiPartitionedRunTest, ARankKilledMidRunEndsTheJob) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_kill");
  // Rank 1 of this job (found by its MPI rank in its environment and its working directory, this test's:
  // other tests run lpsim at the same time) is killed once the run is under way: rank 0 has written the first
  // steps of the FCD.
  std::string cmd =
      "cd " + test::shell_quote(tmp.path().string()) + " && (" + test::shell_quote(LPSIM_MPIEXEC) +
      " -n 2 --allow-run-as-root --oversubscribe " + test::shell_quote(LPSIM_BINARY) + " run " +
      test::shell_quote(scenario("grid_tls")) +
      " --parts 2 --fcd-output fcd.xml --no-step-log > out.txt 2> err.txt & job=$!; "
      "for i in $(seq 2000); do [ $(stat -c %s fcd.xml 2>/dev/null || echo 0) -gt 20000 ] && break; "
      "sleep 0.005; done; for p in $(pgrep -x lpsim); do "
      "[ \"$(readlink /proc/$p/cwd)\" = \"$PWD\" ] && "
      "grep -qz '^OMPI_COMM_WORLD_RANK=1$' /proc/$p/environ && kill -9 $p; done; "
      "wait $job; echo $? > status.txt)";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string status = test::read_file(tmp.path() / "status.txt");
  EXPECT_NE(std::stoi(status), 0) << test::read_file(tmp.path() / "err.txt");
  // Killed before the end: the FCD stops short of the last step.
  EXPECT_EQ(test::read_file(tmp.path() / "fcd.xml").find("time=\"3599.00\""), std::string::npos);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(60));
}

// Only `run` and `assign` are split over ranks: any other command under mpirun would run once per rank,
// writing the same files. Refused once (by rank 0), exit 2, nothing written.
TEST(MpiPartitionedRunTest, OtherCommandsUnderMpirunAreRefusedOnce) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_other");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"info", scenario("grid_tls")},
        std::vector<std::string>{"convert", scenario("grid_tls"), "-o", "g.lpsim"},
        std::vector<std::string>{"partition", scenario("grid_tls"), "--parts", "2", "-o", "p.txt"}}) {
    const test::CliResult r = mpirun_lpsim(tmp.path(), 2, args);
    EXPECT_NE(r.exit_code, 0) << args[0];
    const std::string line = "lpsim: error: under mpirun only 'lpsim run' and 'lpsim assign' run";
    const size_t at = r.err.find(line);
    EXPECT_NE(at, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(line, at + 1), std::string::npos) << "printed twice: " << r.err;
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "g.lpsim"));
  EXPECT_FALSE(fs::exists(tmp.path() / "p.txt"));
}

// A rank that stops without dying (SIGSTOP, a debugger, a swapped-out node) ends the job after
// --part-timeout with one error line naming it, and rank 0 waits for it without spinning a core (it polled
// MPI every 20 us before: 1.4 cores).
TEST(MpiPartitionedRunTest, AStoppedRankEndsTheJobAfterThePartTimeoutWithoutSpinning) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_stop");
  std::string cmd =
      "cd " + test::shell_quote(tmp.path().string()) +
      " && mine() { for p in $(pgrep -x lpsim); do "
      "[ \"$(readlink /proc/$p/cwd)\" = \"$PWD\" ] && grep -qz \"^OMPI_COMM_WORLD_RANK=$1$\" "
      "/proc/$p/environ "
      "&& echo $p; done; }; (" +
      test::shell_quote(LPSIM_MPIEXEC) + " -n 2 --allow-run-as-root --oversubscribe " +
      test::shell_quote(LPSIM_BINARY) + " run " + test::shell_quote(scenario("grid_tls")) +
      " --parts 2 --end 1000000 --part-timeout 4 --fcd-output fcd.xml --no-step-log > out.txt 2> err.txt & "
      "job=$!; for i in $(seq 2000); do [ $(stat -c %s fcd.xml 2>/dev/null || echo 0) -gt 20000 ] && break; "
      "sleep 0.005; done; r0=$(mine 0); r1=$(mine 1); kill -STOP $r1; sleep 1; "
      "a=$(awk '{print $14+$15}' /proc/$r0/stat); sleep 2; b=$(awk '{print $14+$15}' /proc/$r0/stat); "
      "echo $((b-a)) > ticks.txt; wait $job; echo $? > status.txt; kill -9 $r1 2>/dev/null; true)";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string err = test::read_file(tmp.path() / "err.txt");
  EXPECT_NE(std::stoi(test::read_file(tmp.path() / "status.txt")), 0) << err;
  // Receiving from it, or sending to it (a large buffer waits for the receiver).
  EXPECT_TRUE(
      std::regex_search(err, std::regex("lpsim: error: rank 0: (receiving from|sending to) rank 1 in round")))
      << err;
  EXPECT_NE(err.find("took more than 4 s: has it stopped?"), std::string::npos) << err;
  // Clock ticks (1/100 s) rank 0 spent in 2 s of waiting: a spinning rank spends about 200.
  EXPECT_LT(std::stoi(test::read_file(tmp.path() / "ticks.txt")), 40);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(60));
}

}  // namespace
}  // namespace lpsim

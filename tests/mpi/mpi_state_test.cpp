// Checkpoints of `mpirun -n 2 lpsim run ... --parts 2` (label mpi): rank 0 writes one state file holding
// every rank's part, a job of as many ranks resumed from it writes every output byte for byte as the run
// never stopped (the run in one part), whether the state was saved at a time or on the signal a batch system
// sends every rank when it pre-empts the job, and a job of another part count is refused with one line,
// exit 2.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
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

// Bundled scenario `name`'s files copied into `dir` (the outputs its add-file names land there).
void copy_scenario(const std::string& name, const fs::path& dir) {
  fs::create_directories(dir);
  for (const auto& f : fs::directory_iterator(std::string(LPSIM_SOURCE_DIR) + "/scenarios/" + name))
    fs::copy_file(f.path(), dir / f.path().filename(), fs::copy_options::overwrite_existing);
}

const std::vector<std::string> kOutputs{"trip.xml", "fcd.xml", "summary.xml", "edge.xml", "stat.xml"};

std::string output_args() {
  return " --tripinfo-output trip.xml --tripinfo-output.write-unfinished --fcd-output fcd.xml "
         "--summary-output "
         "summary.xml --edgedata-output edge.xml --statistic-output stat.xml --no-step-log --no-warnings";
}

std::string mpirun_command(int ranks, const std::string& args) {
  return test::shell_quote(LPSIM_MPIEXEC) + " -n " + std::to_string(ranks) +
         " --allow-run-as-root --oversubscribe --mca odls_base_sigkill_timeout 1 " +
         test::shell_quote(LPSIM_BINARY) + " run " + args;
}

// Runs `command` in `dir`; its exit status.
int run_in(const fs::path& dir, const std::string& command) {
  const std::string cmd = "cd " + test::shell_quote(dir.string()) + " && (" + command +
                          ") > out.txt 2> err.txt; echo $? > status.txt";
  if (std::system(cmd.c_str()) != 0) return -1;
  return std::stoi(test::read_file(dir / "status.txt"));
}

void expect_same_outputs(const fs::path& a, const fs::path& b, const std::string& what) {
  for (const std::string& f : kOutputs) {
    ASSERT_TRUE(fs::exists(b / f)) << f;
    EXPECT_TRUE(test::read_file(a / f) == test::read_file(b / f)) << f << " differs " << what;
  }
}

TEST(MpiStateTest, AJobResumedFromTheStateItsRanksSavedWritesTheOutputsOfTheRunNeverStopped) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_state");
  // grid_tls's signals and right of way across the cut; reroute_block's rerouting device, whose routes and
  // samples every part keeps.
  for (const auto& [name, t] :
       {std::pair<std::string, std::string>{"grid_tls", "613"}, {"reroute_block", "311"}}) {
    const fs::path whole = tmp.path() / (name + "_whole"), saved = tmp.path() / (name + "_saved");
    copy_scenario(name, whole);
    copy_scenario(name, saved);
    const std::string args = test::shell_quote(name + ".sumocfg") + output_args();
    ASSERT_EQ(run_in(whole, test::shell_quote(LPSIM_BINARY) + " run " + args), 0)
        << test::read_file(whole / "err.txt");
    ASSERT_EQ(run_in(saved, mpirun_command(2, args + " --parts 2 --save-state.times " + t)), 0)
        << test::read_file(saved / "err.txt");
    const std::string state = "state_" + t + ".00.lpstate";
    ASSERT_TRUE(fs::exists(saved / state)) << test::read_file(saved / "err.txt");
    expect_same_outputs(whole, saved, "after saving in " + name);

    // Resumed in other parts (the state re-cut for them: 3 ranks, one process) and in its own; each run
    // continues the outputs from where the saving run had written them at the save.
    const std::string resume = args + " --load-state " + state;
    ASSERT_EQ(run_in(saved, mpirun_command(3, resume + " --parts 3")), 0)
        << test::read_file(saved / "err.txt");
    expect_same_outputs(whole, saved, "after resuming " + name + " at " + t + " in 3 ranks");
    ASSERT_EQ(run_in(saved, test::shell_quote(LPSIM_BINARY) + " run " + resume), 0)
        << test::read_file(saved / "err.txt");
    expect_same_outputs(whole, saved, "after resuming " + name + " at " + t + " in one part");
    ASSERT_EQ(run_in(saved, mpirun_command(2, resume + " --parts 2")), 0)
        << test::read_file(saved / "err.txt");
    EXPECT_NE(test::read_file(saved / "err.txt").find("resumed from " + state + " at time " + t + ".00"),
              std::string::npos);
    expect_same_outputs(whole, saved, "after resuming " + name + " at " + t + " in its 2 ranks");
  }
}

// The batch system's SIGTERM reaches every rank at once; --save-state.on-signal saves the state of the step
// they all stop at, and the job started again from it ends as the job never stopped.
TEST(MpiStateTest, AJobPreemptedBySigtermResumesFromTheStateItSavedOnTheSignal) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir tmp("lpsim_mpi_state_signal");
  tmp.write("long.rou.xml", test::kEndlessFlow);
  const fs::path whole = tmp.path() / "whole", stopped = tmp.path() / "stopped";
  fs::create_directory(whole);
  fs::create_directory(stopped);
  const std::string args =
      test::shell_quote(scenario("grid_tls")) + " -a ../long.rou.xml --end 60000 --parts 2" + output_args();
  ASSERT_EQ(run_in(whole, mpirun_command(2, args)), 0) << test::read_file(whole / "err.txt");

  const std::string cmd = test::signalled_job(stopped, mpirun_command(2, args + " --save-state.on-signal"),
                                              "for p in $(mine); do kill -TERM $p; done");
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string err = test::read_file(stopped / "err.txt");
  ASSERT_EQ(std::stoi(test::read_file(stopped / "status.txt")), 128 + SIGTERM) << err;
  std::smatch saved;
  ASSERT_TRUE(std::regex_search(err, saved, std::regex(R"(lpsim: state saved to (state_[0-9.]+\.lpstate))")))
      << err;

  ASSERT_EQ(run_in(stopped, mpirun_command(2, args + " --load-state " + saved[1].str())), 0)
      << test::read_file(stopped / "err.txt");
  expect_same_outputs(whole, stopped, "after resuming from " + saved[1].str());
}

}  // namespace
}  // namespace lpsim

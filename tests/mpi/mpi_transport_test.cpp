// The MPI transport under the real mpirun (label mpi): rounds between 2 and 3 ranks arrive intact and in
// order; a rank that stalls, dies or runs another build ends the job with an error, never a hang. As root,
// OpenMPI needs --allow-run-as-root; --oversubscribe lets 3 ranks share 2 cores.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

test::CliResult mpirun(const test::TempDir& dir, int ranks, const std::vector<std::string>& args) {
  std::vector<std::string> all{"-n", std::to_string(ranks), "--allow-run-as-root", "--oversubscribe",
                               LPSIM_MPI_PROBE};
  all.insert(all.end(), args.begin(), args.end());
  return test::run_program(dir.path(), {LPSIM_MPIEXEC}, all);
}

bool have_mpirun() { return std::filesystem::exists(LPSIM_MPIEXEC); }

TEST(MpiTransportTest, RoundsArriveIntactBetweenRanks) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir dir("lpsim_mpi_ring");
  for (int ranks : {2, 3}) {
    const test::CliResult r = mpirun(dir, ranks, {"ring", "200"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("ok " + std::to_string(ranks) + " ranks, 200 rounds"), std::string::npos)
        << r.out << r.err;
  }
}

TEST(MpiTransportTest, AStalledRankIsAnErrorNotAHang) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir dir("lpsim_mpi_stall");
  const auto t0 = std::chrono::steady_clock::now();
  const test::CliResult r = mpirun(dir, 2, {"stall"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("rank 0: receiving from rank 1 in round 'ring' (#1) took more than"),
            std::string::npos)
      << r.err;
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(25));  // the stall lasts 30 s
}

TEST(MpiTransportTest, ADeadRankEndsTheJob) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir dir("lpsim_mpi_die");
  const test::CliResult r = mpirun(dir, 2, {"die"});
  EXPECT_NE(r.exit_code, 0) << r.out << r.err;
}

TEST(MpiTransportTest, RanksOfDifferentBuildsRefuseToRun) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  test::TempDir dir("lpsim_mpi_mismatch");
  const test::CliResult r = mpirun(dir, 2, {"mismatch"});
  EXPECT_NE(r.exit_code, 0);
  // Whichever rank finds the mismatch first ends the job with its own view of it.
  EXPECT_NE(r.err.find("build 'other-build'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("every rank must run the same build"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lpsim

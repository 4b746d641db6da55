// A driver's commands between steps (engine/vehicle_commands.hpp) in a run split over MPI ranks (label mpi):
// `mpirun -n 2` of tests/mpi/mpi_commands_probe.cpp adds trips and removes vehicles at the same times as a
// run in one part in this process, and the two runs' accounts (command outcomes, FCD, trip records, counts)
// are the same text.
#include <gtest/gtest.h>

#include <string>

#include "app/simulation_options.hpp"
#include "converters/cli_options.hpp"
#include "mpi/mpi_job.hpp"
#include "temp_dir.hpp"
#include "unit/command_drive.hpp"

namespace lpsim {
namespace {

TEST(MpiCommandsTest, TwoRanksApplyTheCommandsAsOnePart) {
  if (!test::have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string cfg = test::scenario("grid_tls");
  const Scenario sc = load_scenario(parse_cli_options({"-c", cfg}));
  engine_test::CommandRun one;
  {
    Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
    engine_test::drive_removals(sim, sc, false, one);
  }
  ASSERT_TRUE(one.finished);
  test::TempDir tmp("lpsim_mpi_commands");
  const test::CliResult r =
      test::run_program(tmp.path(), {LPSIM_MPIEXEC},
                        {"-n", "2", "--allow-run-as-root", "--oversubscribe", LPSIM_MPI_COMMANDS_PROBE, cfg});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string expected = engine_test::command_run_text(one);
  EXPECT_NE(expected.find("outcome \n"), std::string::npos);
  EXPECT_TRUE(r.out == expected) << "the 2-rank run's account differs from one part's (" << r.out.size()
                                 << " against " << expected.size() << " bytes)";
}

}  // namespace
}  // namespace lpsim

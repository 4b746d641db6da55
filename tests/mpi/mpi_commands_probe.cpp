// A run of grid_tls with a driver's commands between steps (tests/unit/command_drive.hpp) as K parts, one per
// MPI rank, for tests/mpi/mpi_commands_test.cpp:
//   mpirun -n K lpsim_mpi_commands_probe SCENARIO.sumocfg
// Rank 0 prints the run's account (command_run_text) on stdout; an error is printed as "lpsim: error: ...",
// and ends the job with status 1.
#include <cstdio>
#include <exception>
#include <memory>

#include "app/part_launcher.hpp"
#include "app/simulation_options.hpp"
#include "converters/cli_options.hpp"
#include "transport/mpi/mpi_transport.hpp"
#include "unit/command_drive.hpp"

int main(int argc, char** argv) {
  lpsim::MpiSession session(&argc, &argv);
  try {
    if (argc != 2) throw std::runtime_error("usage: lpsim_mpi_commands_probe SCENARIO.sumocfg");
    const lpsim::Scenario sc = lpsim::load_scenario(lpsim::parse_cli_options({"-c", argv[1]}));
    const int parts = lpsim::MpiSession::world_size();
    const std::vector<int32_t> edge_part = lpsim::edge_parts_from_junctions(
        sc.network, lpsim::partition_junctions(lpsim::build_junction_graph(sc.network, sc.demand, 1.0), parts,
                                               lpsim::PartitionMethod::Metis, 2));
    const std::unique_ptr<lpsim::PartLauncher> launcher =
        lpsim::launch_parts(parts, sc, edge_part, parts, 60);
    const lpsim::SimulationOptions options = lpsim::simulation_options(sc.config);
    if (!launcher->leads()) {
      launcher->serve(sc.network, sc.demand, options);
      return 0;
    }
    lpsim::engine_test::CommandRun run;
    launcher->run_part0(sc.network, sc.demand, options, [&](const lpsim::SimulationOptions& o) {
      lpsim::Simulation sim(sc.network, sc.demand, o);
      lpsim::engine_test::drive_removals(sim, sc, false, run);
    });
    std::fputs(lpsim::engine_test::command_run_text(run).c_str(), stdout);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lpsim: error: %s\n", e.what());
    lpsim::MpiSession::abort_job(1);
  }
}

// `lpsim run`: load, simulate, write SUMO outputs, print a SUMO-like summary. SIGINT, SIGTERM and SIGHUP
// stop it at the end of the current step with every output closed well-formed (as SUMO does on Ctrl-C), one
// line on stderr and exit status 128 + the signal. Under mpirun every rank records the signal it gets and
// reports it to rank 0 with the step, so the job stops together however its ranks are signalled (mpirun
// itself passes SIGINT and SIGTERM on to every rank as SIGTERM).
#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "app/commands.hpp"
#include "app/device_select.hpp"
#include "app/drive_loop.hpp"
#include "app/error_report.hpp"
#include "app/interrupt.hpp"
#include "app/output_paths.hpp"
#include "app/part_launcher.hpp"
#include "app/partitioned_parts.hpp"
#include "app/progress_log.hpp"
#include "app/run.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "core/error.hpp"
#include "transport/mpi/mpi_transport.hpp"

namespace lpsim {

namespace {

// What `lpsim run` loads before any part runs: everything that can fail on bad input.
struct LoadedRun {
  ConfigSpec config;
  Scenario sc;
  SimulationOptions options;
  int32_t parts = 1;
  std::vector<int32_t> edge_part;
};

void load_run(const std::vector<std::string>& args, int ranks, LoadedRun* l) {
  l->sc = scenario_from_args(args, &l->config);
  refuse_overwrites(l->sc, CliCommand::Run);
  const ConfigSpec& config = l->config;
  l->options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  l->options.backend = device.backend;
  l->options.lane_counters = Run::needs_lane_counters(l->sc, config.outputs);
  l->options.emission_sums = Run::needs_emission_sums(l->sc, config.outputs);
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());
  l->edge_part = run_edge_parts(config, l->sc, ranks, &l->parts);
  require_one_part_per_rank(ranks, l->parts);
  if (l->parts > 1 && !config.jam_report.empty())
    throw InputError("--jam-report reads one part's vehicles: leave out --parts and --partition-file");
}

}  // namespace

int command_run(const std::vector<std::string>& args) {
  // Loading writes nothing, so a signal until the Run is built may end the process as usual. Under mpirun
  // every rank loads the scenario, and all of them learn whether any failed before a part starts: an error
  // is printed once, by the lowest rank that met it, and every rank ends with its status.
  const int ranks = MpiSession::world_size();
  LoadedRun loaded;
  load_on_every_rank(ranks, [&] { load_run(args, ranks, &loaded); });
  const ConfigSpec& config = loaded.config;
  Scenario& sc = loaded.sc;
  SimulationOptions& options = loaded.options;
  const int32_t parts = loaded.parts;
  const std::vector<int32_t>& edge_part = loaded.edge_part;

  // From the guard on a signal is recorded, not fatal: the Run's constructor creates the output files, and
  // the loop below stops at the first step boundary after a signal (to any rank), so that finish() closes
  // them well-formed while the other ranks still serve it. Ranks install it before they build their tables,
  // so that none dies while the others wait for it; a single process before it starts its parts.
  const InterruptGuard interrupt;
  // A partitioned run: under mpirun one part per rank, part 0 (rank 0) running the outputs and the others
  // serving it; else parts 1..K-1 on threads of this process, started before part 0's Run, as they build
  // alongside it.
  const std::unique_ptr<PartLauncher> launcher =
      launch_parts(ranks, sc, edge_part, parts, config.part_timeout);
  if (launcher->ranks() != nullptr) {
    if (!launcher->leads()) release_name_indexes(sc.network);
    // What loading and partitioning freed goes back to the system before the part's tables are allocated:
    // a rank's peak is its tables on top of what it loaded.
    malloc_trim(0);
    options.pending_signal = [&interrupt] { return interrupt.received(); };
  }
  if (!launcher->leads()) {
    launcher->serve(sc.network, std::move(sc.demand), options);
    const int signal = interrupt.received();
    return signal != 0 ? 128 + signal : 0;
  }

  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  const double load_seconds = sc.load_seconds;
  ProgressLog progress(stderr, isatty(fileno(stderr)) != 0, config.no_step_log, config.progress_interval,
                       config.end);
  int signal = 0;
  launcher->run_part0(sc.network, sc.demand, options, [&](const SimulationOptions& part0_options) {
    Run run(std::move(sc), config, part0_options);
    auto signalled = [&] {
      const int own = interrupt.received();
      return own != 0 ? own : run.simulation().link().signal();
    };
    drive_to_end(run, run.simulation(), progress, signalled);
    if (config.save_state_on_signal && signalled() != 0)
      std::fprintf(stderr, "lpsim: state saved to %s\n", run.save_state_now().c_str());
    run.finish();
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    progress.end_line();
    signal = signalled();
    report_run_end(run, wall, load_seconds, signal);
  });
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace lpsim

// The `lpsim` command: dispatches sub-commands, prints errors as one line, and maps them to exit codes
// (2: bad input or usage, 1: internal failure).
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/error_report.hpp"
#include "app/interrupt.hpp"
#include "converters/cli_options.hpp"
#include "core/error.hpp"
#if LPSIM_COSIM
#include "sumo_bridge/cosim_command.hpp"
#endif
#include "transport/mpi/mpi_transport.hpp"

namespace {

constexpr const char* kUsage = R"(usage: lpsim <command> [options]

commands:
  info     load a scenario and report what it holds
           lpsim info -c scenario.sumocfg | lpsim info -n net.xml -r routes.xml [-a add.xml]
           lpsim info --lpsim-nodes nodes.csv --lpsim-edges edges.csv [--lpsim-od od.csv]
           lpsim info scenario.lpsim (a snapshot written by convert)
  convert  load a scenario and write a binary snapshot that later commands load much faster
           lpsim convert -c scenario.sumocfg -o scenario.lpsim
  run      simulate and write SUMO outputs
           lpsim run -c scenario.sumocfg [--threads N] [--end T] [--fcd-output f.xml] [--tripinfo-output f.xml]
           [--edgedata-output f.xml] [--summary-output f.xml] [--device cpu|auto|gpu]
  cosim    simulate with SUMO driving a corridor (the edges of a sumo-gui selection), LPSim the rest
           lpsim cosim -c scenario.sumocfg --corridor corridor.txt [outputs as for run]
           [--sumo-binary sumo|sumo-gui (over TraCI; default: libsumo in process)] [--sumo-args "..."]
  partition  split the network into K parts (METIS, Leiden + k-means, random) for a partitioned run
           lpsim partition -c scenario.sumocfg --parts 4 -o parts.txt [--map parts.png]
  assign   dynamic user assignment (duaIterate.py's iterations of routing and simulation, Gawron's model)
           lpsim assign -c scenario.sumocfg -o assigned.rou.xml [--iterations 50] [--gap 0.01]
  version  print the version

options follow SUMO's names; `lpsim <command> --help` lists those a command takes.
)";

// Runs a command: its exit status, errors printed as one line. `job_ended` is set when the ranks of an MPI
// job agreed to end together (none waits for another).
int dispatch(const std::string& command, const std::vector<std::string>& args, bool* job_ended) {
  try {
    if (command == "info") return lpsim::command_info(args);
    if (command == "convert") return lpsim::command_convert(args);
    if (command == "run") return lpsim::command_run(args);
    if (command == "partition") return lpsim::command_partition(args);
    if (command == "assign") return lpsim::command_assign(args);
    if (command == "cosim") {
#if LPSIM_COSIM
      return lpsim::command_cosim(args);
#else
      throw lpsim::InputError("this lpsim was built without the co-simulation (cmake -DLPSIM_COSIM=OFF)");
#endif
    }
    if (command == "version" || command == "--version") {
      std::printf("lpsim %s\n", LPSIM_VERSION);
      return 0;
    }
    std::fprintf(stderr, "lpsim: error: unknown command '%s'\n%s", command.c_str(), kUsage);
    return lpsim::kExitBadInput;
  } catch (const lpsim::JobEnded& e) {
    *job_ended = true;
    if (e.cause) lpsim::report_error(e.cause);
    return e.code;
  } catch (...) {
    return lpsim::report_error(std::current_exception());
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun every rank runs one part of a partitioned run: MPI is up for the whole process.
  std::unique_ptr<lpsim::MpiSession> mpi;
  if (lpsim::MpiSession::launched_by_mpirun()) mpi = std::make_unique<lpsim::MpiSession>(&argc, &argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? lpsim::kExitBadInput : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  // -h, --help or -? among the command's options, as SUMO takes it (not as an option's value).
  if (lpsim::help_requested(args)) {
    const std::string help = lpsim::command_help(command);
    if (!help.empty()) {
      std::fputs(help.c_str(), stdout);
      return 0;
    }
  }
  // Only a run and an assignment are split over ranks: any other command would run once per rank, writing
  // the same files.
  if (mpi && lpsim::MpiSession::world_size() > 1 && command != "run" && command != "assign") {
    if (lpsim::MpiSession::world_rank() == 0)
      std::fprintf(stderr,
                   "lpsim: error: under mpirun only 'lpsim run' and 'lpsim assign' run (one part per rank): "
                   "start 'lpsim %s' "
                   "without mpirun\n",
                   command.c_str());
    return lpsim::kExitBadInput;  // every rank alike: no rank waits for another
  }
  bool job_ended = false;
  const int code = dispatch(command, args, &job_ended);
  // A rank that failed while the others ran ends the job: they would wait for it until their rounds time
  // out. A signal stops every rank at the same step, and an error while loading every rank at once: they end
  // together, as MPI expects.
  if (code != 0 && !job_ended && !lpsim::interrupted_status(code) && mpi &&
      lpsim::MpiSession::world_size() > 1)
    lpsim::MpiSession::abort_job(code);
  return code;
}

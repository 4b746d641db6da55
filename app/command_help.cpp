// `lpsim <command> --help`: usage lines written here, the options listed from cli_options' own table.
#include <string>

#include "app/commands.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

namespace {

constexpr const char* kInfoUsage = R"(usage: lpsim info [options] [scenario.sumocfg | scenario.lpsim]
load a scenario and report what it holds
  lpsim info -c scenario.sumocfg | lpsim info -n net.xml -r routes.xml [-a add.xml]
  lpsim info --lpsim-nodes nodes.csv --lpsim-edges edges.csv [--lpsim-od od.csv]
  lpsim info scenario.lpsim (a snapshot written by convert)
)";

constexpr const char* kConvertUsage = R"(usage: lpsim convert [options] -o scenario.lpsim
load a scenario and write a binary snapshot that later commands load much faster
  lpsim convert -c scenario.sumocfg -o scenario.lpsim
)";

constexpr const char* kRunUsage = R"(usage: lpsim run [options] [scenario.sumocfg | scenario.lpsim]
simulate and write SUMO outputs
  lpsim run -c scenario.sumocfg [--end T] [--fcd-output f.xml] [--tripinfo-output f.xml]
)";

constexpr const char* kCosimUsage = R"(usage: lpsim cosim [options] --corridor corridor.txt [scenario.sumocfg]
simulate with SUMO driving the corridor's edges and LPSim the rest of the network, vehicles handed across
the boundary both ways; outputs as `run` (SUMO writes its side beside each, as sumo.<name>; the tripinfo
has one line per trip for both sides)
  lpsim cosim -c scenario.sumocfg --corridor corridor.txt [--tripinfo-output f.xml]
  lpsim cosim -c scenario.sumocfg --corridor corridor.txt --sumo-binary sumo-gui   (SUMO over TraCI)
)";

constexpr const char* kPartitionUsage = R"(usage: lpsim partition [options] --parts K -o parts.txt
split the network into K parts for a partitioned run: a part per junction, each road in the part of the
junction it leads to; weights from the demand (vehicle-steps per junction's roads, vehicles per road).
Prints a table per part; --map draws the parts.
  lpsim partition -c scenario.sumocfg --parts 4 [--partition-method metis|leiden|random] -o parts.txt
  lpsim partition -c scenario.sumocfg --partition-file parts.txt [--map parts.png]   (summarize a file)
)";

constexpr const char* kAssignUsage =
    R"(usage: lpsim assign [options] -o assigned.rou.xml [scenario.sumocfg | scenario.lpsim]
dynamic user assignment as SUMO's duaIterate.py runs it: each iteration routes every vehicle on the
travel times the last one measured (per --aggregation interval, time-dependent), chooses among its route
alternatives by Gawron's model, and simulates; prints per iteration the relative gap, the mean trip time,
teleports, the CPU time of routing and simulation and the wall time of simulation and iteration; writes
the final routes (-o) and their alternatives (<routeDistribution> per vehicle, .rou.alt.xml beside), which
sumo and lpsim run load
  lpsim assign -c scenario.sumocfg -o assigned.rou.xml [--iterations 50] [--gap 0.01]
  mpirun -n K lpsim assign ... --parts K   (each iteration simulated with one part per rank)
)";

constexpr const char* kTrailer = R"(
Options take SUMO's names and may also come from the .sumocfg (except -c, -o, --device,
--max-lane-map-gb, --progress-interval, --jam-report*, --parts, --partition-*, --map, --corridor,
--sumo-* and assign's, which are LPSim's own). Other SUMO options:
those that cannot change the results (verbose, log, gui-settings-file, ...) are ignored with a warning;
those that could (scale, mesosim, ...) are refused unless set to SUMO's default. No output may be the
same file as an input or another output.
)";

}  // namespace

std::string command_help(const std::string& command) {
  std::string usage;
  CliCommand c;
  if (command == "info") {
    usage = kInfoUsage;
    c = CliCommand::Info;
  } else if (command == "convert") {
    usage = kConvertUsage;
    c = CliCommand::Convert;
  } else if (command == "run") {
    usage = kRunUsage;
    c = CliCommand::Run;
  } else if (command == "cosim") {
    usage = kCosimUsage;
    c = CliCommand::Cosim;
  } else if (command == "assign") {
    usage = kAssignUsage;
    c = CliCommand::Assign;
  } else if (command == "partition") {
    usage = kPartitionUsage;
    c = CliCommand::Partition;
  } else {
    return "";
  }
  return usage + "\noptions:\n" + describe_options(c) + kTrailer;
}

}  // namespace lpsim

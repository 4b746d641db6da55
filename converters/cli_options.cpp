#include "converters/cli_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "converters/sumo_option_catalog.hpp"
#include "converters/sumocfg_reader.hpp"
#include "converters/xml_stream.hpp"
#include "core/partition_spec.hpp"

namespace lpsim {

namespace {

enum class Kind {
  Path,
  PathList,
  Time,
  TimeList,
  Bool,
  Integer,
  Number,
  Device,
  Name,
  Method,
  Algorithm,
  Text
};

// A checked value, handed to the option's store function.
struct Value {
  std::string text;
  std::vector<std::string> list;
  double seconds = 0;
  std::vector<double> times;
  double number = 0;
  long long integer = 0;
  bool flag = false;
  ComputeDevice device = ComputeDevice::Auto;
};

// StepLength: LPSim's clock counts milliseconds; ThreadCount: a team beyond this is a typo, and would exhaust
// the process limit before the run starts.
enum class Check { None, NonNegative, Positive, AtLeastOne, StepLength, ThreadCount };
constexpr double kMinStepLength = 0.001, kMaxStepLength = 86400;
constexpr long long kMaxThreads = 1024;

// Which commands use an option: a bit per CliCommand.
constexpr unsigned kInfo = 1, kConvert = 2, kRun = 4, kPartition = 8, kCosim = 16, kAssign = 32;
// Loading uses these (the demand is built with begin, end, step, seed, routing threads and penalties), so
// every command takes them. Outputs, teleports and the device are `run`'s, -o is `convert`'s: given to
// another command on its command line, they are refused rather than ignored.
constexpr unsigned kLoad = kInfo | kConvert | kRun | kPartition | kCosim | kAssign;
// `cosim` takes what `run` does (outputs, teleports, the device), bar the partitioned run's options.
constexpr unsigned kRuns = kRun | kCosim;
// `assign` simulates too (how vehicles drive, the device, progress), but writes routes, not run outputs.
constexpr unsigned kSimulates = kRuns | kAssign;

unsigned command_bit(CliCommand c) {
  switch (c) {
    case CliCommand::Info:
      return kInfo;
    case CliCommand::Convert:
      return kConvert;
    case CliCommand::Run:
      return kRun;
    case CliCommand::Partition:
      return kPartition;
    case CliCommand::Cosim:
      return kCosim;
    case CliCommand::Assign:
      return kAssign;
  }
  return 0;
}

struct OptionDef {
  std::string_view name, synonym;  // long name and SUMO synonym (empty if none)
  char short_name;                 // 0 if none
  Kind kind;
  Check check;
  bool command_line_only;
  unsigned commands;      // kInfo | kConvert | kRun | kPartition: the commands that use it
  std::string_view help;  // one line for --help
  void (*store)(ConfigSpec&, Value&&);
};

// SUMO's string vectors: ids separated by commas and/or blanks.
std::vector<std::string> split_id_list(const std::string& text) {
  std::vector<std::string> ids;
  size_t i = 0;
  while (i < text.size()) {
    const size_t start = text.find_first_not_of(", \t\n", i);
    if (start == std::string::npos) break;
    const size_t end = std::min(text.find_first_of(", \t\n", start), text.size());
    ids.push_back(text.substr(start, end - start));
    i = end;
  }
  return ids;
}

constexpr std::string_view kConfigFile = "configuration-file";

// clang-format off
const OptionDef kOptions[] = {
  {kConfigFile, "", 'c', Kind::Path, Check::None, true, kLoad, "a SUMO .sumocfg; the other options override it", [](ConfigSpec& c, Value&& v) { c.config_file = std::move(v.text); }},
  {"net-file", "net", 'n', Kind::Path, Check::None, false, kLoad, "the SUMO network (.net.xml or .net.xml.gz)", [](ConfigSpec& c, Value&& v) { c.net_file = std::move(v.text); }},
  {"route-files", "routes", 'r', Kind::PathList, Check::None, false, kLoad, "route files (comma-separated): vehicles, trips, flows, vTypes", [](ConfigSpec& c, Value&& v) { c.route_files = std::move(v.list); }},
  {"additional-files", "additional", 'a', Kind::PathList, Check::None, false, kLoad, "add-files (comma-separated): vTypes, tlLogic, edgeData/laneData", [](ConfigSpec& c, Value&& v) { c.additional_files = std::move(v.list); }},
  {"begin", "", 'b', Kind::Time, Check::None, false, kLoad, "begin time (s or h:m:s); earlier departures are dropped", [](ConfigSpec& c, Value&& v) { c.begin = v.seconds; }},
  {"end", "", 'e', Kind::Time, Check::None, false, kLoad, "end time; -1 (default): until every vehicle has arrived", [](ConfigSpec& c, Value&& v) { c.end = v.seconds; }},
  {"step-length", "", 0, Kind::Time, Check::StepLength, false, kLoad, "step length in s, a whole number of milliseconds (default 1)", [](ConfigSpec& c, Value&& v) { c.step_length = v.seconds; }},
  // Loading applies it (the demand's vTypes carry the model), so every command takes it.
  {"default.carfollowmodel", "", 0, Kind::Name, Check::None, false, kLoad, "car-following model of vTypes that name none: Krauss (default) or IDM; others run IDM", [](ConfigSpec& c, Value&& v) { c.default_car_follow_model = std::move(v.text); }},
  {"seed", "", 0, Kind::Integer, Check::None, false, kLoad, "random seed (default 23423)", [](ConfigSpec& c, Value&& v) { c.seed = v.integer; }},
  // Negative disables teleporting, as in SUMO.
  {"time-to-impatience", "", 0, Kind::Time, Check::None, false, kSimulates, "waiting time after which a vehicle at a link without priority counts on foes that can still brake to let it go (SUMO's impatience; default 180; <= 0: never)", [](ConfigSpec& c, Value&& v) { c.time_to_impatience = v.seconds; }},
  {"time-to-teleport", "", 0, Kind::Time, Check::None, false, kSimulates, "waiting time before a blocked vehicle teleports; < 0: never (default 300)", [](ConfigSpec& c, Value&& v) { c.time_to_teleport = v.seconds; }},
  {"time-to-teleport.highways", "", 0, Kind::Time, Check::None, false, kSimulates, "waiting time before a vehicle on a lane that does not lead on along its route, on a road faster than time-to-teleport.highways.min-speed, teleports; <= 0: never (default 0)", [](ConfigSpec& c, Value&& v) { c.time_to_teleport_highways = v.seconds; }},
  {"time-to-teleport.highways.min-speed", "", 0, Kind::Number, Check::None, false, kSimulates, "speed limit above which a road counts for time-to-teleport.highways, m/s (default 19.1667: 69 km/h)", [](ConfigSpec& c, Value&& v) { c.time_to_teleport_highways_min_speed = v.number; }},
  {"ignore-junction-blocker", "", 0, Kind::Time, Check::None, false, kSimulates, "a vehicle standing this long on a junction no longer blocks the foes crossing its path; < 0: never (default -1)", [](ConfigSpec& c, Value&& v) { c.ignore_junction_blocker = v.seconds; }},
  {"route-steps", "", 's', Kind::Time, Check::None, false, kLoad, "> 0 (default 200): as SUMO, a vehicle or flow listed in a route file after a later-departing one is ignored; <= 0: every one is loaded", [](ConfigSpec& c, Value&& v) { c.route_steps = v.seconds; }},
  {"max-depart-delay", "", 0, Kind::Time, Check::None, false, kSimulates, "a vehicle not inserted this long after its depart time is dropped (discarded); < 0: never (default -1)", [](ConfigSpec& c, Value&& v) { c.max_depart_delay = v.seconds; }},
  // Loading applies it (the network is built without signals), so every command takes it.
  {"tls.all-off", "", 0, Kind::Bool, Check::None, false, kLoad, "switch every traffic light off: its links give way as the net's connection states say (o: yield, O: priority)", [](ConfigSpec& c, Value&& v) { c.tls_all_off = v.flag; }},
  {"weights.random-factor", "", 0, Kind::Number, Check::AtLeastOne, false, kLoad, "multiply the routing cost of each edge by a factor drawn in [1, F) per trip and edge (default 1)", [](ConfigSpec& c, Value&& v) { c.weights_random_factor = v.number; }},
  {"routing-algorithm", "", 0, Kind::Algorithm, Check::None, false, kLoad, "router of trips: dijkstra (default) or astar, or CH or CHWrapper (a customizable contraction hierarchy: the same costs, faster on many trips)", [](ConfigSpec& c, Value&& v) { c.routing_algorithm = std::move(v.text); }},
  {"device.rerouting.probability", "", 0, Kind::Number, Check::None, false, kLoad, "probability that a vehicle gets the rerouting device (trips and flows from/to always have it; < 0: not given)", [](ConfigSpec& c, Value&& v) { c.rerouting.probability = v.number; }},
  {"device.rerouting.explicit", "", 0, Kind::Text, Check::None, false, kLoad, "ids of vehicles that get the rerouting device (comma- or space-separated)", [](ConfigSpec& c, Value&& v) { c.rerouting.explicit_ids = split_id_list(v.text); }},
  {"device.rerouting.deterministic", "", 0, Kind::Bool, Check::None, false, kLoad, "equip exactly the fraction given by device.rerouting.probability", [](ConfigSpec& c, Value&& v) { c.rerouting.deterministic = v.flag; }},
  {"device.rerouting.period", "", 0, Kind::Time, Check::NonNegative, false, kLoad, "equipped vehicles re-route while driving every this many s; 0 (default): never", [](ConfigSpec& c, Value&& v) { c.rerouting.period = v.seconds; }},
  {"device.rerouting.pre-period", "", 0, Kind::Time, Check::NonNegative, false, kLoad, "equipped vehicles waiting to be inserted re-route every this many s (default 60)", [](ConfigSpec& c, Value&& v) { c.rerouting.pre_period = v.seconds; }},
  {"device.rerouting.adaptation-interval", "", 0, Kind::Time, Check::None, false, kLoad, "s between samples of the edges' mean speeds for routing (default 1; <= 0: free-flow travel times throughout)", [](ConfigSpec& c, Value&& v) { c.rerouting.adaptation_interval = v.seconds; }},
  {"device.rerouting.adaptation-steps", "", 0, Kind::Integer, Check::NonNegative, false, kLoad, "samples in the moving average of the edges' speeds (default 180)", [](ConfigSpec& c, Value&& v) { c.rerouting.adaptation_steps = static_cast<int>(v.integer); c.rerouting.adaptation_steps_given = true; }},
  {"device.rerouting.adaptation-weight", "", 0, Kind::Number, Check::NonNegative, false, kLoad, "weight of the old value in the exponential average of the edges' speeds (used when adaptation-steps is not given; >= 1: no updates)", [](ConfigSpec& c, Value&& v) { c.rerouting.adaptation_weight = v.number; }},
  {"device.rerouting.synchronize", "", 0, Kind::Bool, Check::None, false, kLoad, "count the re-routing period from time 0 rather than from each vehicle's departure", [](ConfigSpec& c, Value&& v) { c.rerouting.synchronize = v.flag; }},
  {"weights.minor-penalty", "", 0, Kind::Time, Check::NonNegative, false, kLoad, "routing cost of a minor link, in s (default 1.5)", [](ConfigSpec& c, Value&& v) { c.minor_penalty = v.seconds; }},
  {"no-warnings", "", 'W', Kind::Bool, Check::None, false, kSimulates, "no warnings on stderr (loading, teleports, the parts' count), as SUMO's --no-warnings", [](ConfigSpec& c, Value&& v) { c.no_warnings = v.flag; }},
  {"no-step-log", "", 0, Kind::Bool, Check::None, false, kSimulates, "no progress lines on stderr", [](ConfigSpec& c, Value&& v) { c.no_step_log = v.flag; }},
  {"ignore-route-errors", "", 0, Kind::Bool, Check::None, false, kLoad, "skip vehicles with broken routes instead of refusing the input", [](ConfigSpec& c, Value&& v) { c.ignore_route_errors = v.flag; }},
  {"threads", "", 0, Kind::Integer, Check::ThreadCount, false, kLoad, "threads for routing and stepping; 0: all for routing, 1 for stepping", [](ConfigSpec& c, Value&& v) { c.threads = static_cast<int>(v.integer); }},
  // Not a SUMO option: command line only, so a .sumocfg stays valid for SUMO.
  {"device", "", 0, Kind::Device, Check::None, true, kSimulates, "cpu (default), auto (a usable CUDA device, else the CPU) or gpu", [](ConfigSpec& c, Value&& v) { c.device = v.device; }},
  {"max-lane-map-gb", "", 0, Kind::Number, Check::Positive, true, kLoad, "the most lane map (one byte per metre of lane) a network may need, GiB (default 16)", [](ConfigSpec& c, Value&& v) { c.max_lane_map_gb = v.number; }},
  {"progress-interval", "", 0, Kind::Number, Check::Positive, true, kSimulates, "wall seconds between progress lines when stderr is not a terminal (default 60)", [](ConfigSpec& c, Value&& v) { c.progress_interval = v.number; }},
  {"jam-report", "", 0, Kind::Path, Check::None, true, kRuns, "LPSim's jam report: each teleport and long stop, its cause and blockers", [](ConfigSpec& c, Value&& v) { c.jam_report = std::move(v.text); }},
  {"save-state.times", "", 0, Kind::TimeList, Check::None, false, kRun, "times at which to save the run's state (comma-separated), as an LPSim state file that --load-state resumes from", [](ConfigSpec& c, Value&& v) { c.save_state_times = std::move(v.times); }},
  {"save-state.period", "", 0, Kind::Time, Check::None, false, kRun, "save the run's state every this many s; <= 0 (default -1): never", [](ConfigSpec& c, Value&& v) { c.save_state_period = v.seconds; }},
  {"save-state.prefix", "", 0, Kind::Path, Check::None, false, kRun, "state files are named PREFIX_TIME SUFFIX (default prefix: state)", [](ConfigSpec& c, Value&& v) { c.save_state_prefix = std::move(v.text); }},
  {"save-state.suffix", "", 0, Kind::Text, Check::None, false, kRun, "the state files' suffix (default .lpstate)", [](ConfigSpec& c, Value&& v) { c.save_state_suffix = std::move(v.text); }},
  {"save-state.files", "", 0, Kind::PathList, Check::None, false, kRun, "the state files' names, one per time of save-state.times (comma-separated)", [](ConfigSpec& c, Value&& v) { c.save_state_files = std::move(v.list); }},
  {"save-state.on-signal", "", 0, Kind::Bool, Check::None, true, kRun, "when a signal stops the run (SIGTERM of a pre-empted job), save its state before the outputs close, as PREFIX_TIME SUFFIX", [](ConfigSpec& c, Value&& v) { c.save_state_on_signal = v.flag; }},
  {"load-state", "", 0, Kind::Path, Check::None, false, kRun, "resume the run from this LPSim state file (of the same scenario and options), continuing its outputs", [](ConfigSpec& c, Value&& v) { c.load_state = std::move(v.text); }},
  {"jam-report.stop-time", "", 0, Kind::Number, Check::Positive, true, kRuns, "the jam report's shortest stop, in s (default 60)", [](ConfigSpec& c, Value&& v) { c.jam_report_stop_time = v.number; }},
  {"fcd-output", "", 0, Kind::Path, Check::None, false, kRuns, "SUMO FCD output (.gz: compressed)", [](ConfigSpec& c, Value&& v) { c.outputs.fcd = std::move(v.text); }},
  {"device.fcd.period", "", 0, Kind::Time, Check::NonNegative, false, kRuns, "FCD sampling period in s; 0 (default): every step", [](ConfigSpec& c, Value&& v) { c.outputs.fcd_period = v.seconds; }},
  {"tripinfo-output", "tripinfo", 0, Kind::Path, Check::None, false, kRuns, "SUMO tripinfo output", [](ConfigSpec& c, Value&& v) { c.outputs.tripinfo = std::move(v.text); }},
  {"tripinfo-output.write-unfinished", "", 0, Kind::Bool, Check::None, false, kRuns, "tripinfo also for vehicles still running at the end", [](ConfigSpec& c, Value&& v) { c.outputs.tripinfo_write_unfinished = v.flag; }},
  {"tripinfo-output.write-undeparted", "", 0, Kind::Bool, Check::None, false, kRuns, "tripinfo also for vehicles still running and for those due that never departed (implies write-unfinished)", [](ConfigSpec& c, Value&& v) { c.outputs.tripinfo_write_undeparted = v.flag; }},
  {"summary-output", "summary", 0, Kind::Path, Check::None, false, kRuns, "SUMO summary output", [](ConfigSpec& c, Value&& v) { c.outputs.summary = std::move(v.text); }},
  {"statistic-output", "statistics-output", 0, Kind::Path, Check::None, false, kRuns, "SUMO statistic output", [](ConfigSpec& c, Value&& v) { c.outputs.statistic = std::move(v.text); }},
  {"emissions.volumetric-fuel", "", 0, Kind::Bool, Check::None, false, kRuns, "emissions outputs give fuel in ml (by the fuel's density) instead of mg", [](ConfigSpec& c, Value&& v) { c.volumetric_fuel = v.flag; }},
  {"edgedata-output", "", 0, Kind::Path, Check::None, false, kRuns, "SUMO edgeData output, one interval for the whole run", [](ConfigSpec& c, Value&& v) { c.outputs.edgedata = std::move(v.text); }},
  {"lanedata-output", "", 0, Kind::Path, Check::None, false, kRuns, "SUMO laneData output, one interval for the whole run", [](ConfigSpec& c, Value&& v) { c.outputs.lanedata = std::move(v.text); }},
  {"corridor", "", 0, Kind::Path, Check::None, true, kCosim, "the edges SUMO simulates: a sumo-gui/netedit selection file (edge:ID, lane:ID lines) or plain edge ids", [](ConfigSpec& c, Value&& v) { c.corridor_file = std::move(v.text); }},
  {"sumo-binary", "", 0, Kind::Text, Check::None, true, kCosim, "run SUMO as this program (sumo, sumo-gui, or a path) over TraCI on 127.0.0.1 instead of in process (libsumo)", [](ConfigSpec& c, Value&& v) { c.sumo_binary = std::move(v.text); }},
  {"sumo-timeout", "", 0, Kind::Time, Check::Positive, true, kCosim, "over TraCI (--sumo-binary): seconds SUMO may take to answer one call before it is taken for hung and killed (default 300)", [](ConfigSpec& c, Value&& v) { c.sumo_timeout = v.seconds; }},
  {"sumo-args", "", 0, Kind::Text, Check::None, true, kCosim, "further SUMO options, as on its command line (quoted: --sumo-args \"--lateral-resolution 0.8\")", [](ConfigSpec& c, Value&& v) { c.sumo_args = std::move(v.text); }},
  {"lpsim-nodes", "", 0, Kind::Path, Check::None, false, kLoad, "LPSim CSV nodes (with --lpsim-edges, instead of a SUMO network)", [](ConfigSpec& c, Value&& v) { c.lpsim_nodes_csv = std::move(v.text); }},
  {"lpsim-edges", "", 0, Kind::Path, Check::None, false, kLoad, "LPSim CSV edges (with --lpsim-nodes)", [](ConfigSpec& c, Value&& v) { c.lpsim_edges_csv = std::move(v.text); }},
  {"lpsim-od", "", 0, Kind::Path, Check::None, false, kLoad, "LPSim CSV origin-destination demand", [](ConfigSpec& c, Value&& v) { c.lpsim_od_csv = std::move(v.text); }},
  {"output", "", 'o', Kind::Path, Check::None, true, kConvert | kPartition | kAssign, "the file to write: the snapshot (convert, .lpsim), the partition file (partition) or the assigned routes (assign; their alternatives beside it as .rou.alt.xml)", [](ConfigSpec& c, Value&& v) { c.output_file = std::move(v.text); }},
  {"parts", "", 0, Kind::Integer, Check::Positive, true, kPartition | kRun | kAssign, "the number of parts K (run: the network split into K parts, each stepped by its own threads)", [](ConfigSpec& c, Value&& v) { c.parts = static_cast<int>(v.integer); }},
  {"parts.min-vehicles", "", 0, Kind::Integer, Check::NonNegative, true, kRun | kAssign, "the fewest vehicles per part and step, estimated from the routes in free flow, for which the network is split into --parts K parts; with fewer, fewer parts run, as they would cost more in exchanges than they save (default 2500; 0: always K)", [](ConfigSpec& c, Value&& v) { c.parts_min_vehicles = v.integer; }},
  {"part-timeout", "", 0, Kind::Time, Check::Positive, true, kRun | kAssign, "seconds a part waits for another in one exchange before it takes it for stopped and ends the run with an error (default 600)", [](ConfigSpec& c, Value&& v) { c.part_timeout = v.seconds; }},
  {"partition-method", "", 0, Kind::Method, Check::None, true, kPartition | kRun | kAssign, "metis (default: balanced k-way), leiden (communities merged into K parts by k-means) or random", [](ConfigSpec& c, Value&& v) { c.partition_method = std::move(v.text); c.partition_method_given = true; }},
  {"partition-file", "", 0, Kind::Path, Check::None, true, kPartition | kRun | kAssign, "a partition file: to summarize (and map) instead of computing one; run: the parts to run in", [](ConfigSpec& c, Value&& v) { c.partition_file = std::move(v.text); }},
  {"partition.load-from", "", 0, Kind::Path, Check::None, true, kPartition | kRun | kAssign, "an edgeData output of a run of the scenario: the parts balanced on the vehicle-seconds it measured at each junction and cut where fewest vehicles crossed, in place of the routes in free flow (congested junctions weigh what their queues cost); run: its vehicles per step also decide how many parts pay", [](ConfigSpec& c, Value&& v) { c.partition_load_from = std::move(v.text); }},
  {"migrations-from", "", 0, Kind::Path, Check::None, true, kPartition, "an edgeData output of a run of the scenario: the vehicles of that run that crossed a cut", [](ConfigSpec& c, Value&& v) { c.migrations_from = std::move(v.text); }},
  {"map", "", 0, Kind::Path, Check::None, true, kPartition, "a PNG map of the network coloured by part", [](ConfigSpec& c, Value&& v) { c.partition_map = std::move(v.text); }},
  {"iterations", "last-step", 'l', Kind::Integer, Check::AtLeastOne, true, kAssign, "iterations of routing and simulation at most (default 50, as duaIterate.py)", [](ConfigSpec& c, Value&& v) { c.assign.iterations = static_cast<int>(v.integer); }},
  {"aggregation", "", 0, Kind::Time, Check::Positive, true, kAssign, "s per interval of the edge travel times routes are chosen on (default 900)", [](ConfigSpec& c, Value&& v) { c.assign.aggregation = v.seconds; }},
  {"gawron.beta", "gBeta", 0, Kind::Number, Check::NonNegative, true, kAssign, "Gawron's beta: weight of the new travel time in a route's cost (default 0.9, as duaIterate.py)", [](ConfigSpec& c, Value&& v) { c.assign.gawron_beta = v.number; }},
  {"gawron.a", "gA", 0, Kind::Number, Check::NonNegative, true, kAssign, "Gawron's a: how strongly cost differences shift the route probabilities (default 0.5, as duaIterate.py)", [](ConfigSpec& c, Value&& v) { c.assign.gawron_a = v.number; }},
  {"route-choice-method", "", 0, Kind::Text, Check::None, true, kAssign, "gawron (default) or logit (C-logit with its commonality factor, as duarouter)", [](ConfigSpec& c, Value&& v) { c.assign.logit = v.text == "logit"; if (v.text != "logit" && v.text != "gawron") throw InputError(SourceLoc{"command line", 0}, "--route-choice-method: gawron or logit, got '" + v.text + "'"); }},
  {"logit.beta", "lBeta", 0, Kind::Number, Check::None, true, kAssign, "C-logit's weight of the commonality factor (default 0.15; < 0: the cheapest route's cost in hours)", [](ConfigSpec& c, Value&& v) { c.assign.logit_beta = v.number; }},
  {"logit.gamma", "lGamma", 0, Kind::Number, Check::None, true, kAssign, "C-logit's exponent of the overlap (default 1)", [](ConfigSpec& c, Value&& v) { c.assign.logit_gamma = v.number; }},
  {"logit.theta", "lTheta", 0, Kind::Number, Check::None, true, kAssign, "logit's scale of the costs (default -1: from the costs' spread, as duarouter)", [](ConfigSpec& c, Value&& v) { c.assign.logit_theta = v.number; }},
  {"max-alternatives", "", 0, Kind::Integer, Check::AtLeastOne, true, kAssign, "route alternatives kept per vehicle (default 5)", [](ConfigSpec& c, Value&& v) { c.assign.max_alternatives = static_cast<int>(v.integer); }},
  {"keep-all-routes", "", 0, Kind::Bool, Check::None, true, kAssign, "keep alternatives whose probability fell to 0", [](ConfigSpec& c, Value&& v) { c.assign.keep_all_routes = v.flag; }},
  {"gap", "", 0, Kind::Number, Check::Positive, true, kAssign, "stop once an iteration's relative gap is at most this (default: off)", [](ConfigSpec& c, Value&& v) { c.assign.gap = v.number; }},
  {"max-convergence-deviation", "", 0, Kind::Number, Check::Positive, true, kAssign, "stop once the relative standard deviation of the mean trip time over the last convergence-iterations iterations is below this (duaIterate.py's measure; default: off)", [](ConfigSpec& c, Value&& v) { c.assign.max_convergence_deviation = v.number; }},
  {"weight-files", "weights", 'w', Kind::Path, Check::None, true, kAssign, "an edgeData output (duaIterate's dump): print the relative gap of the loaded routes on its travel times instead of iterating", [](ConfigSpec& c, Value&& v) { c.assign.weight_files = std::move(v.text); }},
  {"first-iteration", "first-step", 'f', Kind::Integer, Check::NonNegative, true, kAssign, "go on as iteration N from the alternatives the route files hold (the .rou.alt.xml of iteration N-1)", [](ConfigSpec& c, Value&& v) { c.assign.first_iteration = static_cast<int>(v.integer); }},
  {"plot", "", 0, Kind::Path, Check::None, true, kAssign, "a PNG plot of the relative gap per iteration", [](ConfigSpec& c, Value&& v) { c.assign.plot = std::move(v.text); }},
  {"convergence-iterations", "", 0, Kind::Integer, Check::AtLeastOne, true, kAssign, "iterations max-convergence-deviation looks at (default 10)", [](ConfigSpec& c, Value&& v) { c.assign.convergence_iterations = static_cast<int>(v.integer); }},
};
// clang-format on

const OptionDef* find_long(std::string_view name) {
  for (const auto& d : kOptions)
    if (d.name == name || (!d.synonym.empty() && d.synonym == name)) return &d;
  return nullptr;
}

const OptionDef* find_short(char c) {
  for (const auto& d : kOptions)
    if (d.short_name != 0 && d.short_name == c) return &d;
  return nullptr;
}

std::string resolve(const std::string& path, const std::string& base_dir) {
  if (path.empty() || base_dir.empty()) return path;
  std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

std::string option_label(const OptionSource& where, std::string_view name) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
  std::string label = where.command_line ? "--" : "<";
  label += name;
  if (!where.command_line) label += '>';
  return label;
}

[[noreturn]] void bad_value(const OptionSource& where, std::string_view name, const std::string& value,
                            const std::string& expected) {
  throw InputError(where.loc, option_label(where, name) + ": " + expected + ", got '" + value + "'");
}

Value convert(const OptionDef& def, std::string_view name, const std::string& value,
              const OptionSource& where) {
  Value v;
  switch (def.kind) {
    case Kind::Path:
      v.text = resolve(value, where.base_dir);
      break;
    case Kind::PathList: {
      size_t i = 0;
      while (i < value.size()) {
        auto sep = [](char c) { return c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
        while (i < value.size() && sep(value[i])) ++i;
        size_t start = i;
        while (i < value.size() && !sep(value[i])) ++i;
        if (i > start) v.list.push_back(resolve(value.substr(start, i - start), where.base_dir));
      }
      break;
    }
    case Kind::TimeList: {
      for (const std::string& item : split_id_list(std::string(value))) {
        auto t = parse_sumo_time(item);
        if (!t || !time_in_range(*t))
          bad_value(where, name, value, "expected times (seconds, h:m:s or d:h:m:s)");
        v.times.push_back(*t);
      }
      break;
    }
    case Kind::Time: {
      auto t = parse_sumo_time(value);
      if (!t) bad_value(where, name, value, "expected a time (seconds, h:m:s or d:h:m:s)");
      if (def.check == Check::NonNegative && *t < 0) bad_value(where, name, value, "expected a time >= 0");
      if (def.check == Check::Positive && !(*t > 0)) bad_value(where, name, value, "expected a time > 0");
      if (def.check == Check::StepLength && !(*t >= kMinStepLength && *t <= kMaxStepLength))
        bad_value(where, name, value, "expected a step length from 0.001 to 86400 s");
      if (!time_in_range(*t)) bad_value(where, name, value, "expected a time within +-1e12 s");
      v.seconds = *t;
      break;
    }
    case Kind::Bool: {
      auto b = parse_sumo_bool(value);
      if (!b) bad_value(where, name, value, "expected true or false");
      v.flag = *b;
      break;
    }
    case Kind::Integer: {
      auto n = parse_integer(value);
      if (!n) bad_value(where, name, value, "expected an integer");
      if (def.check == Check::ThreadCount && (*n < 0 || *n > kMaxThreads))
        bad_value(where, name, value, "expected a thread count from 0 to 1024");
      if (def.check == Check::Positive && !(*n > 0 && *n <= kMaxParts))
        bad_value(where, name, value, "expected a whole number from 1 to 1000000");
      v.integer = *n;
      break;
    }
    case Kind::Number: {
      auto x = parse_double(value);
      if (!x || !std::isfinite(*x)) bad_value(where, name, value, "expected a number");
      if (def.check == Check::Positive && !(*x > 0)) bad_value(where, name, value, "expected a number > 0");
      if (def.check == Check::AtLeastOne && !(*x >= 1))
        bad_value(where, name, value, "expected a number >= 1");
      v.number = *x;
      break;
    }
    case Kind::Text:
      v.text = value;
      break;
    case Kind::Name:
      if (value.empty() || value.find_first_of(" \t\r\n,") != std::string::npos)
        bad_value(where, name, value, "expected a model name");
      v.text = value;
      break;
    case Kind::Method:
      if (value != "metis" && value != "leiden" && value != "random")
        bad_value(where, name, value, "expected metis, leiden or random");
      v.text = value;
      break;
    case Kind::Algorithm:  // SUMO's names; SUMO's own router takes no other
      if (value != "dijkstra" && value != "astar" && value != "CH" && value != "CHWrapper")
        bad_value(where, name, value, "expected dijkstra, astar, CH or CHWrapper");
      v.text = value;
      break;
    case Kind::Device:
      if (value == "auto")
        v.device = ComputeDevice::Auto;
      else if (value == "cpu")
        v.device = ComputeDevice::Cpu;
      else if (value == "gpu")
        v.device = ComputeDevice::Gpu;
      else
        bad_value(where, name, value, "expected auto, cpu or gpu");
      break;
  }
  return v;
}

bool looks_like_option(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return false;
  return !parse_sumo_time(arg);  // "-1" is a value, not an option
}

// A SUMO option LPSim does not implement: as if absent at SUMO's default, else noted (inert), kept for the
// loaded scenario to decide (scoped) or refused.
void apply_foreign(ConfigSpec& config, const ForeignOption& option, std::string_view name,
                   const std::string& value, const OptionSource& where) {
  if (option.kind == ForeignOptionClass::Scoped) {
    // A later value (the command line after the .sumocfg) replaces an earlier one, the default included.
    auto& scoped = config.scoped_options;
    std::erase_if(scoped, [&](const ScopedOption& o) { return o.name == option.name; });
    if (!is_sumo_default(option, value))
      scoped.push_back({std::string(option.name), value, where.loc, option.scope});
    return;
  }
  if (is_sumo_default(option, value)) return;
  if (option.kind == ForeignOptionClass::Unsupported) {
    std::string what = option_label(where, name) + " '" + value + "': SUMO option not supported by LPSim";
    if (!option.sumo_default.empty())
      what += " (only SUMO's default '" + std::string(option.sumo_default) + "')";
    throw InputError(where.loc, what);
  }
  auto& inert = config.inert_options;
  if (std::find(inert.begin(), inert.end(), name) == inert.end()) inert.emplace_back(name);
}

// Seconds as the user would write them: "3600", "0.5" (the shortest text that reads back as t).
std::string format_seconds(double t) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, t);
  return std::string(buf, result.ptr);
}

}  // namespace

bool apply_option(ConfigSpec& config, std::string_view name, const std::string& value,
                  const OptionSource& where) {
  const OptionDef* def = find_long(name);
  if (def && !(def->command_line_only && !where.command_line)) {
    def->store(config, convert(*def, name, value, where));
    return true;
  }
  if (const ForeignOption* f = def ? nullptr : find_foreign_option(name)) {
    apply_foreign(config, *f, name, value, where);
    return true;
  }
  return false;
}

void check_time_window(const ConfigSpec& config, const SourceLoc& where) {
  if (config.end >= 0 && config.begin > config.end)
    throw InputError(where, "end time " + format_seconds(config.end) + " is before begin time " +
                                format_seconds(config.begin) + ": the end time must not be before the begin");
}

std::string describe_options(CliCommand command) {
  const unsigned bit = command_bit(command);
  std::vector<std::pair<std::string, std::string_view>> rows;
  size_t width = 0;
  for (const auto& d : kOptions) {
    if (!(d.commands & bit)) continue;
    std::string left = d.short_name ? std::string("-") + d.short_name + ", " : std::string("    ");
    left += "--" + std::string(d.name);
    switch (d.kind) {
      case Kind::Path:
        left += " FILE";
        break;
      case Kind::PathList:
        left += " FILE[,FILE]";
        break;
      case Kind::TimeList:
        left += " TIME[,TIME...]";
        break;
      case Kind::Time:
        left += " TIME";
        break;
      case Kind::Bool:
        left += " [BOOL]";
        break;
      case Kind::Integer:
        left += " INT";
        break;
      case Kind::Number:
        left += " NUMBER";
        break;
      case Kind::Device:
        left += " DEVICE";
        break;
      case Kind::Name:
        left += " MODEL";
        break;
      case Kind::Text:
        left += " TEXT";
        break;
      case Kind::Method:
        left += " METHOD";
        break;
      case Kind::Algorithm:
        left += " ALGORITHM";
        break;
    }
    if (!d.synonym.empty()) left += " (or --" + std::string(d.synonym) + ")";
    width = std::max(width, left.size());
    rows.emplace_back(std::move(left), d.help);
  }
  std::string out;
  for (const auto& [left, help] : rows)
    out += "  " + left + std::string(width + 2 - left.size(), ' ') + std::string(help) + "\n";
  return out;
}

std::optional<double> parse_sumo_time(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (text.find(':') == std::string_view::npos) return parse_double(text);
  double sign = 1;
  if (!text.empty() && text.front() == '-') {
    sign = -1;
    text.remove_prefix(1);
  }
  std::vector<std::string_view> parts;
  size_t start = 0;
  for (;;) {
    size_t colon = text.find(':', start);
    parts.push_back(
        text.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start));
    if (colon == std::string_view::npos) break;
    start = colon + 1;
  }
  if (parts.size() != 3 && parts.size() != 4) return std::nullopt;
  static constexpr double kUnit[] = {86400, 3600, 60, 1};  // d, h, m, s
  const size_t first_unit = 4 - parts.size();
  double total = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].empty() || parts[i].front() == '-' || parts[i].front() == '+') return std::nullopt;
    const bool last = i + 1 == parts.size();
    std::optional<double> value;
    if (last) {
      value = parse_double(parts[i]);
    } else if (auto n = parse_integer(parts[i])) {
      value = static_cast<double>(*n);
    }
    if (!value) return std::nullopt;
    total += *value * kUnit[first_unit + i];
  }
  return sign * total;
}

std::optional<bool> parse_sumo_bool(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  if (lower == "true" || lower == "yes" || lower == "on" || lower == "1" || lower == "x") return true;
  if (lower == "false" || lower == "no" || lower == "off" || lower == "0" || lower == "-") return false;
  return std::nullopt;
}

bool help_requested(const std::vector<std::string>& args) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--") return false;
    if (a == "-h" || a == "--help" || a == "-?") return true;
    if (!looks_like_option(a) || a.find('=') != std::string::npos) continue;
    const OptionDef* def = a.rfind("--", 0) == 0 ? find_long(std::string_view(a).substr(2))
                           : a.size() == 2       ? find_short(a[1])
                                                 : nullptr;
    // Free text takes the next word whatever it looks like (as the parser does); other values only when
    // they do not look like an option.
    if (def && def->kind == Kind::Text)
      ++i;
    else if (def && def->kind != Kind::Bool && i + 1 < args.size() && !looks_like_option(args[i + 1]))
      ++i;
  }
  return false;
}

ConfigSpec parse_cli_options(const std::vector<std::string>& args, std::vector<std::string>* positional,
                             std::optional<CliCommand> command) {
  struct Given {
    const OptionDef* def;          // LPSim's option, or
    const ForeignOption* foreign;  // a SUMO option LPSim does not implement
    std::string value;
  };
  std::vector<Given> given;
  std::vector<std::string> rest;
  std::string config_file;
  const OptionSource where{SourceLoc{"command line", 0}, "", true};
  bool time_given = false;

  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") {
      rest.insert(rest.end(), args.begin() + static_cast<std::ptrdiff_t>(i) + 1, args.end());
      break;
    }
    if (!looks_like_option(arg)) {
      rest.push_back(arg);
      continue;
    }
    const OptionDef* def = nullptr;
    const ForeignOption* foreign = nullptr;
    std::optional<std::string> inline_value;
    if (arg.rfind("--", 0) == 0) {
      std::string_view body = std::string_view(arg).substr(2);
      size_t eq = body.find('=');
      if (eq != std::string_view::npos) inline_value = std::string(body.substr(eq + 1));
      def = find_long(body.substr(0, eq));
      if (!def) foreign = find_foreign_option(body.substr(0, eq));
    } else if (arg.size() == 2 || arg[2] == '=') {
      def = find_short(arg[1]);
      if (!def) foreign = find_foreign_short(arg[1]);
      if (arg.size() > 2) inline_value = arg.substr(3);
    }
    if (!def && !foreign) throw InputError(where.loc, "unknown option '" + arg + "'");
    const std::string shown = "--" + std::string(def ? def->name : foreign->name);
    if (def && command && !(def->commands & command_bit(*command)))
      throw InputError(where.loc, "option '" + arg + "' is not used by this command (see its --help)");

    std::string value;
    if (inline_value) {
      value = *inline_value;
    } else if (def ? def->kind == Kind::Bool : is_foreign_switch(*foreign)) {
      // A bare flag means true; a following true/false belongs to it.
      if (i + 1 < args.size() && parse_sumo_bool(args[i + 1])) {
        value = args[++i];
      } else {
        value = "true";
      }
    } else {
      // Free text (--sumo-args "--opt v") may look like an option: it is the value all the same.
      if (i + 1 >= args.size() || (looks_like_option(args[i + 1]) && !(def && def->kind == Kind::Text)))
        throw InputError(where.loc, "option '" + arg + "' (" + shown + ") needs a value");
      value = args[++i];
    }

    if (def && def->name == kConfigFile) {
      if (!config_file.empty()) throw InputError(where.loc, "option '" + arg + "' given more than once");
      if (value.empty()) throw InputError(where.loc, "option '" + arg + "' needs a file name");
      config_file = value;
    } else {
      if (def && (def->name == "begin" || def->name == "end")) time_given = true;
      given.push_back({def, foreign, std::move(value)});
    }
  }

  SourceLoc window_at{config_file, 0};  // where the .sumocfg sets the window, unless the command line does
  ConfigSpec config = config_file.empty() ? ConfigSpec{} : read_sumocfg(config_file, &window_at);
  for (auto& g : given) {
    if (g.def)
      g.def->store(config, convert(*g.def, g.def->name, g.value, where));
    else
      apply_foreign(config, *g.foreign, g.foreign->name, g.value, where);
  }
  check_time_window(config, time_given || config_file.empty() ? where.loc : window_at);

  if (positional) {
    *positional = std::move(rest);
  } else if (!rest.empty()) {
    throw InputError(where.loc, "unexpected argument '" + rest.front() + "'");
  }
  return config;
}

}  // namespace lpsim

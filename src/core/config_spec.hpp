#pragma once
// What a run or a load is asked to do: a .sumocfg and/or command-line options, merged (options win).
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace lpsim {

struct OutputSpec {
  std::string fcd, tripinfo, summary, edgedata, lanedata, statistic;
  double fcd_period = 0;  // 0: every step
  // SUMO's --tripinfo-output.write-unfinished: a tripinfo line at the end for every vehicle still running;
  // --tripinfo-output.write-undeparted: also for every vehicle due by then that never departed (it implies
  // write-unfinished, as in SUMO).
  bool tripinfo_write_unfinished = false, tripinfo_write_undeparted = false;
};

/// What a SUMO option that LPSim does not implement acts on, where it acts only in some scenarios. Given
/// with a value other than SUMO's default, it is refused where the loaded scenario has what it acts on (it
/// would change the results) and otherwise named in one warning (it cannot act there).
enum class OptionScope : uint8_t {
  BidiEdges,         // edges with a `bidi` partner (time-to-teleport.bidi)
  ReroutingDevice,   // what the rerouting device's options LPSim lacks act on (device.rerouting.*)
  ParkingAreaStops,  // stops at a parkingArea (parking.maneuver)
  Persons,           // persons (pedestrian.model, ride.stop-tolerance, person-device.*)
};

/// A scoped option as given: decided once the scenario is loaded (app/option_scopes.hpp).
struct ScopedOption {
  std::string name, value;
  SourceLoc loc;
  OptionScope scope;
};

/// SUMO's rerouting device options (MSDevice_Routing, MSRoutingEngine), SUMO's defaults.
struct ReroutingSpec {
  double probability = -1;                // < 0: not given
  std::vector<std::string> explicit_ids;  // device.rerouting.explicit
  bool deterministic = false;             // equip exactly the fraction `probability`, by a counter
  double period = 0;                      // s between en-route re-routings of equipped vehicles; 0: never
  double pre_period = 60;                 // s between re-routings while a vehicle waits to be inserted
  double adaptation_interval = 1;         // s between samples of the edges' mean speeds; <= 0: never
  int adaptation_steps = 180;             // samples averaged (a moving average); 0: exponential
  bool adaptation_steps_given = false;    // SUMO averages exponentially when only the weight is given
  double adaptation_weight = 0;           // the exponential average's weight of the old value
  bool synchronize = false;               // periods counted from time 0, not from each vehicle's departure
};

/// Where `lpsim run` steps the simulation (--device): auto takes a usable CUDA device, else the CPU.
enum class ComputeDevice { Auto, Cpu, Gpu };

/// `lpsim assign`: dynamic user assignment as duaIterate.py runs it (its defaults).
struct AssignSpec {
  int iterations = 50;
  double aggregation = 900;  // s
  double gawron_beta = 0.9, gawron_a = 0.5;
  bool logit = false;  // --route-choice-method logit instead of Gawron's
  double logit_beta = 0.15, logit_gamma = 1.0, logit_theta = -1;
  int max_alternatives = 5;
  bool keep_all_routes = false;
  double gap = 0;                        // stop at this relative gap; 0: off
  double max_convergence_deviation = 0;  // 0: off
  int convergence_iterations = 10;
  // Not iterating: the relative gap of the loaded routes on these travel times (an edgeData output).
  std::string weight_files;
  std::string plot;         // PNG of the gap per iteration
  int first_iteration = 0;  // > 0: go on from the alternatives in the route files (an .rou.alt.xml)
};

struct ConfigSpec {
  std::string config_file;    // the .sumocfg, if any
  std::string snapshot_file;  // the snapshot (`lpsim convert`'s output) the scenario was read from, if any
  std::string net_file;
  std::vector<std::string> route_files, additional_files;
  std::string lpsim_nodes_csv, lpsim_edges_csv, lpsim_od_csv;  // original LPSim format
  double begin = 0, end = -1, step_length = 1.0;               // end -1: until all vehicles arrived
  long long seed = 23423;
  AssignSpec assign;
  // SUMO's --default.carfollowmodel: the car-following model of every vType that names none.
  std::string default_car_follow_model = "Krauss";
  double time_to_teleport = 300;
  double time_to_teleport_highways = 0;  // SUMO's --time-to-teleport.highways [s]; <= 0: never
  double time_to_teleport_highways_min_speed = 69.0 / 3.6;  // its roads: speed limit above this [m/s]
  double time_to_impatience = 180;  // SUMO's --time-to-impatience [s]; <= 0: never impatient
  // SUMO's --ignore-junction-blocker [s]: a vehicle standing this long on a junction's internal lane no
  // longer blocks the foes crossing its path; < 0: never.
  double ignore_junction_blocker = -1;
  // SUMO's --max-depart-delay [s]: a vehicle still not inserted this long after its depart time is dropped
  // (counted as discarded); < 0: never.
  double max_depart_delay = -1;
  // SUMO's --route-steps [s]: > 0, route files are read ahead in steps, so a vehicle or flow departing before
  // one listed ahead of it in the same file is ignored; <= 0, every one is loaded.
  double route_steps = 200;
  // SUMO's --tls.all-off: every traffic light is off; its links keep the right of way the net's connection
  // states give them ('O' priority, 'o' yield).
  bool tls_all_off = false;
  // SUMO's --weights.random-factor (>= 1): each routed trip's edge costs are multiplied by factors drawn
  // in [1, F), per trip and edge, from the seed.
  double weights_random_factor = 1;
  // SUMO's --routing-algorithm: dijkstra and astar route trips with the Dijkstra router, CH and CHWrapper
  // with the contraction hierarchy (net/cch_router.hpp). Every one finds least-cost routes; among routes of
  // equal cost each picks its own, as SUMO's do.
  std::string routing_algorithm = "dijkstra";
  // SUMO's rerouting device (--device.rerouting.*): which vehicles get it beyond the trips and flows LPSim
  // routes (from/to), which always do; how often they re-route; how the travel times are averaged.
  ReroutingSpec rerouting;
  double minor_penalty =
      1.5;                   // SUMO's --weights.minor-penalty: routing cost of a crossing on a minor link [s]
  bool no_warnings = false;  // SUMO's --no-warnings: no teleport warnings on stderr
  bool no_step_log = false;  // SUMO's --no-step-log: no progress lines while running
  // Not a SUMO option: when stderr is not a terminal, `lpsim run` prints a progress line every this many
  // wall-clock seconds (on a terminal it redraws one line instead).
  double progress_interval = 60;
  // Not a SUMO option: `lpsim run --jam-report FILE` records every teleport and every vehicle standing at
  // least jam_report_stop_time s, with what blocked it (app/jam_report.hpp); empty: no report, no work.
  std::string jam_report;
  double jam_report_stop_time = 60;
  // SUMO's --save-state.* and --load-state: the run's state written between steps, as an LPSim binary
  // state file (app/state_file.hpp), at the given times and every period (state times: <= 0, none); each
  // named by the next of save_state_files, else prefix_TIME suffix. load_state: the file a run resumes from.
  std::vector<double> save_state_times;
  double save_state_period = -1;
  std::string save_state_prefix = "state", save_state_suffix = ".lpstate";
  std::vector<std::string> save_state_files;
  std::string load_state;
  // LPSim's --save-state.on-signal: a run stopped by SIGINT/SIGTERM/SIGHUP saves its state (prefix_TIME
  // suffix) before its outputs close, so that a pre-empted batch job resumes where it stopped.
  bool save_state_on_signal = false;
  bool ignore_route_errors = false;
  // SUMO's --emissions.volumetric-fuel: emissions outputs give fuel in ml (by the fuel's density), not mg.
  bool volumetric_fuel = false;
  int threads = 0;  // 0: all hardware threads
  // Not a SUMO option: the most lane map (one byte per metre of car lane) a network may ask for, in GiB, so
  // that an absurd lane length is refused before it allocates.
  double max_lane_map_gb = 16;
  // CPU until the GPU backend has been checked byte-identical on a GPU (tests/gpu); `--device auto` opts in.
  ComputeDevice device = ComputeDevice::Cpu;
  OutputSpec outputs;
  std::string output_file;  // -o/--output on the command line: LPSim's own result file
  // `lpsim partition`: K, the method (metis, leiden, random), a partition file to summarize instead of
  // computing one, the PNG map to draw, and a run's edgeData to count migrations from.
  int parts = 0;
  std::string partition_method = "metis";
  bool partition_method_given = false;  // named on the command line (it then needs --parts)
  // The fewest vehicles per part and step (estimated from the routes in free flow) for which `run` and
  // `assign` split the network into --parts K parts; with fewer they run fewer parts, as parts then cost more
  // in exchanges than they save (measured: docs/PERFORMANCE.md, "Partitioned engine"). 0: always K.
  int64_t parts_min_vehicles = 2500;
  // How long a part waits for another in one exchange before it calls it stopped (s).
  double part_timeout = 600;
  // Co-simulation over TraCI: how long SUMO may take to answer one call before it is killed (s).
  double sumo_timeout = 300;
  std::string partition_file, partition_map;
  std::string migrations_from;  // an edgeData output whose entries count the vehicles crossing the cuts
  // An edgeData output of a run of the scenario: the partition weighed by its measured load.
  std::string partition_load_from;
  // `lpsim cosim`: the corridor file, SUMO as a program over TraCI (empty: libsumo in process) and the
  // options passed to it, as one command-line text.
  std::string corridor_file, sumo_binary, sumo_args;
  // SUMO options given that cannot change LPSim's results (verbose, log, gui-settings-file, ...), in the
  // order first given, for the one warning that names them.
  std::vector<std::string> inert_options;
  // SUMO options that act only in some scenarios, given with other values than SUMO's defaults, in the order
  // given: refused or named in a warning once the scenario is loaded.
  std::vector<ScopedOption> scoped_options;
};

}  // namespace lpsim

// `lpsim assign`: dynamic user assignment (app/assignment.hpp) from the command line: a line per iteration
// on stdout, the assigned routes and their alternatives written as SUMO route files at the end.
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>

#include "app/assignment.hpp"
#include "app/commands.hpp"
#include "app/device_select.hpp"
#include "app/error_report.hpp"
#include "app/part_launcher.hpp"
#include "app/partitioned_parts.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "converters/edge_weights_reader.hpp"
#include "converters/gap_plot_writer.hpp"
#include "converters/route_alternatives_reader.hpp"
#include "converters/route_file_writer.hpp"
#include "core/error.hpp"
#include "transport/mpi/mpi_transport.hpp"

namespace lpsim {
namespace {

// duarouter's name for the alternatives of an output: ".alt" before the final ".xml" (or ".xml.gz").
std::string alternatives_path(const std::string& routes) {
  for (const std::string suffix : {".xml.gz", ".xml"})
    if (routes.size() > suffix.size() &&
        routes.compare(routes.size() - suffix.size(), suffix.size(), suffix) == 0)
      return routes.substr(0, routes.size() - suffix.size()) + ".alt" + suffix;
  return routes + ".alt";
}

void refuse_input_as_output(const ConfigSpec& config, const std::string& out) {
  std::vector<std::string> inputs = config.route_files;
  inputs.insert(inputs.end(), config.additional_files.begin(), config.additional_files.end());
  inputs.push_back(config.net_file);
  inputs.push_back(config.config_file);
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (!in.empty() && std::filesystem::equivalent(in, out, ec))
      throw InputError("lpsim assign: output '" + out + "' is the input '" + in + "'");
  }
}

// duaIterate.py's --max-convergence-deviation: the relative (population) standard deviation of the mean
// trip times of the last `n` iterations.
double relative_deviation(const std::deque<double>& means) {
  double mean = 0;
  for (double m : means) mean += m;
  mean /= double(means.size());
  double sq = 0;
  for (double m : means) sq += (m - mean) * (m - mean);
  return mean > 0 ? std::sqrt(sq / double(means.size())) / mean : 0.0;
}

// What `lpsim assign` loads before any iteration runs: everything that can fail on bad input.
struct LoadedAssignment {
  ConfigSpec config;
  Scenario sc;
  SimulationOptions options;
  int32_t parts = 1;
  std::vector<int32_t> edge_part;
  std::string routes_file, alternatives_file;
  std::unordered_map<std::string, RouteAlternatives> resumed;  // --first-iteration's alternatives
};

void load_assignment(const std::vector<std::string>& args, int ranks, LoadedAssignment* l) {
  l->sc = scenario_from_args(args, &l->config, CliCommand::Assign);
  const ConfigSpec& config = l->config;
  if (ranks > 1 && !config.assign.weight_files.empty())
    throw InputError(
        "lpsim assign --weight-files costs given routes in one process: start it without mpirun");
  if (!config.assign.weight_files.empty()) return;
  if (config.output_file.empty())
    throw InputError(
        "lpsim assign: give -o, the route file the assigned routes go to (e.g. assigned.rou.xml)");
  l->routes_file = config.output_file;
  l->alternatives_file = alternatives_path(config.output_file);
  refuse_input_as_output(config, l->routes_file);
  refuse_input_as_output(config, l->alternatives_file);
  if (!config.assign.plot.empty()) refuse_input_as_output(config, config.assign.plot);
  l->options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  l->options.backend = device.backend;
  if (config.device != ComputeDevice::Cpu && MpiSession::world_rank() == 0)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());
  l->edge_part = run_edge_parts(config, l->sc, ranks, &l->parts);
  require_one_part_per_rank(ranks, l->parts);
  const int first = config.assign.first_iteration;
  if (first > 0) {
    if (!config.snapshot_file.empty())
      throw InputError(
          "--first-iteration reads the alternatives from the route files (-r), not from a snapshot");
    for (const std::string& file : config.route_files)
      l->resumed.merge(read_route_alternatives(file, l->sc.network.edge_index));
    if (l->resumed.empty())
      throw InputError("--first-iteration " + std::to_string(first) +
                       ": no vehicle in the route files has a <routeDistribution> of alternatives (give the "
                       ".rou.alt.xml of the iteration before)");
  }
}

// Routes assigned elsewhere (an iteration of duaIterate.py) on the travel times they met: their gap.
int print_gap_of_given_routes(const LoadedAssignment& l) {
  const ConfigSpec& config = l.config;
  const IntervalTravelTimes times =
      read_edge_weights(config.assign.weight_files, l.sc.network.edge_index, l.sc.network.num_edges());
  const Router router(l.sc.network, simulation_options(config).rerouting.minor_penalty);
  const GapSums g = relative_gap(l.sc.network, router, l.sc.demand, times, config.threads);
  std::printf("vehicles %llu, route cost %.2f s, best route cost %.2f s, relative gap %.6f\n",
              static_cast<unsigned long long>(g.vehicles), g.route_cost_sum, g.best_cost_sum,
              g.relative_gap());
  return 0;
}

}  // namespace

int command_assign(const std::vector<std::string>& args) {
  // Under mpirun every rank loads the scenario and all of them learn whether any failed before an iteration
  // starts (an error is printed once). Each iteration is simulated with one part per rank; every rank routes
  // and chooses alike, and rank 0 alone prints and writes.
  const int ranks = MpiSession::world_size();
  LoadedAssignment loaded;
  load_on_every_rank(ranks, [&] { load_assignment(args, ranks, &loaded); });
  const ConfigSpec& config = loaded.config;
  if (!config.assign.weight_files.empty()) return print_gap_of_given_routes(loaded);
  Scenario& sc = loaded.sc;
  const AssignSpec& spec = config.assign;
  const std::unique_ptr<PartLauncher> launcher =
      launch_parts(ranks, sc, loaded.edge_part, loaded.parts, config.part_timeout);
  Assignment assignment(sc.network, std::move(sc.demand), loaded.options, spec, config.begin, config.end,
                        config.threads, loaded.options.rerouting.contraction_hierarchy);
  assignment.simulate_in(launcher.get());
  if (spec.first_iteration > 0) assignment.resume(spec.first_iteration, loaded.resumed);
  // duaIterate's stops: why the iterations end after result r ("" to go on).
  std::deque<double> means;
  auto stop_reason = [&](const IterationResult& r) -> std::string {
    char text[200];
    if (spec.gap > 0 && r.gap.relative_gap() <= spec.gap) {
      std::snprintf(text, sizeof text, "relative gap %.6f reached --gap %g", r.gap.relative_gap(), spec.gap);
      return text;
    }
    means.push_back(r.mean_trip_time);
    if (means.size() > static_cast<size_t>(spec.convergence_iterations)) means.pop_front();
    if (spec.max_convergence_deviation > 0 &&
        means.size() == static_cast<size_t>(spec.convergence_iterations) &&
        relative_deviation(means) < spec.max_convergence_deviation) {
      std::snprintf(text, sizeof text,
                    "mean trip time deviation %.6f over %d iterations below --max-convergence-deviation %g",
                    relative_deviation(means), spec.convergence_iterations, spec.max_convergence_deviation);
      return text;
    }
    return "";
  };
  // Every rank's iterations give the same results (but for CPU seconds): all stop alike, rank 0 reports.
  const bool reports = launcher->leads();
  if (reports)
    std::printf("%9s %13s %14s %9s %9s %10s %10s %10s %10s\n", "iteration", "relative gap", "mean trip [s]",
                "finished", "teleports", "route CPU", "sim CPU", "sim wall", "wall");
  std::vector<double> gaps;
  for (int i = spec.first_iteration; i < spec.iterations; ++i) {
    const IterationResult r = assignment.iterate();
    if (reports) {
      std::printf("%9d %13.6f %14.2f %9llu %9llu %9.2fs %9.2fs %9.2fs %9.2fs\n", r.iteration,
                  r.gap.relative_gap(), r.mean_trip_time, static_cast<unsigned long long>(r.finished),
                  static_cast<unsigned long long>(r.teleports), r.routing_cpu_seconds,
                  r.simulation_cpu_seconds, r.simulation_wall_seconds, r.wall_seconds);
      std::fflush(stdout);
    }
    gaps.push_back(r.gap.relative_gap());
    const std::string why = stop_reason(r);
    if (!why.empty()) {
      if (reports) std::printf("%s\n", why.c_str());
      break;
    }
  }
  if (!reports) return 0;
  const std::string& routes_file = loaded.routes_file;
  const std::string& alternatives_file = loaded.alternatives_file;
  write_route_file(routes_file, sc.network, assignment.assigned());
  write_route_file(alternatives_file, sc.network, assignment.assigned(), &assignment.alternatives());
  std::printf("routes: %s\nalternatives: %s\n", routes_file.c_str(), alternatives_file.c_str());
  if (!config.assign.plot.empty()) {
    write_gap_plot(config.assign.plot, gaps);
    std::printf("plot: %s\n", config.assign.plot.c_str());
  }
  return 0;
}

}  // namespace lpsim

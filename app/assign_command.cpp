// `lpsim assign`: dynamic user assignment (app/assignment.hpp) from the command line: a line per iteration
// on stdout, the assigned routes and their alternatives written as SUMO route files at the end.
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>

#include "app/assignment.hpp"
#include "app/commands.hpp"
#include "app/device_select.hpp"
#include "app/partitioned_parts.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "converters/edge_weights_reader.hpp"
#include "converters/gap_plot_writer.hpp"
#include "converters/route_alternatives_reader.hpp"
#include "converters/route_file_writer.hpp"
#include "core/error.hpp"

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

}  // namespace

int command_assign(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config, CliCommand::Assign);
  if (!config.assign.weight_files.empty()) {
    // Routes assigned elsewhere (an iteration of duaIterate.py) on the travel times they met.
    const IntervalTravelTimes times =
        read_edge_weights(config.assign.weight_files, sc.network.edge_index, sc.network.num_edges());
    const Router router(sc.network, simulation_options(config).rerouting.minor_penalty);
    const GapSums g = relative_gap(sc.network, router, sc.demand, times, config.threads);
    std::printf("vehicles %llu, route cost %.2f s, best route cost %.2f s, relative gap %.6f\n",
                static_cast<unsigned long long>(g.vehicles), g.route_cost_sum, g.best_cost_sum,
                g.relative_gap());
    return 0;
  }
  if (config.output_file.empty())
    throw InputError(
        "lpsim assign: give -o, the route file the assigned routes go to (e.g. assigned.rou.xml)");
  const std::string routes_file = config.output_file,
                    alternatives_file = alternatives_path(config.output_file);
  refuse_input_as_output(config, routes_file);
  refuse_input_as_output(config, alternatives_file);
  if (!config.assign.plot.empty()) refuse_input_as_output(config, config.assign.plot);
  SimulationOptions options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  options.gpu = device.gpu;
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());

  const AssignSpec& spec = config.assign;
  int32_t parts = 1;
  const std::vector<int32_t> edge_part = run_edge_parts(config, sc, &parts);
  std::vector<PartPlan> plans;
  if (parts > 1) plans = part_plans(sc.network, edge_part, parts, longest_vehicle(sc.demand));
  Assignment assignment(sc.network, std::move(sc.demand), options, spec, config.begin, config.end,
                        config.threads, options.rerouting.contraction_hierarchy);
  if (parts > 1) assignment.run_in_parts(std::move(plans), config.part_timeout);
  if (spec.first_iteration > 0) {
    if (!config.snapshot_file.empty())
      throw InputError(
          "--first-iteration reads the alternatives from the route files (-r), not from a snapshot");
    std::unordered_map<std::string, RouteAlternatives> alternatives;
    for (const std::string& file : config.route_files)
      alternatives.merge(read_route_alternatives(file, sc.network.edge_index));
    if (alternatives.empty())
      throw InputError("--first-iteration " + std::to_string(spec.first_iteration) +
                       ": no vehicle in the route files has a <routeDistribution> of alternatives (give the "
                       ".rou.alt.xml of the iteration before)");
    assignment.resume(spec.first_iteration, alternatives);
  }
  std::printf("%9s %13s %14s %9s %9s %10s %10s\n", "iteration", "relative gap", "mean trip [s]", "finished",
              "teleports", "route CPU", "sim CPU");
  std::deque<double> means;
  std::vector<double> gaps;
  for (int i = spec.first_iteration; i < spec.iterations; ++i) {
    const IterationResult r = assignment.iterate();
    std::printf("%9d %13.6f %14.2f %9llu %9llu %9.2fs %9.2fs\n", r.iteration, r.gap.relative_gap(),
                r.mean_trip_time, static_cast<unsigned long long>(r.finished),
                static_cast<unsigned long long>(r.teleports), r.routing_cpu_seconds,
                r.simulation_cpu_seconds);
    std::fflush(stdout);
    gaps.push_back(r.gap.relative_gap());
    if (spec.gap > 0 && r.gap.relative_gap() <= spec.gap) {
      std::printf("relative gap %.6f reached --gap %g\n", r.gap.relative_gap(), spec.gap);
      break;
    }
    means.push_back(r.mean_trip_time);
    if (means.size() > static_cast<size_t>(spec.convergence_iterations)) means.pop_front();
    if (spec.max_convergence_deviation > 0 &&
        means.size() == static_cast<size_t>(spec.convergence_iterations) &&
        relative_deviation(means) < spec.max_convergence_deviation) {
      std::printf("mean trip time deviation %.6f over %d iterations below --max-convergence-deviation %g\n",
                  relative_deviation(means), spec.convergence_iterations, spec.max_convergence_deviation);
      break;
    }
  }
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

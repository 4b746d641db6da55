#include "app/partitioned_parts.hpp"

#include <algorithm>
#include <cstdio>
#include <tuple>

#include "app/partition_resolution.hpp"
#include "converters/partition_file.hpp"
#include "core/error.hpp"
#include "partition/junction_graph.hpp"
#include "partition/partition_method.hpp"
#include "transport/mpi/mpi_transport.hpp"

namespace lpsim {

void refuse_split_options_without_parts(const ConfigSpec& config) {
  for (const auto& [given, option, what] :
       {std::tuple{config.partition_method_given, "--partition-method", "chooses how"},
        std::tuple{!config.partition_load_from.empty(), "--partition.load-from", "weighs what"}}) {
    if (!given) continue;
    if (!config.partition_file.empty())
      throw InputError(
          std::string(option) + " " + what +
          " --parts splits the network; --partition-file gives the parts already: leave one out");
    if (config.parts < 1)
      throw InputError(std::string(option) + " " + what +
                       " --parts K splits the network: give --parts K as well");
  }
}

double mean_vehicles_per_step(const Scenario& sc, const ConfigSpec& config) {
  const Demand& d = sc.demand;
  const Network& net = sc.network;
  if (d.size() == 0) return 0;
  // A trip's free-flow time: its route's edges at their speed, averaged over every trip (a sample of them in
  // a large demand: the estimate decides only whether parts pay).
  const uint32_t stride = std::max<uint32_t>(1, d.size() / 10000);
  double trip_seconds = 0;
  uint32_t sampled = 0;
  for (uint32_t v = 0; v < d.size(); v += stride, ++sampled)
    for (uint32_t k = 0; k < d.route_length[v]; ++k) {
      const uint32_t e = d.route_edges[d.route_begin[v] + k];
      if (net.edge_speed[e] > 0) trip_seconds += net.edge_length[e] / net.edge_speed[e];
    }
  trip_seconds /= sampled;
  const double first = std::max(config.begin, static_cast<double>(d.depart.front()));
  // The run's end, or the demand's when it has run out before.
  double end = static_cast<double>(d.depart.back()) + trip_seconds;
  if (config.end >= 0) end = std::min(end, config.end);
  // The trips that depart while the run lasts, each on the road for that time or until the run ends.
  double vehicle_seconds = 0;
  for (auto t = std::lower_bound(d.depart.begin(), d.depart.end(), config.begin);
       t != d.depart.end() && *t < end; ++t)
    vehicle_seconds += std::min(trip_seconds, end - static_cast<double>(*t));
  return vehicle_seconds / std::max(config.step_length, end - first);
}

std::vector<int32_t> run_edge_parts(const ConfigSpec& config, const Scenario& sc, int ranks, int32_t* parts) {
  const Network& net = sc.network;
  std::vector<int32_t> junction_part;
  int32_t k = config.parts;
  refuse_split_options_without_parts(config);
  // A run's measured load, when given, in place of the routes in free flow.
  const bool measured = !config.partition_load_from.empty();
  MeasuredLoad load;
  double measured_seconds = 0;
  if (measured && k > 1) load = read_measured_load(config.partition_load_from, net, &measured_seconds);
  if (!config.partition_file.empty()) {
    const PartitionSpec spec = read_partition_file(config.partition_file);
    junction_part = resolve_partition(spec, net, k);
    k = spec.parts;
  } else {
    if (k <= 1) {
      *parts = 1;
      return {};
    }
    if (config.parts_min_vehicles > 0) {
      // A part's step costs its exchange rounds whatever it carries: below some vehicles per part the rounds
      // cost more than the part saves.
      double vehicles = mean_vehicles_per_step(sc, config);
      if (measured) {
        double vehicle_seconds = 0;
        for (const double s : load.vehicle_seconds) vehicle_seconds += s;
        vehicles = vehicle_seconds / std::max(measured_seconds, config.step_length);
      }
      const auto fit = static_cast<int32_t>(
          std::clamp(vehicles / static_cast<double>(config.parts_min_vehicles), 1.0, static_cast<double>(k)));
      if (fit < k) {
        char why[160];
        std::snprintf(why, sizeof why, "about %.0f vehicles per step %s, fewer than %lld per part", vehicles,
                      measured ? "measured" : "in free flow",
                      static_cast<long long>(config.parts_min_vehicles));
        if (ranks > 1) {
          if (!config.no_warnings && MpiSession::world_rank() == 0)
            std::fprintf(stderr,
                         "lpsim: warning: --parts %d: %s: these parts cost more in exchanges than they "
                         "save (%d would pay)\n",
                         k, why, fit);
        } else {
          if (!config.no_warnings)
            std::fprintf(
                stderr,
                "lpsim: warning: --parts %d: %s: running %d part%s, as more would cost more in exchanges "
                "than they save (--parts.min-vehicles 0 keeps %d)\n",
                k, why, fit, fit == 1 ? "" : "s", k);
          k = fit;
          if (k == 1) {
            *parts = 1;
            return {};
          }
        }
      }
    }
    // Built only for the parts that run: a large network's graph takes seconds.
    const PartitionMethod method = *partition_method_from_name(config.partition_method);
    const JunctionGraph g = measured ? build_junction_graph(net, load, config.step_length)
                                     : build_junction_graph(net, sc.demand, config.step_length);
    junction_part = partition_junctions(g, k, method, static_cast<uint64_t>(config.seed));
  }
  *parts = k;
  std::vector<int32_t> edge_part = edge_parts_from_junctions(net, junction_part);
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (!net.edge_is_internal[e] && edge_part[e] < 0) edge_part[e] = 0;
  return edge_part;
}

double longest_vehicle(const Demand& demand) {
  double longest = 0;
  for (const float l : demand.types.length) longest = std::max(longest, static_cast<double>(l));
  return longest;
}

InProcessParts::InProcessParts(const Network& net, const Demand& demand, const SimulationOptions& options,
                               std::vector<PartPlan> plans, double timeout_s)
    : plans_(std::move(plans)), fabric_(static_cast<int>(plans_.size()), timeout_s) {
  const int k = static_cast<int>(plans_.size());
  for (int p = 0; p < k; ++p) endpoints_.push_back(fabric_.endpoint(p));
  errors_.resize(static_cast<size_t>(k));
  for (int p = 1; p < k; ++p) {
    // Each part its own copies: the caller's may be moved into part 0's Run while they start.
    auto network = std::make_shared<Network>(net);
    auto trips = std::make_shared<Demand>(demand);
    SimulationOptions o = options;
    o.part = &plans_[static_cast<size_t>(p)];
    o.transport = endpoints_[static_cast<size_t>(p)].get();
    o.gpu_device = p;  // the machine's GPUs dealt out to the parts in turn
    threads_.emplace_back([this, p, o, network, trips]() {
      try {
        Simulation sim(*network, std::move(*trips), o);
        sim.serve_part();
      } catch (const std::exception& e) {
        errors_[static_cast<size_t>(p)] = e.what();
        fabric_.fail(p, e.what());
      }
    });
  }
}

SimulationOptions InProcessParts::part0_options(SimulationOptions options) const {
  options.part = &plans_[0];
  options.transport = endpoints_[0].get();
  return options;
}

std::string InProcessParts::finish(bool part0_failed) {
  if (finished_) return "";
  finished_ = true;
  if (part0_failed) fabric_.fail(0, "part 0 stopped");
  for (std::thread& t : threads_) t.join();
  for (size_t p = 1; p < errors_.size(); ++p)
    if (!errors_[p].empty()) return "part " + std::to_string(p) + ": " + errors_[p];
  return "";
}

InProcessParts::~InProcessParts() { finish(true); }

}  // namespace lpsim

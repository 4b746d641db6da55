#include <chrono>
#include <cstdint>
#include <string>

#include "app/load_warnings.hpp"
#include "app/option_scopes.hpp"
#include "app/scenario.hpp"
#include "converters/lpsim_csv_reader.hpp"
#include "converters/net_reader.hpp"
#include "converters/route_reader.hpp"
#include "demand/demand_builder.hpp"
#include "net/network_builder.hpp"

namespace lpsim {

namespace {

// SUMO's --tls.all-off: every traffic light runs its "off" program, under which each link keeps the right
// of way netconvert wrote into its connection's state ('O' as a priority link, 'o' as a yield link) and the
// junction's request rows decide the conflicts, as at a priority junction. So the network is built without
// programs and without signal control.
void switch_signals_off(NetSpec& net, AdditionalSpec& additional) {
  net.tl_logics.clear();
  additional.tl_logics.clear();
  for (ConnectionSpec& c : net.connections) {
    if (c.tl.empty()) continue;
    c.tl.clear();
    c.link_index = -1;
  }
}

}  // namespace

Scenario load_scenario(const ConfigSpec& config) {
  auto t0 = std::chrono::steady_clock::now();
  Scenario sc;
  sc.config = config;

  NetSpec net;
  if (!config.net_file.empty()) {
    net = read_sumo_net(config.net_file);
  } else if (!config.lpsim_nodes_csv.empty() && !config.lpsim_edges_csv.empty()) {
    net = read_lpsim_csv_net(config.lpsim_nodes_csv, config.lpsim_edges_csv);
  } else {
    throw InputError("no network given: use -c file.sumocfg, -n file.net.xml or --lpsim-nodes/--lpsim-edges");
  }

  // As SUMO: add-files first (they may define vTypes the routes use), then route files in order.
  DemandSpec demand;
  AdditionalSpec additional;
  for (const auto& f : config.additional_files) read_sumo_routes(f, demand, additional);
  for (const auto& f : config.route_files) read_sumo_routes(f, demand, additional, config.route_steps > 0);
  if (!config.lpsim_od_csv.empty()) read_lpsim_od_csv(config.lpsim_od_csv, net, demand);

  if (config.tls_all_off) switch_signals_off(net, additional);
  sc.warnings = unimplemented_settings(demand, net, additional, config.default_car_follow_model);
  if (std::string line = decide_scoped_options(config, net, demand); !line.empty())
    sc.warnings.push_back(std::move(line));
  NetworkLimits limits;
  limits.max_lane_map_gib = config.max_lane_map_gb;
  limits.max_lane_map_option = "--max-lane-map-gb";
  sc.network = build_network(net, additional.tl_logics, limits);
  DemandOptions opt;
  opt.seed = static_cast<uint64_t>(config.seed);
  opt.ignore_route_errors = config.ignore_route_errors;
  opt.threads = config.threads;
  opt.begin = config.begin;
  opt.end = config.end;
  opt.step_length = config.step_length;
  opt.minor_penalty = config.minor_penalty;
  opt.contraction_hierarchy = config.routing_algorithm == "CH" || config.routing_algorithm == "CHWrapper";
  opt.random_factor = config.weights_random_factor;
  opt.default_car_follow_model = config.default_car_follow_model;
  opt.rerouting = config.rerouting;
  sc.demand = build_demand(demand, sc.network, opt);
  if (const uint64_t n = sc.demand.raised_speed_factors; n > 0)
    sc.warnings.push_back(
        "departSpeed above the first edge's speed limit times the drawn speed factor: as "
        "SUMO does, the speed factor was raised to match for " +
        std::to_string(n) + (n == 1 ? " vehicle: '" : " vehicles, the first '") +
        sc.demand.first_raised_speed_factor + "'");
  if (const int64_t n = demand.unsorted_ignored; n > 0)
    sc.warnings.push_back(
        "route file not sorted by departure time: as SUMO does, " + std::to_string(n) +
        (n == 1 ? " vehicle or flow listed after a later departure was ignored: '"
                : " vehicles and flows listed after a later departure were ignored, the first '") +
        demand.first_unsorted_ignored + "' (" + demand.first_unsorted_loc.str() +
        "); --route-steps 0 loads them");
  sc.mean_data = std::move(additional.mean_data);
  sc.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sc;
}

}  // namespace lpsim

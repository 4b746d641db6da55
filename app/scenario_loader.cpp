#include <chrono>
#include <cstdint>
#include <string>

#include "app/load_warnings.hpp"
#include "app/scenario.hpp"
#include "converters/lpsim_csv_reader.hpp"
#include "converters/net_reader.hpp"
#include "converters/route_reader.hpp"
#include "demand/demand_builder.hpp"
#include "net/network_builder.hpp"

namespace lpsim {

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
  for (const auto& f : config.route_files) read_sumo_routes(f, demand, additional);
  if (!config.lpsim_od_csv.empty()) read_lpsim_od_csv(config.lpsim_od_csv, net, demand);

  sc.warnings = unimplemented_settings(demand, net, additional, config.default_car_follow_model);
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
  opt.default_car_follow_model = config.default_car_follow_model;
  sc.demand = build_demand(demand, sc.network, opt);
  if (const uint64_t n = sc.demand.raised_speed_factors; n > 0)
    sc.warnings.push_back(
        "departSpeed above the first edge's speed limit times the drawn speed factor: as "
        "SUMO does, the speed factor was raised to match for " +
        std::to_string(n) + (n == 1 ? " vehicle: '" : " vehicles, the first '") +
        sc.demand.first_raised_speed_factor + "'");
  sc.mean_data = std::move(additional.mean_data);
  sc.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sc;
}

}  // namespace lpsim

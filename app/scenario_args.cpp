#include "app/scenario_args.hpp"

#include <cstdio>

#include "app/info_report.hpp"
#include "app/snapshot.hpp"

namespace lpsim {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A snapshot holds network, demand and output definitions: input options beside it would be ignored.
void refuse_inputs_beside_snapshot(const ConfigSpec& c, const std::string& snapshot, CliCommand command) {
  const char* given = !c.config_file.empty()        ? "-c (configuration-file)"
                      : !c.net_file.empty()         ? "-n (net-file)"
                      : !c.route_files.empty()      ? "-r (route-files)"
                      : !c.additional_files.empty() ? "-a (additional-files)"
                      : !c.lpsim_nodes_csv.empty()  ? "--lpsim-nodes"
                      : !c.lpsim_edges_csv.empty()  ? "--lpsim-edges"
                      : !c.lpsim_od_csv.empty()     ? "--lpsim-od"
                                                    : nullptr;
  if (given)
    throw InputError(SourceLoc{"command line", 0},
                     std::string(given) + " given beside the snapshot '" + snapshot +
                         "', which already holds network and demand; give one or the other");
  // Options that act only while loading: the snapshot was loaded by `lpsim convert`, with its own. `assign`
  // routes every iteration with the router and costs these name.
  const ConfigSpec defaults;
  const bool routes_again = command == CliCommand::Assign;
  const char* load_only =
      c.ignore_route_errors != defaults.ignore_route_errors                ? "--ignore-route-errors"
      : c.minor_penalty != defaults.minor_penalty && !routes_again         ? "--weights.minor-penalty"
      : c.routing_algorithm != defaults.routing_algorithm && !routes_again ? "--routing-algorithm"
      : c.max_lane_map_gb != defaults.max_lane_map_gb                      ? "--max-lane-map-gb"
      : c.tls_all_off != defaults.tls_all_off                              ? "--tls.all-off"
      : c.weights_random_factor != defaults.weights_random_factor          ? "--weights.random-factor"
      : c.default_car_follow_model != defaults.default_car_follow_model    ? "--default.carfollowmodel"
      : c.rerouting.probability != defaults.rerouting.probability          ? "--device.rerouting.probability"
      : !c.rerouting.explicit_ids.empty()                                  ? "--device.rerouting.explicit"
      : c.rerouting.deterministic != defaults.rerouting.deterministic ? "--device.rerouting.deterministic"
                                                                      : nullptr;
  if (load_only)
    throw InputError(SourceLoc{"command line", 0}, std::string(load_only) + " given beside the snapshot '" +
                                                       snapshot +
                                                       "': it acts while loading; give it to lpsim convert");
  // What a scoped option acts on is in the scenario's files, which a snapshot no longer has.
  if (!c.scoped_options.empty())
    throw InputError(c.scoped_options.front().loc,
                     "--" + c.scoped_options.front().name + " given beside the snapshot '" + snapshot +
                         "': whether it can act depends on the scenario's files; give it to lpsim convert");
  if (c.seed != defaults.seed)
    std::fprintf(stderr,
                 "lpsim: warning: --seed beside the snapshot '%s' seeds the simulation's own draws only; the "
                 "demand's (flows, distributions, speed factors) were drawn by lpsim convert\n",
                 snapshot.c_str());
}

// The loader takes a SUMO network when there is one and then never reads LPSim's CSV network (the OD CSV is
// read against either network, so it combines with both); a CSV network needs both of its files.
void refuse_ignored_csv(const ConfigSpec& c) {
  const bool csv_net = !c.lpsim_nodes_csv.empty() || !c.lpsim_edges_csv.empty();
  if (csv_net && !c.net_file.empty())
    throw InputError(std::string(!c.lpsim_nodes_csv.empty() ? "--lpsim-nodes" : "--lpsim-edges") +
                     " given beside the SUMO network '" + c.net_file +
                     "' (-n or the .sumocfg's net-file): a run takes one network");
  if (csv_net && (c.lpsim_nodes_csv.empty() || c.lpsim_edges_csv.empty()))
    throw InputError(std::string(c.lpsim_nodes_csv.empty() ? "--lpsim-edges" : "--lpsim-nodes") + " needs " +
                     (c.lpsim_nodes_csv.empty() ? "--lpsim-nodes" : "--lpsim-edges") + " too");
}

void warn_inert(const ConfigSpec& c) {
  if (c.inert_options.empty()) return;
  std::string names;
  for (const auto& n : c.inert_options) names += (names.empty() ? "" : ", ") + n;
  std::fprintf(stderr, "lpsim: warning: ignoring SUMO options that cannot change LPSim's results: %s\n",
               names.c_str());
}

}  // namespace

Scenario scenario_from_args(const std::vector<std::string>& args, ConfigSpec* config_out,
                            CliCommand command) {
  std::vector<std::string> positional;
  ConfigSpec config = parse_cli_options(args, &positional, command);
  if (positional.size() > 1) throw InputError("expected at most one input file, got '" + positional[1] + "'");
  if (positional.size() == 1) {
    const std::string& file = positional[0];
    if (is_snapshot(file)) {
      refuse_inputs_beside_snapshot(config, file, command);
      warn_inert(config);
      Scenario sc = read_snapshot(file);
      config.snapshot_file = file;
      sc.config = config;
      if (config_out) *config_out = config;
      return sc;
    }
    if (!ends_with(file, ".sumocfg") && !ends_with(file, ".xml"))
      throw InputError(SourceLoc{file, 0}, "not a snapshot and not a .sumocfg");
    std::vector<std::string> with_cfg{"-c", file};
    for (const auto& a : args)
      if (a != file) with_cfg.push_back(a);
    config = parse_cli_options(with_cfg, nullptr, command);
  }
  refuse_ignored_csv(config);
  // --no-warnings silences every warning, as SUMO's does (`lpsim info` still lists what loads unmodelled).
  if (!config.no_warnings) warn_inert(config);
  if (config_out) *config_out = config;
  Scenario sc = load_scenario(config);
  if (config.no_warnings) return sc;
  std::string unsupported = unsupported_summary(sc.demand);
  if (!unsupported.empty()) std::fprintf(stderr, "lpsim: warning: %s\n", unsupported.c_str());
  for (const auto& line : sc.warnings) std::fprintf(stderr, "lpsim: warning: %s\n", line.c_str());
  if (!sc.demand.unroutable.empty())
    std::fprintf(stderr,
                 "lpsim: warning: %zu vehicles skipped (route outside the road lane map, or broken with "
                 "--ignore-route-errors); `lpsim info` lists them\n",
                 sc.demand.unroutable.size());
  return sc;
}

}  // namespace lpsim

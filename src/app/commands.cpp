#include "app/commands.hpp"

#include <cstdio>

#include "app/info_report.hpp"
#include "app/scenario.hpp"
#include "app/snapshot.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A scenario from options: `-c`/`-n`/... or one positional argument that is a snapshot or a .sumocfg.
Scenario scenario_from_args(const std::vector<std::string>& args, ConfigSpec* config_out = nullptr) {
  std::vector<std::string> positional;
  ConfigSpec config = parse_cli_options(args, &positional);
  if (positional.size() > 1) throw InputError("expected at most one input file, got '" + positional[1] + "'");
  if (positional.size() == 1) {
    const std::string& file = positional[0];
    if (is_snapshot(file)) {
      Scenario sc = read_snapshot(file);
      sc.config = config;
      if (config_out) *config_out = config;
      return sc;
    }
    if (!ends_with(file, ".sumocfg") && !ends_with(file, ".xml"))
      throw InputError(SourceLoc{file, 0}, "not a snapshot and not a .sumocfg");
    std::vector<std::string> with_cfg{"-c", file};
    for (const auto& a : args)
      if (a != file) with_cfg.push_back(a);
    config = parse_cli_options(with_cfg, nullptr);
  }
  if (config_out) *config_out = config;
  Scenario sc = load_scenario(config);
  std::string unsupported = unsupported_summary(sc.demand);
  if (!unsupported.empty()) std::fprintf(stderr, "lpsim: warning: %s\n", unsupported.c_str());
  if (!sc.demand.unroutable.empty())
    std::fprintf(stderr, "lpsim: warning: %zu vehicles skipped (unroutable or broken routes, --ignore-route-errors)\n",
                 sc.demand.unroutable.size());
  return sc;
}

}  // namespace

int command_info(const std::vector<std::string>& args) {
  Scenario sc = scenario_from_args(args);
  std::fputs(describe_scenario(sc).c_str(), stdout);
  return 0;
}

int command_convert(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config);
  if (config.output_file.empty()) throw InputError("convert needs -o <file.lpsim>");
  write_snapshot(sc, config.output_file);
  std::printf("wrote %s: %u edges, %u lanes, %u vehicles\n", config.output_file.c_str(), sc.network.num_edges(),
              sc.network.num_lanes(), sc.demand.size());
  return 0;
}

}  // namespace lpsim

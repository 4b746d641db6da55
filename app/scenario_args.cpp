#include "app/scenario_args.hpp"

#include <cstdio>

#include "app/info_report.hpp"
#include "app/snapshot.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Scenario scenario_from_args(const std::vector<std::string>& args, ConfigSpec* config_out) {
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
  for (const auto& line : sc.warnings) std::fprintf(stderr, "lpsim: warning: %s\n", line.c_str());
  if (!sc.demand.unroutable.empty())
    std::fprintf(stderr,
                 "lpsim: warning: %zu vehicles skipped (route outside the car lane map, or broken with "
                 "--ignore-route-errors); `lpsim info` lists them\n",
                 sc.demand.unroutable.size());
  return sc;
}

}  // namespace lpsim

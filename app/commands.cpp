#include "app/commands.hpp"

#include <cstdio>

#include "app/info_report.hpp"
#include "app/output_paths.hpp"
#include "app/scenario.hpp"
#include "app/scenario_args.hpp"
#include "app/snapshot.hpp"

namespace lpsim {

int command_info(const std::vector<std::string>& args) {
  Scenario sc = scenario_from_args(args, nullptr, CliCommand::Info);
  std::fputs(describe_scenario(sc).c_str(), stdout);
  return 0;
}

int command_convert(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config, CliCommand::Convert);
  if (config.output_file.empty()) throw InputError("convert needs -o <file.lpsim>");
  refuse_overwrites(sc, CliCommand::Convert);
  write_snapshot(sc, config.output_file);
  std::printf("wrote %s: %u edges, %u lanes, %u vehicles\n", config.output_file.c_str(),
              sc.network.num_edges(), sc.network.num_lanes(), sc.demand.size());
  return 0;
}

}  // namespace lpsim

#pragma once
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

/// The scenario a command names: `-c`/`-n`/`-r`/... options, or one positional argument that is a snapshot
/// or a .sumocfg (further options override it). `command` decides which options are accepted (run, the
/// default, takes the most). Refuses inputs that would be silently ignored: input options beside a
/// snapshot, LPSim CSV networks beside a SUMO one. Prints the load warnings (options that cannot change the
/// results, skipped elements and vehicles). The merged options go to `config_out` when given.
Scenario scenario_from_args(const std::vector<std::string>& args, ConfigSpec* config_out = nullptr,
                            CliCommand command = CliCommand::Run);

}  // namespace lpsim

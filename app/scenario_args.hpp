#pragma once
#include <string>
#include <vector>

#include "app/scenario.hpp"

namespace lpsim {

/// The scenario a command names: `-c`/`-n`/`-r`/... options, or one positional argument that is a snapshot
/// or a .sumocfg (further options override it). Prints the load warnings (skipped elements and vehicles).
/// The merged options go to `config_out` when given.
Scenario scenario_from_args(const std::vector<std::string>& args, ConfigSpec* config_out = nullptr);

}  // namespace lpsim

#pragma once
// A loaded scenario: everything a run needs, built from a ConfigSpec (a .sumocfg and/or options).
#include <string>
#include <vector>

#include "core/additional_spec.hpp"
#include "core/config_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

struct Scenario {
  ConfigSpec config;
  Network network;
  Demand demand;
  std::vector<MeanDataSpec> mean_data;
  // Settings loaded but not modelled (app/load_warnings.hpp), one warning line each; not kept in snapshots.
  std::vector<std::string> warnings;
  double load_seconds = 0;
};

/// Reads every input the config names (SUMO XML or LPSim CSV), builds network and demand.
Scenario load_scenario(const ConfigSpec& config);

}  // namespace lpsim

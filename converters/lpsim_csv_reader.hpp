#pragma once
#include <string>

#include "core/demand_spec.hpp"
#include "core/net_spec.hpp"

namespace lpsim {

/// Reads the original LPSim network: nodes.csv (osmid,x,y,...) and edges.csv in either header the original
/// used. Lanes, speeds (mph) and lengths come from edges.csv; connections and signal programs are derived.
NetSpec read_lpsim_csv_net(const std::string& nodes_csv, const std::string& edges_csv);

/// Reads an LPSim OD demand CSV (dep_time, origin, destination; origin/destination dense node indices).
void read_lpsim_od_csv(const std::string& path, const NetSpec& net, DemandSpec& demand);

}  // namespace lpsim

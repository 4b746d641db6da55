#pragma once
#include <string>

#include "core/net_spec.hpp"

namespace lpsim {

/// Reads a SUMO .net.xml or .net.xml.gz (streaming). Lanes a passenger car may not use are dropped and
/// counted in NetSpec::skipped_non_car_lanes; edges left without car lanes are kept with no lanes.
NetSpec read_sumo_net(const std::string& path);

}  // namespace lpsim

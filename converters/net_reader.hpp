#pragma once
#include <string>

#include "core/net_spec.hpp"

namespace lpsim {

/// Reads a SUMO .net.xml or .net.xml.gz (streaming). Every lane is kept with its vClass permissions
/// resolved; lanes no vehicle may use (sidewalks, crossings, walking areas) are counted in
/// NetSpec::skipped_non_car_lanes (the builder drops them).
NetSpec read_sumo_net(const std::string& path);

}  // namespace lpsim

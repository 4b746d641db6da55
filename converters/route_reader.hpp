#pragma once
#include <string>

#include "core/additional_spec.hpp"
#include "core/demand_spec.hpp"

namespace lpsim {

/// Reads a SUMO route file or add-file (both may hold vTypes, routes, vehicles, trips, flows;
/// add-files also tlLogic programs and edgeData/laneData definitions). Unsupported elements (persons,
/// containers, stops, detectors, ...) are counted per element name in DemandSpec::skipped.
void read_sumo_routes(const std::string& path, DemandSpec& demand, AdditionalSpec& additional);

}  // namespace lpsim

#pragma once
#include <string>

#include "core/additional_spec.hpp"
#include "core/demand_spec.hpp"

namespace lpsim {

/// Reads a SUMO route file or add-file (both may hold vTypes, routes, vehicles, trips, flows;
/// add-files also tlLogic programs and edgeData/laneData definitions). Unsupported elements (persons,
/// containers, stops, detectors, ...) are counted per element name in DemandSpec::skipped.
/// `sorted_by_depart`: the file is a route file SUMO reads ahead by departure time (--route-steps > 0), so a
/// vehicle, trip or flow departing before one listed ahead of it is ignored and counted, as SUMO does.
void read_sumo_routes(const std::string& path, DemandSpec& demand, AdditionalSpec& additional,
                      bool sorted_by_depart = false);

}  // namespace lpsim

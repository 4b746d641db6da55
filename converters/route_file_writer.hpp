#pragma once
// A demand's vehicles with their routes as a SUMO route file, as duarouter writes its output: the vTypes
// the vehicles use, then each vehicle (by depart) with its depart and arrival attributes, its route (or its
// route alternatives as a <routeDistribution>: duarouter's .rou.alt.xml) and its stops. sumo, duarouter and
// `lpsim run` load it.
#include <string>
#include <vector>

#include "demand/demand.hpp"
#include "demand/route_choice.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Writes `d`'s vehicles with their routes to `path`. With `alternatives` (one per vehicle), a vehicle
/// that has some is written with them as <routeDistribution last="..."> of routes with cost and
/// probability, as duarouter's .rou.alt.xml. The vTypes carry the parameters LPSim models (what they
/// were loaded with that LPSim does not model is not written). An InputError when the file cannot be
/// written.
void write_route_file(const std::string& path, const Network& net, const Demand& d,
                      const std::vector<RouteAlternatives>* alternatives = nullptr);

}  // namespace lpsim

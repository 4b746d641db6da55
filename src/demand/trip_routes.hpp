#pragma once
// A trip's routing request and new routes for a demand's vehicles: what routing a whole demand again needs
// (the rerouting device before departure, `lpsim assign` between iterations).
#include <cstdint>
#include <vector>

#include "demand/demand.hpp"
#include "net/network.hpp"
#include "net/router.hpp"

namespace lpsim {

/// Vehicle v's whole trip as a routing request: from its route's first edge to its last, through its via
/// edges and then its stops' edges in order, for its type's vClass.
RouteRequest trip_request(const Demand& d, const Network& net, uint32_t v);

/// Where each of vehicle v's stops lies on `route` (from its start): the first pass of its edge after the
/// stop before. Empty when one is not on it.
std::vector<uint32_t> stop_positions(const Demand& d, const Network& net, uint32_t v,
                                     const std::vector<uint32_t>& route);

/// Gives vehicle v the route routes[v] where that is not empty, its stops placed along it; a vehicle with a
/// stop not on its new route keeps its old one. `route_edges` is rebuilt (routes no longer shared), so the
/// demand takes no more room than its routes.
void replace_routes(Demand& d, const Network& net, const std::vector<std::vector<uint32_t>>& routes);

}  // namespace lpsim

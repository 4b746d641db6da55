#pragma once
// The route alternatives of a duarouter-style .rou.alt.xml (what `lpsim assign` writes beside its routes):
// per vehicle its <routeDistribution last="..."> of routes with cost and probability, for an assignment to
// go on from.
#include <string>
#include <unordered_map>

#include "demand/route_choice.hpp"

namespace lpsim {

/// Vehicle id -> its alternatives, for the vehicles of `path` that have a nested <routeDistribution> whose
/// routes give edges, cost and probability. Edges are resolved by `edge_index`; an unknown edge, a missing
/// attribute or a `last` beyond the routes is an InputError naming file:line.
std::unordered_map<std::string, RouteAlternatives> read_route_alternatives(
    const std::string& path, const std::unordered_map<std::string, uint32_t>& edge_index);

}  // namespace lpsim

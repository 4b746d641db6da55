#pragma once
// A corridor file's objects resolved against the network: the edges SUMO simulates in a co-simulation.
#include <stdint.h>

#include <vector>

#include "core/corridor_spec.hpp"
#include "net/network.hpp"

namespace lpsim {

/// The corridor's normal edges, ascending, each once (a lane names its edge). An InputError naming file:line
/// for an edge or lane the network does not have, or an internal one (a junction's inside is simulated by
/// whichever side drives the roads around it).
std::vector<uint32_t> resolve_corridor(const CorridorSpec& spec, const Network& net);

/// The corridor closed over its junctions: with every edge it holds, every other normal edge into the same
/// junction (ascending). One simulator then drives every approach of a junction, so its right of way and
/// signals see all the junction's traffic: neither SUMO nor LPSim sees the other's vehicles approach, and a
/// junction whose approaches were split would let both streams go as if alone. (The partitioned engine keeps
/// a junction's approaches in one part for the same reason.)
std::vector<uint32_t> close_corridor(const std::vector<uint32_t>& edges, const Network& net);

}  // namespace lpsim

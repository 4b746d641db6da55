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

}  // namespace lpsim

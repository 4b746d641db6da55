#pragma once
// The corridor file of `lpsim cosim --corridor`: the edges SUMO simulates, as sumo-gui and netedit save a
// selection ("Save" in the selection dialog), one object per line:
//
//   edge:<id>      an edge
//   lane:<id>      a lane: its edge
//   <kind>:<id>    another kind of object (junction, vehicle, ...): not part of the corridor, counted
//                  (the caller warns); a kind SUMO has no element for (Edge:, ...) is an error
//   <id>           an edge (a plain list of edge ids)
//
// Blank lines and lines starting with '#' are ignored; surrounding whitespace and a UTF-8 byte-order mark
// are not part of an id.
#include <string>

#include "core/corridor_spec.hpp"

namespace lpsim {

/// Reads a corridor file; an InputError naming the file when it cannot be read or names nothing, or file:line
/// for a line that is not one object. Whether its edges exist is for the caller (resolve_corridor).
CorridorSpec read_corridor_file(const std::string& path);

}  // namespace lpsim

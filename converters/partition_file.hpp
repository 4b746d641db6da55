#pragma once
// The partition file of `lpsim partition` (read by `lpsim run --partition-file`): plain text, one normal edge
// per line after a header.
//
//   # comments: lines starting with '#' (the writer names method, seed and network there)
//   parts K                 the number of parts, before any edge
//   <edge id> <part>        every normal edge of the network once, part in 0..K-1, one space between
//
// Blank lines are ignored. Edge ids are SUMO's (they hold no whitespace).
#include <string>
#include <vector>

#include "core/partition_spec.hpp"

namespace lpsim {

/// Writes `parts` (a part per entry of edge_id) with `comment` lines (without the '#') first.
void write_partition_file(const std::string& path, const std::vector<std::string>& comment, int32_t parts,
                          const std::vector<std::string>& edge_id, const std::vector<int32_t>& part);

/// Reads a partition file; a malformed line is an InputError naming file:line. Whether the edges and the part
/// count fit a network is for the caller to check (resolve_partition in app/).
PartitionSpec read_partition_file(const std::string& path);

}  // namespace lpsim

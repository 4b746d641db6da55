#pragma once
// A partition file as read: the part of each named edge (converters/partition_file.hpp says the format).
#include <stdint.h>

#include <string>
#include <vector>

#include "core/error.hpp"

namespace lpsim {

/// The most parts a run may have (--parts, a partition file's `parts`); a network's junctions bound it too.
inline constexpr int32_t kMaxParts = 1000000;

struct PartitionSpec {
  SourceLoc loc;      // the file (line 0) and, for `parts`, where it was set
  int32_t parts = 0;  // the part count the file declares
  std::vector<std::string> edge_id;
  std::vector<int32_t> part;
  std::vector<int> line;  // of each edge's entry
};

}  // namespace lpsim

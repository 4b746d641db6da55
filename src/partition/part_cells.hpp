#pragma once
// Where each part keeps the lane-map cells of the lanes it holds: the cells of its owned lanes first, then
// its ghost lanes', each in lane order.
#include <stdint.h>

#include <vector>

#include "net/network.hpp"
#include "partition/partition_layout.hpp"

namespace lpsim {

inline constexpr uint64_t kNoCells = ~uint64_t{0};

struct PartCells {
  std::vector<uint64_t> cell_begin;  // per lane of the network: its first cell in the part's map, or kNoCells
  uint64_t owned_cells = 0;          // cells [0, owned_cells) are the owned lanes', the rest the ghosts'
  uint64_t cells = 0;
};

/// The cell layout of one part.
PartCells part_cells(const Network& net, const PartLayout& part);

}  // namespace lpsim

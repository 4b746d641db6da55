#pragma once
// Where each part keeps the lane-map cells of its lanes, and the copies that bring its ghost lanes up to date
// from their owners before each plan (the partitioned step's forward_comm): every part holds the network's
// static columns whole, and only the cells of its owned lanes (first) and ghost lanes (after), in lane order.
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

/// A run of cells copied from the owner's map (from) into a part's map (to).
struct CellRun {
  uint64_t from = 0, to = 0, count = 0;
};

/// What a part receives from one owner before plan: runs over its ghost lanes, contiguous runs merged.
struct GhostFeed {
  int32_t owner = 0;
  std::vector<CellRun> runs;
  uint64_t cells = 0;  // their total: the bytes of one forward exchange
};

/// Per part, its feeds, one per owner of its ghost lanes, owners ascending.
std::vector<std::vector<GhostFeed>> forward_plan(const std::vector<PartLayout>& layout,
                                                 const std::vector<PartCells>& cells,
                                                 const std::vector<int32_t>& lane_part, const Network& net);

/// Applies one feed: copies the owner's cells into the part's map.
void apply_feed(const GhostFeed& feed, const uint8_t* owner_map, uint8_t* part_map);

}  // namespace lpsim

#include "partition/part_cells.hpp"

namespace lpsim {

PartCells part_cells(const Network& net, const PartLayout& part) {
  PartCells c;
  c.cell_begin.assign(net.num_lanes(), kNoCells);
  auto place = [&](uint32_t l) {
    c.cell_begin[l] = c.cells;
    c.cells += net.lane_cell_begin[l + 1] - net.lane_cell_begin[l];
  };
  for (uint32_t l : part.owned) place(l);
  c.owned_cells = c.cells;
  for (uint32_t l : part.ghosts) place(l);
  return c;
}

}  // namespace lpsim

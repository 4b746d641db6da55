#include "partition/exchange_plan.hpp"

#include <cstring>
#include <map>

namespace lpsim {

namespace {
uint64_t lane_cells(const Network& net, uint32_t l) {
  return net.lane_cell_begin[l + 1] - net.lane_cell_begin[l];
}
}  // namespace

PartCells part_cells(const Network& net, const PartLayout& part) {
  PartCells c;
  c.cell_begin.assign(net.num_lanes(), kNoCells);
  for (uint32_t l : part.owned) c.cell_begin[l] = c.cells, c.cells += lane_cells(net, l);
  c.owned_cells = c.cells;
  for (uint32_t l : part.ghosts) c.cell_begin[l] = c.cells, c.cells += lane_cells(net, l);
  return c;
}

std::vector<std::vector<GhostFeed>> forward_plan(const std::vector<PartLayout>& layout,
                                                 const std::vector<PartCells>& cells,
                                                 const std::vector<int32_t>& lane_part, const Network& net) {
  std::vector<std::vector<GhostFeed>> plan(layout.size());
  for (size_t p = 0; p < layout.size(); ++p) {
    std::map<int32_t, GhostFeed> by_owner;
    for (uint32_t l : layout[p].ghosts) {
      const int32_t owner = lane_part[l];
      GhostFeed& f = by_owner[owner];
      f.owner = owner;
      const CellRun run{cells[static_cast<size_t>(owner)].cell_begin[l], cells[p].cell_begin[l],
                        lane_cells(net, l)};
      if (!f.runs.empty() && f.runs.back().from + f.runs.back().count == run.from &&
          f.runs.back().to + f.runs.back().count == run.to)
        f.runs.back().count += run.count;
      else
        f.runs.push_back(run);
      f.cells += run.count;
    }
    for (auto& [owner, feed] : by_owner) plan[p].push_back(std::move(feed));
  }
  return plan;
}

void apply_feed(const GhostFeed& feed, const uint8_t* owner_map, uint8_t* part_map) {
  for (const CellRun& r : feed.runs) std::memcpy(part_map + r.to, owner_map + r.from, r.count);
}

}  // namespace lpsim

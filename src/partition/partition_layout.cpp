#include "partition/partition_layout.hpp"

#include <functional>
#include <queue>
#include <utility>

namespace lpsim {

namespace {

// Lanes reachable from lane l in one move: an outgoing connection's internal lane, else its target lane.
template <class Visit>
void for_each_next(const Network& net, uint32_t l, Visit visit) {
  for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c) {
    const int32_t via = net.conn_via_lane[c];
    visit(via >= 0 ? static_cast<uint32_t>(via) : net.conn_to_lane[c]);
  }
}

// Lanes of other parts than p within `limit` metres of p's boundary, walking from every lane of p along
// `neighbours` (successors or predecessors): a Dijkstra whose distance is the length of the foreign lanes
// passed before reaching a lane (a lane of p resets it to 0).
void add_within(const Network& net, const std::vector<int32_t>& lane_part, int32_t p,
                const std::vector<std::vector<uint32_t>>& neighbours, double limit,
                std::vector<uint8_t>& ghost) {
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  std::vector<double> best(net.num_lanes(), limit);
  for (uint32_t l = 0; l < net.num_lanes(); ++l)
    if (lane_part[l] == p)
      for (uint32_t n : neighbours[l])
        if (lane_part[n] != p && best[n] > 0) best[n] = 0, queue.push({0.0, n});
  while (!queue.empty()) {
    const auto [d, l] = queue.top();
    queue.pop();
    if (d > best[l]) continue;
    ghost[l] = 1;
    const double next = d + net.lane_length[l];
    if (next >= limit) continue;
    for (uint32_t n : neighbours[l])
      if (lane_part[n] != p && next < best[n]) best[n] = next, queue.push({next, n});
  }
}

}  // namespace

std::vector<PartLayout> partition_layout(const Network& net, const std::vector<int32_t>& lane_part,
                                         int32_t parts, double look_ahead, double tail) {
  const uint32_t n = net.num_lanes();
  std::vector<std::vector<uint32_t>> next(n), prev(n);
  for (uint32_t l = 0; l < n; ++l)
    for_each_next(net, l, [&](uint32_t m) {
      next[l].push_back(m);
      prev[m].push_back(l);
    });
  std::vector<PartLayout> layout(static_cast<size_t>(parts));
  for (int32_t p = 0; p < parts; ++p) {
    std::vector<uint8_t> ghost(n, 0);
    add_within(net, lane_part, p, next, look_ahead, ghost);
    add_within(net, lane_part, p, prev, tail, ghost);
    // A ghost edge comes whole: the step's lane logic (best lanes, neighbours) assumes an edge's every lane.
    for (uint32_t l = 0; l < n; ++l) {
      if (!ghost[l]) continue;
      const uint32_t e = net.lane_edge[l];
      for (uint32_t m = net.edge_first_lane[e]; m < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++m)
        ghost[m] = 1;
    }
    PartLayout& part = layout[static_cast<size_t>(p)];
    for (uint32_t l = 0; l < n; ++l) {
      const uint64_t cells = net.lane_cell_begin[l + 1] - net.lane_cell_begin[l];
      if (lane_part[l] == p) {
        part.owned.push_back(l);
        part.owned_cells += cells;
      } else if (ghost[l]) {
        part.ghosts.push_back(l);
        part.ghost_cells += cells;
      }
    }
  }
  return layout;
}

}  // namespace lpsim

#include "partition/partition_summary.hpp"

#include <algorithm>
#include <set>

#include "partition/partition_layout.hpp"

namespace lpsim {

std::vector<int32_t> lane_parts(const Network& net, const std::vector<int32_t>& edge_part) {
  std::vector<int32_t> part(net.num_lanes(), kNone);
  for (uint32_t l = 0; l < net.num_lanes(); ++l) part[l] = edge_part[net.lane_edge[l]];
  // Internal lanes follow the lane that leads into them; chains through internal junctions take a few
  // passes (each pass reaches one internal lane further).
  for (bool changed = true; changed;) {
    changed = false;
    for (uint32_t l = 0; l < net.num_lanes(); ++l) {
      if (part[l] == kNone) continue;
      for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c) {
        const int32_t via = net.conn_via_lane[c];
        const uint32_t to = net.conn_to_lane[c];
        const int32_t next =
            via >= 0 ? via : (net.edge_is_internal[net.lane_edge[to]] ? static_cast<int32_t>(to) : kNone);
        if (next >= 0 && part[static_cast<uint32_t>(next)] == kNone) {
          part[static_cast<uint32_t>(next)] = part[l];
          changed = true;
        }
      }
    }
  }
  return part;
}

int32_t cut_source_part(const Network& net, const std::vector<int32_t>& junction_part,
                        const std::vector<int32_t>& edge_part, uint32_t e) {
  const int32_t from = net.edge_from_junction[e];
  if (edge_part[e] == kNone || from < 0) return kNone;
  const int32_t source = junction_part[static_cast<uint32_t>(from)];
  return source == edge_part[e] ? kNone : source;
}

PartitionSummary summarize_partition(const Network& net, const Demand& demand,
                                     const std::vector<int32_t>& junction_part, int32_t k, double dt) {
  PartitionSummary s;
  s.parts.resize(static_cast<size_t>(k));
  for (uint32_t j = 0; j < junction_part.size(); ++j)
    if (j >= net.junction_type.size() || net.junction_type[j] != JunctionType::Internal)
      ++s.parts[static_cast<size_t>(junction_part[j])].junctions;
  // A departure is no migration: a cut road's entries are.
  const auto [uses, entries] = count_route_uses(demand, net.num_edges());
  const std::vector<int32_t> edge_part = edge_parts_from_junctions(net, junction_part);
  const std::vector<int32_t> lane_part = lane_parts(net, edge_part);
  for (uint32_t l = 0; l < net.num_lanes(); ++l) {
    if (lane_part[l] == kNone) continue;
    PartSummary& ps = s.parts[static_cast<size_t>(lane_part[l])];
    ++ps.lanes;
    ps.lane_km += net.lane_length[l] / 1000.0;
  }
  std::vector<std::set<int32_t>> neighbours(static_cast<size_t>(k));
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (edge_part[e] == kNone) continue;
    PartSummary& ps = s.parts[static_cast<size_t>(edge_part[e])];
    ps.vehicle_steps += uses[e] * free_flow_steps(net, e, dt);
    const int32_t other = cut_source_part(net, junction_part, edge_part, e);
    if (other == kNone) continue;
    ps.cut_lanes_in += net.edge_num_lanes[e];
    ps.vehicles_in += entries[e];
    s.parts[static_cast<size_t>(other)].cut_lanes_out += net.edge_num_lanes[e];
    neighbours[static_cast<size_t>(edge_part[e])].insert(other);
    neighbours[static_cast<size_t>(other)].insert(edge_part[e]);
    ++s.cut_roads;
    s.cut_lanes += net.edge_num_lanes[e];
    s.migrations += entries[e];
  }
  float tail = 0;  // the longest vehicle: how far back a vehicle that crossed a cut may still reach
  for (float length : demand.types.length) tail = std::max(tail, length);
  const std::vector<PartLayout> layout = partition_layout(net, lane_part, k, kGhostLookAhead, tail);
  s.total_cells = net.lane_cell_begin.empty() ? 0 : net.lane_cell_begin.back();
  uint64_t most = 0;
  for (int32_t p = 0; p < k; ++p) {
    PartSummary& ps = s.parts[static_cast<size_t>(p)];
    const PartLayout& pl = layout[static_cast<size_t>(p)];
    ps.ghost_lanes = static_cast<uint32_t>(pl.ghosts.size());
    ps.cells = pl.owned_cells;
    ps.ghost_cells = pl.ghost_cells;
    most = std::max(most, pl.owned_cells + pl.ghost_cells);
  }
  s.largest_share = s.total_cells > 0 ? static_cast<double>(most) / static_cast<double>(s.total_cells) : 1.0;
  int64_t total = 0, largest = 0;
  for (int32_t p = 0; p < k; ++p) {
    PartSummary& ps = s.parts[static_cast<size_t>(p)];
    ps.neighbours.assign(neighbours[static_cast<size_t>(p)].begin(),
                         neighbours[static_cast<size_t>(p)].end());
    total += ps.vehicle_steps;
    largest = std::max(largest, ps.vehicle_steps);
  }
  s.imbalance = total > 0 ? static_cast<double>(largest) * k / static_cast<double>(total) : 1.0;
  return s;
}

void add_measured_migrations(PartitionSummary& s, const Network& net,
                             const std::vector<int32_t>& junction_part,
                             const std::vector<int64_t>& entered_per_edge) {
  const std::vector<int32_t> edge_part = edge_parts_from_junctions(net, junction_part);
  s.measured_migrations = 0;
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (cut_source_part(net, junction_part, edge_part, e) != kNone)
      s.measured_migrations += entered_per_edge[e];
}

}  // namespace lpsim

#include "engine/engine_net.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/foe_crossings.hpp"

namespace lpsim {

EngineNet::EngineNet(const Network& net) {
  const uint32_t nl = net.num_lanes();
  if (net.num_cells() >= (uint64_t{1} << 32))
    throw std::length_error("lane map of " + std::to_string(net.num_cells()) +
                            " cells exceeds 32-bit offsets");
  lane_cell_begin.assign(net.lane_cell_begin.begin(), net.lane_cell_begin.end());
  lane_internal.resize(nl);
  lane_left.assign(nl, -1);
  lane_right.assign(nl, -1);
  lane_rank.resize(nl);
  for (uint32_t l = 0; l < nl; ++l) {
    const uint32_t e = net.lane_edge[l];
    lane_internal[l] = net.edge_is_internal[e];
    const uint32_t first = net.edge_first_lane[e], n = net.edge_num_lanes[e];
    if (l + 1 < first + n) lane_left[l] = static_cast<int32_t>(l + 1);
    if (l > first) lane_right[l] = static_cast<int32_t>(l - 1);
    lane_rank[l] = static_cast<uint8_t>(std::min<uint32_t>(l - first, 255));
  }
  if (net.conn_foe_begin.size() == net.num_connections() + 1) {
    conn_foe_begin = net.conn_foe_begin;
    conn_foe = net.conn_foe;
  } else {
    conn_foe_begin.assign(net.num_connections() + 1, 0);
  }
  foe_block_cells = lpsim::foe_block_cells(net, conn_foe_begin, conn_foe);
  // Reverse of the foe CSR; ascending c keeps each list sorted, independent of anything else.
  const size_t nc = conn_foe_begin.size() - 1;
  yielder_begin.assign(nc + 1, 0);
  for (uint32_t foe : conn_foe) ++yielder_begin[foe + 1];
  for (size_t c = 0; c < nc; ++c) yielder_begin[c + 1] += yielder_begin[c];
  yielder.assign(conn_foe.size(), 0);
  std::vector<uint32_t> fill(yielder_begin.begin(), yielder_begin.end() - 1);
  for (size_t c = 0; c < nc; ++c)
    for (uint32_t k = conn_foe_begin[c]; k < conn_foe_begin[c + 1]; ++k)
      yielder[fill[conn_foe[k]]++] = static_cast<uint32_t>(c);
  const uint32_t ns = net.num_signals();
  durations_ms.resize(net.phase_duration.size());
  for (size_t p = 0; p < net.phase_duration.size(); ++p)
    durations_ms[p] = static_cast<int32_t>(std::lround(static_cast<double>(net.phase_duration[p]) * 1000.0));
  num_links.assign(ns, 0);
  cycle_ms.assign(ns, 0);
  offset_ms.assign(ns, 0);
  link_begin.assign(ns + 1, 0);
  for (uint32_t s = 0; s < ns; ++s) {
    const uint32_t p0 = net.signal_phase_begin[s], p1 = net.signal_phase_begin[s + 1];
    if (p1 > p0) {
      const uint32_t end = p0 + 1 < net.phase_state_begin.size()
                               ? net.phase_state_begin[p0 + 1]
                               : static_cast<uint32_t>(net.phase_state.size());
      num_links[s] = static_cast<int32_t>(end - net.phase_state_begin[p0]);
    }
    for (uint32_t p = p0; p < p1; ++p) cycle_ms[s] += durations_ms[p];
    offset_ms[s] = std::lround(static_cast<double>(net.signal_offset[s]) * 1000.0);
    link_begin[s + 1] = link_begin[s] + static_cast<uint32_t>(num_links[s]);
  }
}

NetView EngineNet::view(const Network& net) const {
  NetView v{};
  v.num_lanes = net.num_lanes();
  v.lane_cell_begin = lane_cell_begin.data();
  v.lane_length = net.lane_length.data();
  v.lane_speed = net.lane_speed.data();
  v.lane_edge = net.lane_edge.data();
  v.lane_internal = lane_internal.data();
  v.lane_left = lane_left.data();
  v.lane_right = lane_right.data();
  v.lane_rank = lane_rank.data();
  v.lane_conn_begin = net.lane_conn_begin.data();
  v.edge_first_lane = net.edge_first_lane.data();
  v.edge_num_lanes = net.edge_num_lanes.data();
  v.conn_to_lane = net.conn_to_lane.data();
  v.conn_via_lane = net.conn_via_lane.data();
  v.conn_to_edge = net.conn_to_edge.data();
  v.conn_from_lane = net.conn_from_lane.data();
  v.conn_signal = net.conn_signal.data();
  v.conn_link_index = net.conn_link_index.data();
  v.conn_state = net.conn_state.data();
  v.conn_foe_begin = conn_foe_begin.data();
  v.conn_foe = conn_foe.data();
  v.conn_foe_block_cells = foe_block_cells.data();
  v.signal_link_begin = link_begin.data();
  v.lane_permissions = net.lane_permissions.data();
  return v;
}

SignalTable EngineNet::signal_table(const Network& net) const {
  return SignalTable{net.num_signals(),      net.signal_phase_begin.data(),
                     durations_ms.data(),    net.phase_state_begin.data(),
                     net.phase_state.data(), num_links.data(),
                     cycle_ms.data(),        offset_ms.data(),
                     link_begin.data()};
}

}  // namespace lpsim

#include "engine/engine_net.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/foe_crossings.hpp"

namespace lpsim {

EngineNet::EngineNet(const Network& net, const PartPlan* plan) {
  const PartCells* part = plan != nullptr ? &plan->cells : nullptr;
  const uint32_t nl = net.num_lanes();
  if (net.num_cells() >= (uint64_t{1} << 32))
    throw std::length_error("lane map of " + std::to_string(net.num_cells()) +
                            " cells exceeds 32-bit offsets");
  lane_num_cells.resize(nl);
  for (uint32_t l = 0; l < nl; ++l)
    lane_num_cells[l] = static_cast<uint32_t>(net.lane_cell_begin[l + 1] - net.lane_cell_begin[l]);
  if (part == nullptr) {
    lane_cell_begin.assign(net.lane_cell_begin.begin(), net.lane_cell_begin.end());
  } else {
    lane_cell_begin.resize(nl + 1);
    for (uint32_t l = 0; l < nl; ++l)
      lane_cell_begin[l] =
          static_cast<uint32_t>(part->cell_begin[l] == kNoCells ? part->cells : part->cell_begin[l]);
    lane_cell_begin[nl] = static_cast<uint32_t>(part->cells);
  }
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
  build_actuated(net, plan);
}

namespace {
int32_t to_ms(double s) { return static_cast<int32_t>(std::lround(s * 1000.0)); }
}  // namespace

void EngineNet::build_actuated(const Network& net, const PartPlan* part) {
  const uint32_t ns = net.num_signals();
  const size_t np = net.phase_duration.size();
  detector_gap_ms.assign(ns, 0);
  for (uint32_t s = 0; s < ns && s < net.signal_detector_gap.size(); ++s)
    detector_gap_ms[s] = to_ms(net.signal_detector_gap[s]);
  min_ms.resize(np);
  max_ms.resize(np);
  phase_green.resize(np);
  for (size_t p = 0; p < np; ++p) {
    // SUMO: a phase without minDur / maxDur lasts its duration.
    min_ms[p] = net.phase_min_dur[p] >= 0 ? to_ms(net.phase_min_dur[p]) : durations_ms[p];
    max_ms[p] = net.phase_max_dur[p] >= 0 ? to_ms(net.phase_max_dur[p]) : durations_ms[p];
    const uint32_t b = net.phase_state_begin[p], e = net.phase_state_begin[p + 1];
    bool green = false, yellow = false;
    for (uint32_t k = b; k < e; ++k) {
      green |= net.phase_state[k] == 'G' || net.phase_state[k] == 'g';
      yellow |= net.phase_state[k] == 'y' || net.phase_state[k] == 'Y';
    }
    phase_green[p] = green && !yellow ? 1 : 0;
  }
  const bool placed = net.signal_det_begin.size() == ns + 1 && net.phase_det_begin.size() == np + 1 &&
                      net.signal_actuated.size() == ns;
  signal_actuated = placed ? net.signal_actuated : std::vector<uint8_t>(ns, 0);
  if (part != nullptr)
    for (uint32_t s = 0; s < ns; ++s)
      if (part->signal_owner[s] >= 0 && part->signal_owner[s] != part->part) signal_actuated[s] = 0;
  signal_det_begin = placed ? net.signal_det_begin : std::vector<uint32_t>(ns + 1, 0);
  phase_det_begin = placed ? net.phase_det_begin : std::vector<uint32_t>(np + 1, 0);
  phase_det = placed ? net.phase_det : std::vector<uint32_t>{};
  const size_t nd = placed ? net.det_lane.size() : 0;
  det_cell.resize(nd);
  det_last_cell.resize(nd);
  det_offset.resize(nd);
  det_max_gap_ms.resize(nd);
  for (uint32_t s = 0; s < ns; ++s)
    for (uint32_t d = signal_det_begin[s]; d < signal_det_begin[s + 1]; ++d) {
      const uint32_t lane = net.det_lane[d];
      const uint32_t cells = lane_num_cells[lane];
      const float pos = net.det_pos[d];
      const uint32_t c = std::min(static_cast<uint32_t>(pos), cells - 1);
      det_cell[d] = lane_cell_begin[lane] + c;
      det_last_cell[d] = lane_cell_begin[lane] + cells - 1;
      det_offset[d] = std::min(pos - static_cast<float>(c), 0.999f);
      det_max_gap_ms[d] = s < net.signal_max_gap.size() ? to_ms(net.signal_max_gap[s]) : 3000;
    }
}

NetView EngineNet::view(const Network& net) const {
  NetView v{};
  v.num_lanes = net.num_lanes();
  v.lane_cell_begin = lane_cell_begin.data();
  v.lane_num_cells = lane_num_cells.data();
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
  v.conn_keep_clear = net.conn_keep_clear.data();
  v.signal_link_begin = link_begin.data();
  v.lane_permissions = net.lane_permissions.data();
  // Most nets restrict no class: a null table spares every speed lookup its loop.
  if (!net.restriction_vclass.empty()) {
    v.lane_restriction_begin = net.lane_restriction_begin.data();
    v.restriction_vclass = net.restriction_vclass.data();
    v.restriction_speed = net.restriction_speed.data();
  }
  return v;
}

// Named field by field: the table's columns are the network's and this one's under other names.
SignalTable EngineNet::signal_table(const Network& net) const {
  const ActuatedTable actuated{.actuated = signal_actuated.data(),
                               .detector_gap_ms = detector_gap_ms.data(),
                               .min_ms = min_ms.data(),
                               .max_ms = max_ms.data(),
                               .green = phase_green.data(),
                               .signal_det_begin = signal_det_begin.data(),
                               .phase_det_begin = phase_det_begin.data(),
                               .phase_det = phase_det.data(),
                               .det_cell = det_cell.data(),
                               .det_last_cell = det_last_cell.data(),
                               .det_offset = det_offset.data(),
                               .det_max_gap_ms = det_max_gap_ms.data()};
  return SignalTable{.num_signals = net.num_signals(),
                     .phase_begin = net.signal_phase_begin.data(),
                     .durations_ms = durations_ms.data(),
                     .state_begin = net.phase_state_begin.data(),
                     .states = net.phase_state.data(),
                     .num_links = num_links.data(),
                     .cycle_ms = cycle_ms.data(),
                     .offset_ms = offset_ms.data(),
                     .link_begin = link_begin.data(),
                     .actuated = actuated};
}

}  // namespace lpsim

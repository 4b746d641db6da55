#pragma once
// Columns the step kernels need that the Network does not store directly: 32-bit cell offsets, internal
// flags, lane neighbours, signal tables in the kernels' units (milliseconds). Built once per run.
#include <cstdint>
#include <vector>

#include "kernels/signal_step.hpp"
#include "kernels/step_view.hpp"
#include "net/network.hpp"
#include "partition/part_plan.hpp"

namespace lpsim {

struct EngineNet {
  std::vector<uint32_t> lane_cell_begin;  // the network's map, or one part's (its lanes' cells only)
  std::vector<uint32_t> lane_num_cells;
  std::vector<uint8_t> lane_internal;
  std::vector<int32_t> lane_left, lane_right;
  std::vector<uint8_t> lane_rank;  // so that a lane's rank costs one load, not two dependent ones
  std::vector<uint32_t> conn_foe_begin, conn_foe;  // copies, or an empty CSR if the net has none
  std::vector<uint16_t> foe_block_cells;           // per conn_foe entry (foe_crossings.hpp)
  std::vector<uint32_t> yielder_begin, yielder;    // the reverse: connections that must yield to each one
  // Signals.
  std::vector<int32_t> durations_ms, num_links;
  std::vector<int64_t> cycle_ms, offset_ms;
  std::vector<uint32_t> link_begin;
  // Actuated signals (ActuatedTable).
  std::vector<int32_t> detector_gap_ms, min_ms, max_ms, det_max_gap_ms;
  std::vector<uint8_t> phase_green;
  std::vector<uint8_t> signal_actuated;  // copies, or empty tables for a Network built without loops
  std::vector<uint32_t> signal_det_begin, phase_det_begin, phase_det;
  std::vector<uint32_t> det_cell, det_last_cell;
  std::vector<float> det_offset;

  /// The columns of `net` with its whole lane map, or, given `part`, as one part of a partitioned run sees
  /// them: its map holds the cells of some lanes only (the others begin past its last cell), and the actuated
  /// signals another part runs are computed as fixed-time programs here (their owner sends their state).
  explicit EngineNet(const Network& net, const PartPlan* part = nullptr);
  NetView view(const Network& net) const;
  SignalTable signal_table(const Network& net) const;

 private:
  void build_actuated(const Network& net, const PartPlan* part);
};

}  // namespace lpsim

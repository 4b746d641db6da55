#pragma once
// The CPU passes wait mostly on cache misses: the per-lane columns of a vehicle's lane and the lane-map
// cells at its position, scattered over hundreds of MiB on a regional network. Both addresses follow from a
// slot's lane and position, known long before the loop reaches the vehicle, so the loop fetches them ahead:
// a lane's columns kPrefetchFar vehicles ahead, its cells (whose address needs the lane's first cell, in
// cache by then) kPrefetchNear ahead. Prefetches change no value, so results stay as they are.
#include <stdint.h>

#include "kernels/step_view.hpp"

namespace lpsim {

constexpr int64_t kPrefetchNear = 8, kPrefetchFar = 16;

/// Where a pass finds a vehicle: the lane its footprint or front is on (-1: none) and the front's position.
struct LaneAt {
  int32_t lane;
  float pos;
};

/// The lane columns every pass reads at a vehicle's lane.
inline void prefetch_lane_columns(const NetView& net, int32_t lane) {
  __builtin_prefetch(&net.lane_cell_begin[lane]);
  __builtin_prefetch(&net.lane_length[lane]);
  __builtin_prefetch(&net.lane_speed[lane]);
}

/// Runs body(i) for i in [b, e), prefetching for each i the cells of `map` (null: none) that where(i) names,
/// from a few metres behind the front (a footprint) to a few ahead (a leader scan), and before that the
/// lane's columns through fetch_lane(lane).
template <class Where, class FetchLane, class Body>
void run_prefetched(int64_t b, int64_t e, const NetView& net, const uint8_t* map, Where where,
                    FetchLane fetch_lane, Body body) {
  for (int64_t i = b; i < e; ++i) {
    if (i + kPrefetchFar < e) {
      const LaneAt a = where(i + kPrefetchFar);
      if (a.lane >= 0) fetch_lane(a.lane);
    }
    if (map != nullptr && i + kPrefetchNear < e) {
      const LaneAt a = where(i + kPrefetchNear);
      if (a.lane >= 0) {
        // As an integer: the lines fetched may lie a little before or beyond the lane map, which a
        // prefetch may touch but a pointer may not point to.
        const uintptr_t cell = reinterpret_cast<uintptr_t>(map) + net.lane_cell_begin[a.lane] +
                               static_cast<uint32_t>(a.pos > 0.0f ? a.pos : 0.0f);
        __builtin_prefetch(reinterpret_cast<const void*>(cell - 8));
        __builtin_prefetch(reinterpret_cast<const void*>(cell + 40));
      }
    }
    body(i);
  }
}

}  // namespace lpsim

#pragma once
// The per-lane edgeData/laneData counters as the passes add to them. The traffic counters a vehicle's step
// adds to (all but departed) sit side by side in one 64-byte record per lane: a step then touches one cache
// line of them instead of one per counter. On a regional network the counters are far larger than the
// cache, and five scattered lines per vehicle-step evicted the lane map the passes read (measured: +40 %
// CPU on the Bay Area ×8 hour with separate columns).
#include <stddef.h>
#include <stdint.h>

#include "kernels/atomics.hpp"
#include "kernels/hd.hpp"

namespace lpsim {

/// The counters in LaneCounters' order (src/engine/samples.hpp): the traffic measures, then the emissions
/// pass's sums (EmissionSum order), which that pass keeps in columns of its own.
enum LaneCounter : int {
  kCountSampledSteps,
  kCountTravelledMm,
  kCountWaitingSteps,
  kCountTimeLossMs,
  kCountOccupiedMmSteps,
  kCountEntered,
  kCountLeft,
  kCountArrived,
  kCountDeparted,  // counted at insertion only: a column after the records
  kNumTrafficCounters,
  kCountEmissionFirst = kNumTrafficCounters
};

/// Counters per lane record; the record of lane l starts at l * kLaneRecordCounters.
inline constexpr int kLaneRecordCounters = kCountDeparted;
static_assert(kLaneRecordCounters * sizeof(int64_t) == 64, "one cache line per lane record");

/// Adds v to counter k (< kCountDeparted) of `lane` in the records.
LPSIM_HD void count_on_lane(int64_t* records, int32_t lane, int k, int64_t v) {
  atomic_add_i64(records + static_cast<size_t>(lane) * kLaneRecordCounters + k, v);
}

}  // namespace lpsim

#pragma once
// The lane counters as the backends keep them (kernels/lane_counters.hpp: a record per lane, then the
// departed column) added to the engine's columns, for either backend's drain.
#include <cstddef>
#include <cstdint>

#include "kernels/lane_counters.hpp"

namespace lpsim {

/// Adds `records` (kLaneRecordCounters per lane) and `departed` (one per lane), over `num_lanes` lanes, to
/// `columns` (LaneCounter order, num_lanes each).
inline void add_lane_records(const int64_t* records, const int64_t* departed, size_t num_lanes,
                             int64_t* const* columns) {
  for (size_t l = 0; l < num_lanes; ++l)
    for (int k = 0; k < kLaneRecordCounters; ++k) columns[k][l] += records[l * kLaneRecordCounters + k];
  for (size_t l = 0; l < num_lanes; ++l) columns[kCountDeparted][l] += departed[l];
}

}  // namespace lpsim

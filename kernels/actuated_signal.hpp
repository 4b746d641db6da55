#pragma once
// Actuated traffic lights as SUMO 1.15 runs them (type="actuated", MSActuatedTrafficLightLogic's default
// gap control): an induction loop on each controlled approach, and a green phase with minDur < maxDur that
// is extended while one of its loops saw a vehicle less than max-gap seconds ago, never beyond maxDur.
// Where the loops lie and which phase each serves is decided when the network is built
// (src/net/actuated_detectors.cpp); here are the per-step parts, written once for both backends. Times are
// integer milliseconds, as SUMO's. See docs/MODELS.md.
#include <stdint.h>

#include "kernels/hd.hpp"
#include "kernels/lane_map.hpp"

namespace lpsim {

/// An actuated signal's loops and phase bounds, read-only. Phases are indexed as in SignalTable.
struct ActuatedTable {
  const uint8_t* actuated;           // per signal: 1 runs the gap control below, 0 runs its fixed-time plan
  const int32_t* detector_gap_ms;    // per signal: SUMO's detector-gap (s of driving at the limit), in ms
  const int32_t* min_ms;             // per phase: minDur (its duration when not given)
  const int32_t* max_ms;             // per phase: maxDur (its duration when not given)
  const uint8_t* green;              // per phase: SUMO's isGreenPhase (some G or g, no y)
  const uint32_t* signal_det_begin;  // [num_signals+1] loops of each signal
  const uint32_t* phase_det_begin;   // [num_phases+1] loops that may extend each phase, in phase_det
  const uint32_t* phase_det;
  const uint32_t* det_cell;       // lane-map cell under the loop
  const uint32_t* det_last_cell;  // last cell of the loop's lane
  const float* det_offset;        // loop position within its cell [0, 1) m
  const int32_t* det_max_gap_ms;  // per loop: SUMO's max-gap
};

/// Per-signal and per-loop state of actuated signals, written only by update_signal.
struct ActuatedState {
  int32_t* phase;           // per signal: the phase shown
  int64_t* phase_start_ms;  // per signal: when it started
  int64_t* det_last_ms;     // per loop: the last time a vehicle was over it (kNeverDetected: never)
};

constexpr int64_t kNeverDetected = INT64_MIN / 4;
// Cells scanned downstream of a loop for the rear of a vehicle that crossed it within the step: 64 m, more
// than any vehicle drives in a step of 1 s (a rear farther than speed * dt has not crossed in the step).
constexpr uint32_t kDetectorScanCells = 64;

/// Updates loop `d` from the lane map of time `map_time_ms` (the vehicles as they stand before the step
/// that produces the signal states): a vehicle over the loop is detected now; otherwise the nearest rear
/// downstream, if it crossed the loop within the last dt_ms at its cell's speed, was detected when it left
/// (SUMO's induction loops interpolate the leaving time within the step as well).
LPSIM_HD void update_detector(const ActuatedTable& t, const uint8_t* map, uint32_t d, int64_t map_time_ms,
                              int64_t dt_ms, int64_t* det_last_ms) {
  const uint32_t c = t.det_cell[d];
  if (map[c] != 0) {
    det_last_ms[d] = map_time_ms;
    return;
  }
  const uint32_t last =
      t.det_last_cell[d] - c < kDetectorScanCells ? t.det_last_cell[d] : c + kDetectorScanCells;
  for (uint32_t r = c + 1; r <= last; ++r) {
    if (map[r] == 0) continue;
    const float speed = decode_cell_speed(map[r]);
    const float behind = static_cast<float>(r - c) - t.det_offset[d];  // rear past the loop [m]
    if (speed > 0.0f && behind <= speed * static_cast<float>(dt_ms) * 0.001f) {
      const int64_t left = map_time_ms - static_cast<int64_t>(behind / speed * 1000.0f + 0.5f);
      if (left > det_last_ms[d]) det_last_ms[d] = left;
    }
    return;
  }
}

/// SUMO's gap control at a phase's scheduled end, time_ms: how long the phase is extended, or -1 when it
/// ends now. A green phase not yet at maxDur is extended while one of its loops saw a vehicle less than
/// max-gap ago: until that vehicle is detector-gap seconds past the loop and at least to minDur, rounded up
/// so that the phase lasts whole seconds, and never beyond maxDur.
LPSIM_HD int64_t actuated_extension_ms(const ActuatedTable& t, uint32_t s, uint32_t p, int64_t time_ms,
                                       int64_t phase_start_ms, int64_t detect_time_ms,
                                       const int64_t* det_last_ms) {
  const int64_t elapsed = time_ms - phase_start_ms;
  if (!t.green[p] || elapsed >= t.max_ms[p]) return -1;
  int64_t gap = -1;  // the shortest time since a detection among the loops still within max-gap
  for (uint32_t k = t.phase_det_begin[p]; k < t.phase_det_begin[p + 1]; ++k) {
    const uint32_t d = t.phase_det[k];
    const int64_t since = detect_time_ms - det_last_ms[d];
    if (since < t.det_max_gap_ms[d] && (gap < 0 || since < gap)) gap = since;
  }
  if (gap < 0) return -1;
  int64_t ext = t.min_ms[p] - elapsed;
  if (t.detector_gap_ms[s] - gap > ext) ext = t.detector_gap_ms[s] - gap;
  if (ext < 1) ext = 1;
  if ((elapsed + ext) % 1000 != 0) ext = ((elapsed + ext) / 1000 + 1) * 1000 - elapsed;
  if (ext > t.max_ms[p] - elapsed) ext = t.max_ms[p] - elapsed;
  return ext;
}

/// How long a phase of an actuated signal lasts at least once it starts: its minDur, at least 1 s.
LPSIM_HD int64_t actuated_first_try_ms(const ActuatedTable& t, uint32_t p) {
  return t.min_ms[p] > 1000 ? t.min_ms[p] : 1000;
}

}  // namespace lpsim

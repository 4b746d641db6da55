#pragma once
// Scheduled stops (<stop>, e.g. a bus at its busStop) as SUMO 1.15 makes them: the vehicle brakes to stand
// with its front at the stop's end (or behind vehicles already standing there), has reached the stop once
// it stands within the stop's stretch, and leaves after its duration and not before its `until` time.
// Pure functions of plain numbers; the step (vehicle_step.hpp) applies them.
#include <stdint.h>

#include "kernels/hd.hpp"

namespace lpsim {

// A front this close to the stop's end has reached it (SUMO's STOPPING_PLACE_OFFSET) [m].
constexpr float kStopReachTolerance = 0.5f;
// A rear this close to the stop's start is within the stop (SUMO's POSITION_EPS) [m].
constexpr float kStopFitTolerance = 0.1f;

/// A vehicle standing with its front at `front` (its body `length` long) on the stop's lane has reached a
/// stop stretching over [start, end]: at its end, or wholly within it behind a vehicle standing there.
LPSIM_HD bool stop_reached(float front, float length, float start, float end) {
  if (front > end + kStopReachTolerance) return false;
  return front >= end - kStopReachTolerance || front - length >= start - kStopFitTolerance;
}

/// First step in which a vehicle that reached its stop in step `reached` (standing there at the step's end)
/// may move again. As SUMO counts a stop's time from the step that reached it: `duration_steps` steps,
/// that one included, at least one (SUMO ends even a stop whose time has passed one step after reaching it);
/// and not before step `until_step` (the one that ends at the stop's `until` time; 0: no until).
LPSIM_HD uint32_t stop_release_step(uint32_t reached, uint32_t duration_steps, uint32_t until_step) {
  const uint32_t after_duration = reached + (duration_steps > 0 ? duration_steps : 1u);
  return after_duration > until_step ? after_duration : until_step;
}

}  // namespace lpsim

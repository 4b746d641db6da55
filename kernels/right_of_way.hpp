#pragma once
// Right-of-way decisions at junctions as pure functions of plain numbers: which rule a link state implies,
// when a yielding vehicle may enter (time-window test against approaching foes), right-before-left, and
// all-way-stop ordering. The engine supplies distances, speeds and arrival steps. See docs/MODELS.md.
#include <math.h>
#include <stdint.h>

#include "kernels/hd.hpp"

namespace lpsim {

enum class LinkRule : uint8_t {
  Priority,         // 'M', 'G', 'O', 'y'/'Y' (once the vehicle decided to pass at yellow): go
  Yield,            // 'm', 'g', 'o', 'Z': enter only if no foe on a prioritised link conflicts in time
  StopThenYield,    // 's': stop at the line, then as Yield
  RightBeforeLeft,  // '=': yield to conflicting foes approaching from the right
  AllwayStop,       // 'w': stop, then first come first served
  Closed,           // 'r', 'u' and anything unknown: do not enter
};

/// Rule implied by a SUMO link state character (connection state or current signal character).
LPSIM_HD LinkRule link_rule(char c) {
  switch (c) {
    case 'M':
    case 'G':
    case 'O':
    case 'y':
    case 'Y':
      return LinkRule::Priority;
    case 'm':
    case 'g':
    case 'o':
    case 'Z':
      return LinkRule::Yield;
    case 's':
      return LinkRule::StopThenYield;
    case '=':
      return LinkRule::RightBeforeLeft;
    case 'w':
      return LinkRule::AllwayStop;
    default:
      return LinkRule::Closed;
  }
}

// How far before a link without priority a driver sees whether foes come: SUMO's default foe visibility
// distance of a connection (a connection's own `visibility` attribute is not read) [m].
constexpr float kFoeVisibility = 4.5f;

/// A link whose state gives no priority ('m', 'g', 'o', 's', '=', 'w'; not the zipper 'Z', which SUMO counts
/// as prioritised), `dist` metres ahead, whose foes the driver cannot see yet: SUMO's vehicles then plan to
/// stop at the link, whether or not a foe comes, until they are within the visibility distance.
LPSIM_HD bool foes_unseen(char c, float dist) {
  const LinkRule r = link_rule(c);
  const bool minor = c != 'Z' && (r == LinkRule::Yield || r == LinkRule::StopThenYield ||
                                  r == LinkRule::RightBeforeLeft || r == LinkRule::AllwayStop);
  return minor && dist > kFoeVisibility;
}

// "Never arrives" for a standing vehicle that cannot accelerate [s].
constexpr float kNeverArrives = 1e30f;

/// Earliest time to cover `dist` metres starting at `speed`, accelerating at `accel` up to max_speed: a
/// foe's soonest arrival at a conflict point, or a vehicle's own time to clear it.
LPSIM_HD float earliest_arrival_time(float dist, float speed, float accel, float max_speed) {
  if (dist <= 0.0f) return 0.0f;
  const float v = lp_fmaxf(speed, 0.0f);
  const float vmax = lp_fmaxf(max_speed, v);
  if (accel <= 0.0f || v >= vmax) return v > 0.0f ? dist / v : kNeverArrives;
  const float t_up = (vmax - v) / accel;
  const float d_up = 0.5f * (v + vmax) * t_up;
  // 2d / (v + sqrt(v^2 + 2ad)) is v*t + a*t^2/2 = d solved without cancellation at small accel.
  if (dist <= d_up) return 2.0f * dist / (v + sqrtf(v * v + 2.0f * accel * dist));
  return t_up + (dist - d_up) / vmax;
}

/// A foe approaching on a prioritised link, as the engine sees it.
struct ApproachingFoe {
  float dist;       // its front bumper's distance to the conflict point [m] (<= 0: already there)
  float speed;      // [m/s]
  float accel;      // its maximum acceleration [m/s^2]
  float max_speed;  // its desired speed on the approach [m/s]
};

/// The foe could reach the conflict point before this vehicle has cleared it plus a safety window.
LPSIM_HD bool foe_conflicts(const ApproachingFoe& foe, float own_time_to_clear, float window) {
  return earliest_arrival_time(foe.dist, foe.speed, foe.accel, foe.max_speed) < own_time_to_clear + window;
}

/// Yield rule ('m', 'g', 'o', and 's' after stopping): enter iff no foe conflicts in time.
LPSIM_HD bool yield_may_enter(float own_time_to_clear, const ApproachingFoe* foes, int32_t num_foes,
                              float window) {
  for (int32_t i = 0; i < num_foes; ++i)
    if (foe_conflicts(foes[i], own_time_to_clear, window)) return false;
  return true;
}

/// Right-before-left ('='): like yield, but only foes approaching from the right count. from_right[i]
/// says whether foes[i] comes from this vehicle's right (the engine derives it from the junction geometry).
/// A circular wait (every approach has a foe on its right) is not resolved here; the engine falls back
/// to the all-way-stop order for it.
LPSIM_HD bool right_before_left_may_enter(float own_time_to_clear, const ApproachingFoe* foes,
                                          const bool* from_right, int32_t num_foes, float window) {
  for (int32_t i = 0; i < num_foes; ++i)
    if (from_right[i] && foe_conflicts(foes[i], own_time_to_clear, window)) return false;
  return true;
}

/// A vehicle waiting at an all-way stop: the step it came to a stop at the line, and a globally unique lane
/// index that breaks ties deterministically.
struct AllwayWaiter {
  int64_t arrival_step;
  int32_t lane_index;
};

/// Strict first-come-first-served order, ties by lower lane index.
LPSIM_HD bool allway_precedes(const AllwayWaiter& a, const AllwayWaiter& b) {
  return a.arrival_step < b.arrival_step || (a.arrival_step == b.arrival_step && a.lane_index < b.lane_index);
}

/// All-way stop ('w'): a vehicle that has stopped at the line enters iff no conflicting foe is inside the
/// junction and no conflicting foe waiting at its line arrived before it (ties by lane index).
LPSIM_HD bool allway_stop_may_enter(bool has_stopped, const AllwayWaiter& self,
                                    const AllwayWaiter* waiting_foes, int32_t num_waiting,
                                    bool conflict_area_occupied) {
  if (!has_stopped || conflict_area_occupied) return false;
  for (int32_t i = 0; i < num_waiting; ++i)
    if (allway_precedes(waiting_foes[i], self)) return false;
  return true;
}

}  // namespace lpsim

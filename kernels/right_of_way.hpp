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

// SUMO's safety margin between a yielding vehicle leaving a link and a foe arriving (MSLink's lookahead
// time, jmTimegapMinor's default) [s].
constexpr float kSumoLinkTimegap = 1.0f;
// How much later an impatient vehicle takes a foe that could still stop (SUMO's arrivalTimeBraking,
// MSLink::computeFoeArrivalTimeBraking) [s].
constexpr float kSumoFoeStopDelay = 30.0f;

/// A vehicle's passage through a link as SUMO estimates it for its gap test (MSVehicle::planMoveInternal's
/// arrival time and speed and estimated leave speed, MSLink::getLeaveTime), in seconds from now.
struct LinkPassage {
  float arrival;        // front at the line
  float leave;          // rear past the link's internal lane
  float arrival_speed;  // [m/s]
  float leave_speed;    // [m/s]
};

/// `dist` to the line at `speed`: the vehicle's next speed (accelerating at `accel`, at most v_max) carries
/// it to the line; it crosses the line at the speed reached accelerating over `dist` and leaves the link at
/// the speed reached over its `link_length` (at most link_speed), at the mean of the two.
LPSIM_HD LinkPassage link_passage(float dist, float speed, float accel, float dt, float v_max,
                                  float link_length, float link_speed, float length) {
  const float d = lp_fmaxf(dist, 0.0f);
  const float v_next = lp_fminf(lp_fmaxf(speed, 0.0f) + accel * dt, lp_fmaxf(v_max, 0.0f));
  const float arrival = d <= 0.0f ? 0.0f : (v_next > 0.0f ? d / v_next : kNeverArrives);
  const float at_line = lp_fminf(sqrtf(v_next * v_next + 2.0f * accel * d), lp_fmaxf(v_max, v_next));
  const float leave_speed =
      lp_fminf(sqrtf(at_line * at_line + 2.0f * accel * lp_fmaxf(link_length, 0.0f)), link_speed);
  const float mean = lp_fmaxf(0.5f * (at_line + leave_speed), 1e-3f);
  return LinkPassage{arrival, arrival + (lp_fmaxf(link_length, 0.0f) + length) / mean, at_line, leave_speed};
}

/// The passage when the vehicle leaves the link no faster than `cap` (behind a leader).
LPSIM_HD LinkPassage link_passage_capped(const LinkPassage& p, float cap, float link_length, float length) {
  const float leave_speed = lp_fminf(p.leave_speed, lp_fmaxf(cap, 0.0f));
  const float mean = lp_fmaxf(0.5f * (p.arrival_speed + leave_speed), 1e-3f);
  return LinkPassage{p.arrival, p.arrival + (lp_fmaxf(link_length, 0.0f) + length) / mean, p.arrival_speed,
                     leave_speed};
}

/// A foe announced at a prioritised link, as SUMO's gap test sees it.
struct AnnouncedFoe {
  float dist;       // [m] to its line
  float speed;      // [m/s]
  float accel;      // its maximum acceleration [m/s^2]
  float max_speed;  // its desired speed on the approach [m/s]
  float decel;      // its comfortable deceleration [m/s^2]
};

/// The foe blocks a vehicle that would pass the link as `own` (SUMO 1.15's MSLink::blockedByFoe for a
/// foe that has not yet passed): it arrives before the vehicle has left plus kSumoLinkTimegap, or, on a
/// merge into the same lane, it would reach the merge faster than the vehicle leaves it (unsafeMergeSpeeds).
/// An impatient vehicle (impatience in (0, 1]) takes the foe as braking at impatience times its decel
/// (computeFoeArrivalTimeBraking): one that can stop so arrives kSumoFoeStopDelay s later, at speed 0;
/// one that cannot arrives at nearly its own speed, and on a merge that blocks. Why a vehicle that has
/// just stopped at a merge waits long in SUMO: with little impatience every foe faster than the
/// vehicle's leave speed blocks it, until the nearest can stop at decel times impatience.
LPSIM_HD bool foe_blocks_passage(const LinkPassage& own, float own_decel, const AnnouncedFoe& foe,
                                 float impatience, bool same_target, float dt) {
  const float v = lp_fmaxf(foe.speed, 0.0f);
  // SUMO's announced arrival: at the speed it plans for this step (accelerating, at most its desired speed).
  const float v_next = v > 0.0f ? lp_fminf(v + foe.accel * dt, lp_fmaxf(foe.max_speed, v)) : 0.0f;
  const float arrival = foe.dist <= 0.0f ? 0.0f : (v_next > 0.0f ? foe.dist / v_next : kNeverArrives);
  if (arrival >= kNeverArrives) return false;
  // The speed at which the foe reaches the line braking now: 0 when it can still stop (SUMO's
  // arrivalSpeedBraking).
  const float brake_gap = v * v / (2.0f * lp_fmaxf(foe.decel, 1e-3f));
  float speed_braking =
      foe.dist < brake_gap ? sqrtf(lp_fmaxf(v * v - 2.0f * foe.decel * foe.dist, 0.0f)) : 0.0f;
  float foe_time = arrival;
  // SUMO counts in whole steps: a foe arriving in the vehicle's own step is taken at its arrival.
  const bool same_step =
      lp_floor_nonneg(lp_fmaxf(own.arrival, 0.0f) / dt) == lp_floor_nonneg(lp_fmaxf(arrival, 0.0f) / dt);
  if (impatience > 0.0f && own.arrival < arrival && !same_step) {
    const float m = lp_fmaxf(foe.decel * impatience, 1e-3f);
    const float gap_t = arrival - own.arrival;
    const float d = gap_t * m;
    const float a = gap_t * d * 0.5f;
    const float vv = foe.dist / (arrival + dt);
    const float dist2 = foe.dist - vv * own.arrival;
    float braking_time;
    if (0.5f * vv * vv / m <= dist2) {
      speed_braking = 0.0f;
      braking_time = arrival + kSumoFoeStopDelay;
    } else {
      const float root = sqrtf(lp_fmaxf(4.0f * (vv - d) * (vv - d) - 8.0f * m * a, 0.0f));
      const float x = (-0.5f * root - d + vv) / m;
      speed_braking = vv - (gap_t + x) * m;
      braking_time = arrival + x;
    }
    foe_time = (1.0f - impatience) * arrival + impatience * braking_time;
  }
  if (foe_time <= own.leave + kSumoLinkTimegap) return true;
  return same_target && own.leave_speed * own.leave_speed / lp_fmaxf(own_decel, 1e-3f) <=
                            speed_braking * speed_braking / lp_fmaxf(foe.decel, 1e-3f);
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

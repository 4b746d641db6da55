#pragma once
// Longitudinal model: SUMO's default car-following model, Krauss (SUMO 1.15's MSCFModel_Krauss), with the
// semi-implicit Euler position update SUMO uses by default. Pure float functions shared by the CPU and CUDA
// step kernels; see docs/MODELS.md.
//
// Gap convention: as in idm.hpp, the caller's `gap` is bumper to bumper with nothing subtracted. Krauss
// measures the distance to a leader behind the follower's minGap (SUMO's gap2pred = gap - minGap); to a stop
// point the whole gap counts (SUMO's stopSpeed ignores minGap).
//
// The model: each step a vehicle takes the fastest speed that is at most its acceleration above the current
// one (maxNextSpeed), at most its desired speed, and "safe" (it can still stop, braking at its comfortable
// decel, behind a leader that brakes from now on, keeping its headway tau). Then it dawdles: it drops up to
// sigma * accel * dt below that speed (sigma * speed * dt when slower than accel), at random, never below
// what braking at its comfortable decel would give unless the safe speed itself is lower.
#include <math.h>

#include "kernels/hd.hpp"
#include "kernels/idm.hpp"

namespace lpsim {

// SUMO's NUMERICAL_EPS: stop speeds shorten the gap by this much so that a vehicle never passes a stop point
// by a rounding error [m].
constexpr float kKraussGapEps = 0.001f;
// A safe speed that asks for harder than comfortable braking by more than this is recomputed with the
// braking the situation needs (SUMO's NUMERICAL_EPS on the deceleration) [m/s^2].
constexpr float kKraussDecelEps = 0.001f;
// SUMO's EMERGENCY_DECEL_AMPLIFIER: the needed braking is taken with this margin.
constexpr float kKraussEmergencyAmplifier = 1.2f;

/// Fastest next speed (SUMO's maxNextSpeed): accelerating at accel for one step. SUMO also caps it by the
/// vehicle's maximum speed; here the free-road speed, which joins every candidate, carries that cap.
LPSIM_HD float krauss_max_next_speed(float speed, float accel, float dt) { return speed + accel * dt; }

/// Distance covered braking from speed n*b by b per step (b = decel*dt) when the first braking step comes
/// `headway` seconds after the next step's start: the h of SUMO's maximumSafeStopSpeedEuler.
LPSIM_HD float krauss_braking_distance(float n, float b, float headway, float dt) {
  return 0.5f * n * (n - 1.0f) * b * dt + n * b * headway;
}

/// Fastest next speed from which a vehicle can stop within `gap` metres braking at `decel` each step, the
/// first braking step coming `headway` seconds after the next step's start (SUMO's
/// maximumSafeStopSpeedEuler). With x = n*b + r (b = decel*dt) the distance is
/// dt*b*n*(n-1)/2 + headway*b*n + r*(n*dt + headway), which is solved for the largest n, then r.
LPSIM_HD float krauss_safe_stop_speed(float gap, float decel, float headway, float dt) {
  const float g = gap - kKraussGapEps;
  if (g <= 0.0f || dt <= 0.0f) return 0.0f;
  const float b = lp_fmaxf(decel, kIdmEps) * dt;
  const float t = headway;
  const float s = dt;
  // The closed form of the largest n; float rounding may leave it one off, settled against the definition.
  const float root = sqrtf(s * s + 4.0f * (s * (2.0f * g / b - t) + t * t));
  float n = floorf(0.5f - (t - 0.5f * root) / s);
  if (n < 0.0f) n = 0.0f;
  if (krauss_braking_distance(n + 1.0f, b, t, s) <= g) n += 1.0f;
  if (n > 0.0f && krauss_braking_distance(n, b, t, s) > g) n -= 1.0f;
  const float r = lp_fmaxf(0.0f, (g - krauss_braking_distance(n, b, t, s)) / (n * s + t));
  return n * b + r;
}

/// Braking SUMO takes as needed to stop behind a leader (calculateEmergencyDeceleration): what stops the
/// follower within the gap plus the leader's braking distance when that is at most the leader's decel,
/// else what keeps it behind a leader that brakes as hard.
LPSIM_HD float krauss_needed_decel(float gap2pred, float speed, float leader_speed, float leader_decel,
                                   float emergency_decel) {
  if (gap2pred <= 0.0f) return emergency_decel;
  const float pred_brake = 0.5f * leader_speed * leader_speed / lp_fmaxf(leader_decel, kIdmEps);
  const float b1 = 0.5f * speed * speed / (gap2pred + pred_brake);
  if (b1 <= leader_decel) return b1;
  return 0.5f * (speed * speed - leader_speed * leader_speed) / gap2pred;
}

/// SUMO's maximumSafeFollowSpeed (Euler): the fastest next speed from which this vehicle, braking at its
/// decel after its headway tau, stops behind a leader `gap2pred` metres ahead (already net of minGap) that
/// brakes at max(decel, leader_decel) from leader_speed. Where that needs harder than comfortable braking,
/// the braking the situation needs (with SUMO's margin) is taken instead, between decel and what the safe
/// speed asked for.
LPSIM_HD float krauss_safe_follow_speed(const IdmParams& p, float speed, float gap2pred, float leader_speed,
                                        float leader_decel, float dt) {
  float x;
  if (gap2pred >= 0.0f) {
    const float leader_room = stopping_distance(leader_speed, lp_fmaxf(p.decel, leader_decel), dt);
    x = krauss_safe_stop_speed(gap2pred + leader_room, p.decel, p.tau, dt);
  } else {
    x = lp_fmaxf(0.0f, speed - p.emergency_decel * dt);
  }
  if (p.decel != p.emergency_decel && (speed - x) / dt > p.decel + kKraussDecelEps) {
    const float asked = (speed - x) / dt;
    const float needed = kKraussEmergencyAmplifier *
                         krauss_needed_decel(gap2pred, speed, leader_speed, leader_decel, p.emergency_decel);
    const float decel = lp_fminf(lp_fmaxf(needed, p.decel), asked);
    x = lp_fmaxf(0.0f, speed - decel * dt);
  }
  return x;
}

/// Krauss's next speed behind a leader: min(safe follow speed, maxNextSpeed). `gap` is bumper to bumper.
LPSIM_HD float krauss_follow_speed(const IdmParams& p, float speed, float gap, float leader_speed,
                                   float leader_decel, float dt) {
  const float v_safe = krauss_safe_follow_speed(p, speed, gap - p.min_gap, leader_speed, leader_decel, dt);
  return lp_fminf(v_safe, krauss_max_next_speed(speed, p.accel, dt));
}

/// Krauss's next speed towards a stop point `gap` metres ahead: the safe stop speed with a headway of one
/// step (SUMO passes the action step length, so the approach brakes evenly), capped by maxNextSpeed.
LPSIM_HD float krauss_stop_speed(const IdmParams& p, float speed, float gap, float dt) {
  return lp_fminf(krauss_safe_stop_speed(gap, p.decel, dt, dt), krauss_max_next_speed(speed, p.accel, dt));
}

/// Krauss's free-road speed: accelerate at accel up to the desired speed v0 (the lane's limit times the
/// speed factor, capped by the vehicle's maximum speed). A vehicle above v0 drops to it.
LPSIM_HD float krauss_free_speed(const IdmParams& p, float speed, float v0, float dt) {
  return lp_fminf(speed + p.accel * dt, v0);
}

/// SUMO's dawdle2 (Euler): the speed less sigma times a uniform draw `u` in [0, 1) times accel*dt, or times
/// speed*dt below accel (a vehicle starting from a stop is slowed in proportion, never kept standing);
/// never negative.
LPSIM_HD float krauss_dawdle(float speed, float accel, float sigma, float u, float dt) {
  const float scale = speed < accel ? speed : accel;
  return lp_fmaxf(0.0f, speed - sigma * scale * u * dt);
}

/// Final speed of a Krauss vehicle from the minimum `candidate` of all its bounds (SUMO's finalizeSpeed with
/// patchSpeedBeforeLC): the candidate capped by accelerating at accel, then dawdled, but never below
/// braking comfortably (unless the candidate itself is lower), nor below braking at emergency_decel.
LPSIM_HD float krauss_finalize_speed(const IdmParams& p, float speed, float candidate, float u, float dt) {
  const float v_min_emergency = lp_fmaxf(0.0f, speed - p.emergency_decel * dt);
  const float v_min = lp_fminf(lp_fmaxf(0.0f, speed - p.decel * dt), lp_fmaxf(candidate, v_min_emergency));
  const float v_max = lp_fminf(candidate, speed + p.accel * dt);
  return lp_fmaxf(v_min, krauss_dawdle(v_max, p.accel, p.sigma, u, dt));
}

/// Distance to stop from `speed` braking at decel each step (Euler) after a reaction of `headway` seconds
/// at that speed: SUMO's brakeGap (brakeGapEuler).
LPSIM_HD float krauss_brake_gap(float speed, float decel, float headway, float dt) {
  return stopping_distance(speed, decel, dt) + speed * headway;
}

/// SUMO's secure gap for Krauss (MSCFModel::getSecureGap): the room, minGap not counted, a vehicle at
/// `speed` needs to a leader at leader_speed, which is assumed to brake at max(decel, leader_decel).
LPSIM_HD float krauss_secure_gap(const IdmParams& p, float speed, float leader_speed, float leader_decel,
                                 float dt) {
  return lp_fmaxf(0.0f, krauss_brake_gap(speed, p.decel, p.tau, dt) -
                            krauss_brake_gap(leader_speed, lp_fmaxf(p.decel, leader_decel), 0.0f, dt));
}

/// SUMO's insertion speed for Krauss (insertionFollowSpeed: maximumSafeFollowSpeed on insertion, without
/// the emergency-braking correction): the fastest speed from which the vehicle stops behind a leader
/// `gap` metres ahead (bumper to bumper) braking as in krauss_safe_follow_speed.
LPSIM_HD float krauss_insertion_speed(const IdmParams& p, float gap, float leader_speed, float leader_decel,
                                      float dt) {
  const float gap2pred = gap - p.min_gap;
  if (gap2pred < 0.0f) return 0.0f;
  const float leader_room = stopping_distance(leader_speed, lp_fmaxf(p.decel, leader_decel), dt);
  return krauss_safe_stop_speed(gap2pred + leader_room, p.decel, p.tau, dt);
}

}  // namespace lpsim

#pragma once
// Longitudinal model: the Intelligent Driver Model (Treiber) integrated as SUMO does (sub-steps within one
// simulation step), capped by a ballistic safe speed that guarantees a vehicle can always stop behind its
// leader. Pure float functions shared by the CPU and CUDA step kernels; see docs/MODELS.md.
//
// Gap convention (all functions here): `gap` is the bumper-to-bumper distance in metres from this vehicle's
// front bumper to the leader's rear bumper (or to a stop point), with NOTHING subtracted. IDM adds min_gap
// itself as its jam distance s0. SUMO's `gap2pred` is this gap minus the follower's minGap.
//
// Position update assumed by the safety guarantee: semi-implicit Euler, x(t+dt) = x(t) + v(t+dt) * dt (SUMO's
// default), with every vehicle choosing its next speed from the state at the start of the step.
#include <math.h>
#include <stdint.h>

#include "kernels/hd.hpp"

namespace lpsim {

/// The car-following model of a vehicle type (the TypeView's model column; SUMO's carFollowModel).
enum CarFollowModel : uint8_t { kCarFollowIdm = 0, kCarFollowKrauss = 1 };

/// A vehicle type's car-following parameters. The IDM reads the first six; Krauss (krauss.hpp) reads accel,
/// decel, emergency_decel, tau (its headway), min_gap and sigma; `model` says which (car_following.hpp).
struct IdmParams {
  float accel;            // a: maximum acceleration [m/s^2]
  float decel;            // b: comfortable deceleration [m/s^2]
  float emergency_decel;  // hardest physically possible braking [m/s^2]
  float tau;              // T: desired time headway [s]
  float min_gap;          // s0: jam distance kept to the leader at standstill [m]
  float delta;            // acceleration exponent (4 in SUMO)
  float sigma = 0.0f;     // Krauss's driver imperfection (dawdling) in [0, 1]
  uint8_t model = kCarFollowIdm;
};

/// SUMO's passenger-car defaults with IDM's delta 4.
LPSIM_HD IdmParams idm_default_params() { return IdmParams{2.6f, 4.5f, 9.0f, 1.0f, 2.5f, 4.0f}; }

/// Speed substeps SUMO's IDM uses for a step of dt seconds with its default stepping of 0.25 s.
LPSIM_HD int idm_default_substeps(float dt) {
  const int n = static_cast<int>(dt / 0.25f + 0.5f);
  return n < 1 ? 1 : n;
}

// Guards against division by zero for a zero desired speed or a zero gap (metres, m/s).
constexpr float kIdmEps = 1e-3f;
// Safe-speed computations shorten the gap by this much so float rounding can never let a follower reach
// exactly zero distance [m].
constexpr float kSafeGapEps = 1e-3f;
// Below this distance to a stop point the vehicle simply stands (SUMO uses 0.01 m as well) [m].
constexpr float kStopReachedEps = 0.01f;
// A standing vehicle this close to its jam distance behind a standing leader stays standing [m].
constexpr float kStandstillSlack = 0.01f;

/// x^delta; exact products for the integer exponents 1..4 so CPU and GPU agree bit for bit (powf is only
/// used for other exponents, where the two backends may differ in the last bit).
LPSIM_HD float idm_pow_delta(float x, float delta) {
  if (delta == 4.0f) {
    const float x2 = x * x;
    return x2 * x2;
  }
  if (delta == 2.0f) return x * x;
  if (delta == 1.0f) return x;
  if (delta == 3.0f) return x * x * x;
  return powf(x, delta);
}

/// Desired (free-flow) speed, as SUMO 1.15 takes it: the lane's limit, or the type's desiredMaxSpeed where
/// lower, scaled by the driver's speed factor, capped by the vehicle's maxSpeed.
LPSIM_HD float desired_speed(float lane_speed, float speed_factor, float max_speed, float desired_max_speed) {
  return lp_fminf(lp_fminf(lane_speed, desired_max_speed) * speed_factor, max_speed);
}

// x^delta as a function object, so sub-step loops pick the exponent's code once per call instead of testing
// delta in every sub-step: PowDelta4 for SUMO's default 4 (most vTypes), PowDeltaAny otherwise. Both give
// idm_pow_delta's bits.
struct PowDelta4 {
  LPSIM_HD float operator()(float x) const {
    const float x2 = x * x;
    return x2 * x2;
  }
};
struct PowDeltaAny {
  float delta;
  LPSIM_HD float operator()(float x) const { return idm_pow_delta(x, delta); }
};

/// 2*sqrt(a*b), the denominator of the IDM's braking term (computed once per call, not per sub-step).
LPSIM_HD float idm_two_sqrt_ab(const IdmParams& p) { return 2.0f * sqrtf(p.accel * p.decel); }

/// IDM desired gap s* = s0 + max(0, v*T + v*(v - v_leader) / (2*sqrt(a*b))).
LPSIM_HD float idm_desired_gap(const IdmParams& p, float speed, float leader_speed, float jam_gap) {
  const float dynamic = speed * p.tau + speed * (speed - leader_speed) / idm_two_sqrt_ab(p);
  return jam_gap + lp_fmaxf(0.0f, dynamic);
}

/// Free-road acceleration a*(1 - (v/v0)^delta). Above the desired speed the result is bounded by -decel:
/// the raw IDM term explodes (v = 2*v0 gives -15a) where a real driver just brakes comfortably.
LPSIM_HD float idm_free_accel(const IdmParams& p, float speed, float v0) {
  const float ratio = speed / lp_fmaxf(v0, kIdmEps);
  return lp_fmaxf(p.accel * (1.0f - idm_pow_delta(ratio, p.delta)), -p.decel);
}

/// IDM acceleration towards a leader `gap` metres ahead (bumper to bumper) driving at leader_speed.
LPSIM_HD float idm_accel(const IdmParams& p, float speed, float v0, float gap, float leader_speed) {
  const float ratio = speed / lp_fmaxf(v0, kIdmEps);
  const float s_star = idm_desired_gap(p, speed, leader_speed, p.min_gap);
  const float s = lp_fmaxf(gap, kIdmEps);
  const float interaction = (s_star / s) * (s_star / s);
  return p.accel * (1.0f - idm_pow_delta(ratio, p.delta) - interaction);
}

/// IDM acceleration towards a stop point (red light, junction entry, lane end) `gap` metres ahead: a
/// standing leader with jam distance 0, so the front bumper may come right up to the line (as SUMO's
/// stopSpeed, which does not respect minGap at stop points).
LPSIM_HD float idm_stop_accel(const IdmParams& p, float speed, float v0, float gap) {
  const float ratio = speed / lp_fmaxf(v0, kIdmEps);
  const float s_star = idm_desired_gap(p, speed, 0.0f, 0.0f);
  const float s = lp_fmaxf(gap, kIdmEps);
  const float interaction = (s_star / s) * (s_star / s);
  return p.accel * (1.0f - idm_pow_delta(ratio, p.delta) - interaction);
}

LPSIM_HD int idm_substep_count(int substeps) { return substeps < 1 ? 1 : substeps; }

// Cruising at the desired speed: every free-road sub-step adds exactly zero (v/v0 is exactly 1).
LPSIM_HD bool idm_cruising(float speed, float v0) { return speed == v0 && v0 >= kIdmEps; }

/// Constants of one call's sub-step loop. The loops are chains of dependent operations, so their latency is
/// the step's cost: the divisions by v0 and by 2*sqrt(ab) are hoisted out as reciprocals (a multiply has a
/// third of a divide's latency on a CPU and is one instruction where a correctly rounded divide is a
/// sequence on a GPU), and accel, decel and the sub-step length are folded into per-sub-step speed changes.
/// Both backends evaluate the same expressions in the same order, so their results stay bit-identical.
struct IdmSubsteps {
  int n;                  // sub-steps
  float h;                // sub-step length [s]
  float inv_v0;           // 1 / max(v0, kIdmEps)
  float inv_two_sqrt_ab;  // 1 / (2*sqrt(a*b))
  float accel_h;          // a*h: speed gained in a sub-step at full acceleration
  float decel_h;          // b*h: speed lost in a sub-step of comfortable braking
};

LPSIM_HD IdmSubsteps idm_substeps(const IdmParams& p, float v0, float dt, int substeps) {
  const int n = idm_substep_count(substeps);
  const float h = dt / static_cast<float>(n);
  return IdmSubsteps{n, h, 1.0f / lp_fmaxf(v0, kIdmEps), 1.0f / idm_two_sqrt_ab(p), p.accel * h, p.decel * h};
}

// One free-road Euler sub-step: v + a*h*(1 - (v/v0)^delta), the change bounded by comfortable braking.
template <class Pow>
LPSIM_HD float idm_free_substep(const IdmSubsteps& c, Pow pow_delta, float v) {
  return lp_fmaxf(0.0f, v + lp_fmaxf(c.accel_h * (1.0f - pow_delta(v * c.inv_v0)), -c.decel_h));
}

// One Euler sub-step towards a leader (or stop point) `s` metres ahead at leader_speed: the IDM's
// a*h*(1 - (v/v0)^delta - (s*/s)^2) with s* = jam_gap + max(0, v*T + v*(v - v_leader)/(2*sqrt(ab))).
template <class Pow>
LPSIM_HD float idm_interaction_substep(const IdmSubsteps& c, Pow pow_delta, float tau, float v, float s,
                                       float leader_speed, float jam_gap) {
  const float dynamic = v * tau + v * (v - leader_speed) * c.inv_two_sqrt_ab;
  const float s_star = jam_gap + lp_fmaxf(0.0f, dynamic);
  const float q = s_star * (1.0f / lp_fmaxf(s, kIdmEps));
  return lp_fmaxf(0.0f, v + c.accel_h * ((1.0f - pow_delta(v * c.inv_v0)) - q * q));
}

// Euler sub-steps can overshoot the desired speed by a little; like SUMO's cap at the lane's maximum speed,
// a vehicle that was not faster never ends above it.
LPSIM_HD float idm_free_result(float speed, float v0, float v) { return speed <= v0 ? lp_fminf(v, v0) : v; }

template <class Pow>
LPSIM_HD float idm_free_speed_with(const IdmParams& p, Pow pow_delta, float speed, float v0, float dt,
                                   int substeps) {
  if (idm_cruising(speed, v0)) return v0;
  const IdmSubsteps c = idm_substeps(p, v0, dt, substeps);
  float v = speed;
  for (int i = 0; i < c.n; ++i) v = idm_free_substep(c, pow_delta, v);
  return idm_free_result(speed, v0, v);
}

/// IDM speed after dt on a free road, integrated in `substeps` equal speed updates.
LPSIM_HD float idm_free_speed(const IdmParams& p, float speed, float v0, float dt, int substeps) {
  if (p.delta == 4.0f) return idm_free_speed_with(p, PowDelta4{}, speed, v0, dt, substeps);
  return idm_free_speed_with(p, PowDeltaAny{p.delta}, speed, v0, dt, substeps);
}

// Shared sub-step loop for a leader or stop point: the gap shrinks by the closing distance of each sub-step
// (never grows, as in SUMO, which assumes the leader keeps its speed). jam_gap selects leader vs stop.
// With free_speed set, the free-road speed (idm_free_speed) is integrated in the same loop: the two chains
// are independent and latency-bound, so interleaving them lets the processor overlap them. Each chain
// performs exactly the operations of its separate computation, so results are bit-identical either way.
template <class Pow>
LPSIM_HD float idm_interaction_speed_with(const IdmParams& p, Pow pow_delta, float speed, float v0, float gap,
                                          float leader_speed, float jam_gap, float dt, int substeps,
                                          float* free_speed) {
  const IdmSubsteps c = idm_substeps(p, v0, dt, substeps);
  const bool free_loop = free_speed != nullptr && !idm_cruising(speed, v0);
  float v = speed;
  float vf = speed;
  float s = gap;
  for (int i = 0; i < c.n; ++i) {
    if (free_loop) vf = idm_free_substep(c, pow_delta, vf);
    v = idm_interaction_substep(c, pow_delta, p.tau, v, s, leader_speed, jam_gap);
    s -= lp_fmaxf(0.0f, (v - leader_speed) * c.h);
  }
  if (free_speed != nullptr) *free_speed = free_loop ? idm_free_result(speed, v0, vf) : v0;
  return v;
}

LPSIM_HD float idm_interaction_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                                     float jam_gap, float dt, int substeps, float* free_speed = nullptr) {
  if (p.delta == 4.0f)
    return idm_interaction_speed_with(p, PowDelta4{}, speed, v0, gap, leader_speed, jam_gap, dt, substeps,
                                      free_speed);
  return idm_interaction_speed_with(p, PowDeltaAny{p.delta}, speed, v0, gap, leader_speed, jam_gap, dt,
                                    substeps, free_speed);
}

/// IDM speed after dt following a leader (IDM only; see follow_speed for the version with the safety cap).
LPSIM_HD float idm_follow_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                                float dt, int substeps, float* free_speed = nullptr) {
  return idm_interaction_speed(p, speed, v0, gap, leader_speed, p.min_gap, dt, substeps, free_speed);
}

/// IDM speed after dt approaching a stop point `gap` metres ahead (IDM only; see stop_speed).
LPSIM_HD float idm_stop_speed(const IdmParams& p, float speed, float v0, float gap, float dt, int substeps,
                              float* free_speed = nullptr) {
  return idm_interaction_speed(p, speed, v0, gap, 0.0f, 0.0f, dt, substeps, free_speed);
}

/// Distance covered from now to standstill when braking at `decel` from `speed` under Euler stepping: the
/// speeds of the next steps are v - b*dt, v - 2*b*dt, ... (each held for dt) until they reach zero.
LPSIM_HD float stopping_distance(float speed, float decel, float dt) {
  const float step_loss = lp_fmaxf(decel, kIdmEps) * dt;  // speed lost per step
  if (speed <= step_loss) return 0.0f;
  const float n = lp_floor_nonneg(speed / step_loss);  // steps that still move (speed > step_loss > 0)
  return dt * (n * speed - step_loss * n * (n + 1.0f) * 0.5f);
}

/// How far ahead a vehicle must scan for leaders and stop points: the distance it could cover by
/// accelerating for one step and then braking comfortably to a stop, plus its jam gap.
LPSIM_HD float lookahead_distance(const IdmParams& p, float speed, float dt) {
  const float v_next = speed + p.accel * dt;
  return v_next * dt + stopping_distance(v_next, p.decel, dt) + p.min_gap;
}

/// Largest speed x for the next step such that x*dt plus the Euler braking distance from x at own_decel
/// fits in `budget` metres. With x = n*b' + r (b' = own_decel*dt, 0 <= r < b') the distance is
/// dt*((n+1)*r + b'*n*(n+1)/2), which is solved for the largest n, then r.
LPSIM_HD float max_speed_within(float budget, float own_decel, float dt) {
  if (budget <= 0.0f || dt <= 0.0f) return 0.0f;
  const float b = lp_fmaxf(own_decel, kIdmEps) * dt;
  const float sum = budget / dt;  // budget expressed as a sum of step speeds
  float n = lp_floor_nonneg((sqrtf(1.0f + 8.0f * sum / b) - 1.0f) * 0.5f);  // sqrt(1 + ...) >= 1
  if (n < 0.0f) n = 0.0f;
  // sqrtf rounding may leave n one off the exact integer; settle it against the defining inequality.
  if (b * (n + 1.0f) * (n + 2.0f) * 0.5f <= sum) n += 1.0f;
  if (n > 0.0f && b * n * (n + 1.0f) * 0.5f > sum) n -= 1.0f;
  const float r = lp_fminf(lp_fmaxf((sum - b * n * (n + 1.0f) * 0.5f) / (n + 1.0f), 0.0f), b);
  return n * b + r;
}

/// Ballistic (Krauss-style) safe speed: the fastest next speed from which this vehicle, braking at
/// own_decel, stops behind a leader `gap` metres ahead that brakes at up to leader_decel from leader_speed.
/// The leader is assumed to brake at least as hard as the follower (max of both decels, as SUMO does) so the
/// follower cannot reach the leader's standstill point "through" it while braking harder. Invariant: if a
/// vehicle used a speed <= safe_speed last step, then max(0, v - own_decel*dt) is <= safe_speed now, so
/// own_decel always suffices and there is no collision as long as the leader brakes at most leader_decel.
LPSIM_HD float safe_speed(float gap, float leader_speed, float leader_decel, float own_decel, float dt) {
  const float leader_room = stopping_distance(leader_speed, lp_fmaxf(leader_decel, own_decel), dt);
  return max_speed_within(gap - kSafeGapEps + leader_room, own_decel, dt);
}

/// Fastest next speed from which the vehicle can stop before a point `gap` metres ahead braking at decel.
LPSIM_HD float safe_stop_speed(float gap, float decel, float dt) {
  return max_speed_within(gap - kSafeGapEps, decel, dt);
}

/// Whether a vehicle at `speed` can stop before a point `gap` ahead without braking harder than decel.
LPSIM_HD bool can_stop_before(float gap, float speed, float decel, float dt) {
  return lp_fmaxf(0.0f, speed - decel * dt) <= safe_stop_speed(gap, decel, dt);
}

/// Next speed following a leader: min(IDM, safe speed). leader_decel is the hardest braking the leader may
/// use (its emergency decel for the hard guarantee); the follower plans with its comfortable decel.
/// With free_speed set, also stores idm_free_speed's result there (computed alongside, same bits), except
/// where the result is 0 without the IDM (standing in a queue): a free speed, never negative, could not
/// lower it, and *free_speed is left as it was.
LPSIM_HD float follow_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                            float leader_decel, float dt, int substeps, float* free_speed = nullptr) {
  // Standing within the jam distance of a standing leader (or less than kStandstillSlack beyond it): stays.
  // Within the jam distance every IDM sub-step gives exactly 0 (the interaction term is at least 1). Just
  // beyond it the IDM creeps asymptotically, by micrometres per step that a position far along a lane
  // rounds away, so the same queued vehicle would compute the same creep every step. The most common state
  // in queues, so worth the test.
  // One branch for the three tests (each alone would be a mispredicted branch).
  if ((speed == 0.0f) & (leader_speed == 0.0f) & (gap <= p.min_gap + kStandstillSlack)) return 0.0f;
  const float v_idm = idm_follow_speed(p, speed, v0, gap, leader_speed, dt, substeps, free_speed);
  return lp_fminf(v_idm, safe_speed(gap, leader_speed, leader_decel, p.decel, dt));
}

/// Next speed approaching a stop point: zero once within kStopReachedEps, else min(IDM, safe stop speed).
/// A standing vehicle close to the line gets a zero IDM speed (its own first sub-step closes too much of
/// the gap); like SUMO it then moves up with the safe stop speed instead of standing short of the line.
/// With free_speed set, as follow_speed: idm_free_speed's result, or left as it was when the result is 0
/// without the IDM (the stop point reached).
LPSIM_HD float stop_speed(const IdmParams& p, float speed, float v0, float gap, float dt, int substeps,
                          float* free_speed = nullptr) {
  if (gap < kStopReachedEps) return 0.0f;
  const float v_safe = safe_stop_speed(gap, p.decel, dt);
  const float v_idm = idm_stop_speed(p, speed, v0, gap, dt, substeps, free_speed);
  if (speed < kIdmEps && v_idm < kIdmEps) return v_safe;
  return lp_fminf(v_idm, v_safe);
}

/// Final speed for the step from the minimum of all candidate speeds (free, leaders, stop points): never
/// faster than accelerating at accel, never slower than braking at emergency_decel, never negative.
LPSIM_HD float finalize_speed(const IdmParams& p, float speed, float candidate, float dt) {
  const float fastest = speed + p.accel * dt;
  const float slowest = lp_fmaxf(0.0f, speed - p.emergency_decel * dt);
  return lp_fminf(lp_fmaxf(candidate, slowest), fastest);
}

/// SUMO's IDM secure gap (getSecureGap): the room, minGap not counted, a vehicle at `speed` keeps to a
/// leader at leader_speed.
LPSIM_HD float idm_secure_gap(const IdmParams& p, float speed, float leader_speed) {
  return lp_fmaxf(0.0f, speed * p.tau + speed * (speed - leader_speed) / (2.0f * sqrtf(p.accel * p.decel)));
}

/// SUMO's IDM insertion speed behind a leader `gap` metres ahead (bumper to bumper): the wished speed where
/// the gap, minGap not counted, is at least the IDM's desired one (idm_secure_gap); else the IDM's next
/// speed, lowered again while the step after it would still brake by more than 1 m/s^2.
LPSIM_HD float idm_insertion_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                                   float dt, int substeps) {
  const float room = gap - p.min_gap;
  for (int k = 0; k < 64; ++k) {
    if (room >= idm_secure_gap(p, speed, leader_speed)) return speed;
    const float s2 = idm_follow_speed(p, speed, v0, gap, leader_speed, dt, substeps);
    const float s3 = idm_follow_speed(p, s2, v0, gap, leader_speed, dt, substeps);
    if (s2 - s3 < 1.0f * dt) return s2;
    speed = s2;
  }
  return speed;
}

}  // namespace lpsim

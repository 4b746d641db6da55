#pragma once
// The car-following speeds the step asks for (free road, behind a leader, towards a stop point, the final
// speed, accelerations for lane-change decisions), dispatched on each vehicle type's model: IDM (idm.hpp)
// or Krauss (krauss.hpp), as SUMO chooses per vType. The step has one code path; only these calls differ.
// With the IDM every function returns exactly what the IDM function it forwards to returns.
#include <stdint.h>

#include "kernels/hd.hpp"
#include "kernels/idm.hpp"
#include "kernels/krauss.hpp"
#include "kernels/rng.hpp"

namespace lpsim {

// Salt that separates the Krauss dawdle draws from every other use of (seed, vehicle, step).
constexpr uint64_t kDawdleRngSalt = 0x4441574444524157ull;  // "DAWDDRAW"

LPSIM_HD bool is_krauss(const IdmParams& p) { return p.model == kCarFollowKrauss; }

/// Speed after dt on a free road towards the desired speed v0.
LPSIM_HD float cf_free_speed(const IdmParams& p, float speed, float v0, float dt, int substeps) {
  if (is_krauss(p)) return krauss_free_speed(p, speed, v0, dt);
  return idm_free_speed(p, speed, v0, dt, substeps);
}

/// Next speed behind a leader `gap` metres ahead (bumper to bumper). leader_decel: the hardest braking the
/// IDM's safety cap assumes of the leader. Krauss assumes, as SUMO's Krauss, the leader's comfortable
/// decel; the step cannot see the leader's type in the lane map and takes the follower's own (exact for
/// a fleet of one decel, and never less safe than SUMO where the follower brakes harder).
/// free_speed: as follow_speed's (the IDM's free-road speed computed alongside); left untouched by Krauss.
LPSIM_HD float cf_follow_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                               float leader_decel, float dt, int substeps, float* free_speed = nullptr) {
  if (is_krauss(p)) return krauss_follow_speed(p, speed, gap, leader_speed, p.decel, dt);
  return follow_speed(p, speed, v0, gap, leader_speed, leader_decel, dt, substeps, free_speed);
}

/// Next speed towards a stop point `gap` metres ahead. free_speed: as cf_follow_speed's.
LPSIM_HD float cf_stop_speed(const IdmParams& p, float speed, float v0, float gap, float dt, int substeps,
                             float* free_speed = nullptr) {
  if (is_krauss(p)) return gap < kStopReachedEps ? 0.0f : krauss_stop_speed(p, speed, gap, dt);
  return stop_speed(p, speed, v0, gap, dt, substeps, free_speed);
}

/// Final speed from the minimum of all candidate speeds. Krauss vehicles dawdle here, with a draw keyed by
/// (seed, vehicle, step) only, so every thread and backend draws the same.
LPSIM_HD float cf_finalize_speed(const IdmParams& p, float speed, float candidate, float dt, uint64_t seed,
                                 uint32_t vehicle, uint32_t step) {
  if (is_krauss(p)) {
    const float u = p.sigma > 0.0f ? rng_uniform(seed ^ kDawdleRngSalt, vehicle, step) : 0.0f;
    return krauss_finalize_speed(p, speed, candidate, u, dt);
  }
  return finalize_speed(p, speed, candidate, dt);
}

/// Acceleration on a free road (lane-change incentives).
LPSIM_HD float cf_free_accel(const IdmParams& p, float speed, float v0, float dt) {
  if (is_krauss(p)) return (krauss_free_speed(p, speed, v0, dt) - speed) / dt;
  return idm_free_accel(p, speed, v0);
}

/// Acceleration behind a leader `gap` metres ahead (lane-change gap acceptance and incentives). For Krauss
/// the speed change of one step towards min(free, follow) speed, per second.
LPSIM_HD float cf_accel(const IdmParams& p, float speed, float v0, float gap, float leader_speed, float dt) {
  if (is_krauss(p)) {
    const float v = lp_fminf(krauss_free_speed(p, speed, v0, dt),
                             krauss_follow_speed(p, speed, gap, leader_speed, p.decel, dt));
    return (v - speed) / dt;
  }
  return idm_accel(p, speed, v0, gap, leader_speed);
}

/// Room (minGap not counted) a vehicle at `speed` keeps to a leader at leader_speed when inserted: the
/// secure gap of its model (the leader's type is not in the lane map: Krauss assumes its own decel).
LPSIM_HD float cf_secure_gap(const IdmParams& p, float speed, float leader_speed, float dt) {
  if (is_krauss(p)) return krauss_secure_gap(p, speed, leader_speed, p.decel, dt);
  return idm_secure_gap(p, speed, leader_speed);
}

/// Fastest speed at which a vehicle may be inserted `gap` metres (bumper to bumper) behind a leader at
/// leader_speed, wishing `speed`: its model's insertion speed, never above `speed`.
LPSIM_HD float cf_insertion_speed(const IdmParams& p, float speed, float v0, float gap, float leader_speed,
                                  float dt, int substeps) {
  if (is_krauss(p)) return lp_fminf(speed, krauss_insertion_speed(p, gap, leader_speed, p.decel, dt));
  return idm_insertion_speed(p, speed, v0, gap, leader_speed, dt, substeps);
}

}  // namespace lpsim

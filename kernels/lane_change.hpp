#pragma once
// Lane-change decisions: gap acceptance (kinematically safe for both the changer and its new follower),
// mandatory-change urgency by distance to the lane end, and a MOBIL-style discretionary incentive. Pure
// functions of plain numbers; the engine gathers neighbours from its lane map. See docs/MODELS.md.
#include <stdint.h>

#include "kernels/car_following.hpp"
#include "kernels/hd.hpp"
#include "kernels/rng.hpp"

namespace lpsim {

struct LaneChangeParams {
  float politeness;               // MOBIL p: weight of the followers' acceleration changes
  float threshold;                // MOBIL a_thr: minimum net gain to change for speed [m/s^2]
  float b_safe;                   // strongest braking a discretionary change may impose [m/s^2]
  float mandatory_dist_per_lane;  // mandatory zone per lane still to cross, at low speed [m]
  float mandatory_time_per_lane;  // mandatory zone per lane still to cross, as travel time [s]
};

LPSIM_HD LaneChangeParams lane_change_default_params() {
  return LaneChangeParams{0.5f, 0.2f, 2.0f, 50.0f, 4.0f};
}

/// A vehicle next to the changer on the target (or current) lane, as the engine sees it.
struct LcNeighbor {
  bool present;         // false: no vehicle within the look-ahead/look-back range (other fields ignored)
  float gap;            // bumper-to-bumper distance to the changer [m] (lead: changer front -> its rear;
                        // lag: its front -> changer rear)
  float speed;          // [m/s]
  float desired_speed;  // its v0, needed to evaluate its IDM acceleration [m/s]
  IdmParams idm;
};

LPSIM_HD LcNeighbor lc_no_neighbor() {
  return LcNeighbor{false, 0.0f, 0.0f, 0.0f, IdmParams{0, 0, 0, 0, 0, 0}};
}

/// Acceleration of a vehicle by its car-following model given its leader (free road when there is none).
LPSIM_HD float lc_accel_behind(const IdmParams& p, float speed, float v0, const LcNeighbor& leader,
                               float dt) {
  if (!leader.present) return cf_free_accel(p, speed, v0, dt);
  return cf_accel(p, speed, v0, leader.gap, leader.speed, dt);
}

/// The changer behind the target lane's leader stays safe: it can keep the safe-speed invariant (see
/// safe_speed) braking no harder than its comfortable decel, even if that leader brakes at its emergency
/// decel.
LPSIM_HD bool lc_lead_gap_safe(const IdmParams& self, float self_speed, const LcNeighbor& lead, float dt) {
  if (!lead.present) return true;
  if (lead.gap <= 0.0f) return false;
  const float v_safe = safe_speed(lead.gap, lead.speed, lead.idm.emergency_decel, self.decel, dt);
  return lp_fmaxf(0.0f, self_speed - self.decel * dt) <= v_safe;
}

/// The target lane's follower stays safe behind the changer: braking at its own decel (the "b_safe" hard
/// limit) keeps the safe-speed invariant even if the changer brakes at its emergency decel.
LPSIM_HD bool lc_lag_gap_safe(const IdmParams& self, float self_speed, const LcNeighbor& lag, float dt) {
  if (!lag.present) return true;
  if (lag.gap <= 0.0f) return false;
  const float v_safe = safe_speed(lag.gap, self_speed, self.emergency_decel, lag.idm.decel, dt);
  return lp_fmaxf(0.0f, lag.speed - lag.idm.decel * dt) <= v_safe;
}

/// Gap acceptance. urgency in [0, 1] (0 = discretionary, 1 = must change now) scales the braking that the
/// change may impose through the car-following model from lc.b_safe up to each vehicle's comfortable decel,
/// so urgent changes accept smaller gaps; the kinematic checks are never relaxed, so no accepted change is
/// unsafe.
LPSIM_HD bool lc_gaps_acceptable(const IdmParams& self, float self_speed, float self_v0,
                                 const LcNeighbor& lead, const LcNeighbor& lag, float urgency,
                                 const LaneChangeParams& lc, float dt) {
  const float u = lp_fminf(lp_fmaxf(urgency, 0.0f), 1.0f);
  if (!lc_lead_gap_safe(self, self_speed, lead, dt) || !lc_lag_gap_safe(self, self_speed, lag, dt))
    return false;
  if (lead.present) {
    const float b_self = lc.b_safe + u * lp_fmaxf(self.decel - lc.b_safe, 0.0f);
    if (cf_accel(self, self_speed, self_v0, lead.gap, lead.speed, dt) < -b_self) return false;
  }
  if (lag.present) {
    const float b_lag = lc.b_safe + u * lp_fmaxf(lag.idm.decel - lc.b_safe, 0.0f);
    if (cf_accel(lag.idm, lag.speed, lag.desired_speed, lag.gap, self_speed, dt) < -b_lag) return false;
  }
  return true;
}

/// Length of road before a lane's end within which a vehicle that still has lanes_to_cross lane changes to
/// do is in mandatory mode: per lane, the larger of a fixed distance and a travel time at current speed.
LPSIM_HD float mandatory_lc_zone(int lanes_to_cross, float speed, const LaneChangeParams& lc) {
  if (lanes_to_cross <= 0) return 0.0f;
  return static_cast<float>(lanes_to_cross) *
         lp_fmaxf(lc.mandatory_dist_per_lane, speed * lc.mandatory_time_per_lane);
}

/// Urgency in [0, 1] of a mandatory change: 0 outside the zone, rising linearly to 1 at the lane's end.
LPSIM_HD float mandatory_lc_urgency(float dist_to_end, int lanes_to_cross, float speed,
                                    const LaneChangeParams& lc) {
  const float zone = mandatory_lc_zone(lanes_to_cross, speed, lc);
  if (zone <= 0.0f || dist_to_end >= zone) return 0.0f;
  return lp_fminf(lp_fmaxf(1.0f - dist_to_end / zone, 0.0f), 1.0f);
}

/// MOBIL incentive: own acceleration gain plus politeness times the gains of the new follower (usually a
/// loss) and of the old follower (usually a gain).
LPSIM_HD float mobil_incentive(float a_self_now, float a_self_after, float a_new_lag_now,
                               float a_new_lag_after, float a_old_lag_now, float a_old_lag_after,
                               float politeness) {
  return (a_self_after - a_self_now) +
         politeness * ((a_new_lag_after - a_new_lag_now) + (a_old_lag_after - a_old_lag_now));
}

/// Discretionary change for speed: evaluates MOBIL for moving from the current lane (leader cur_lead,
/// follower old_lag) to a target lane (leader target_lead, follower target_lag). bias is added to the
/// threshold (positive discourages this direction, e.g. for a keep-right rule). Gaps must be acceptable
/// with urgency 0.
LPSIM_HD bool discretionary_change_wanted(const IdmParams& self, float self_speed, float self_v0,
                                          float self_length, const LcNeighbor& cur_lead,
                                          const LcNeighbor& old_lag, const LcNeighbor& target_lead,
                                          const LcNeighbor& target_lag, float bias,
                                          const LaneChangeParams& lc, float dt) {
  if (!lc_gaps_acceptable(self, self_speed, self_v0, target_lead, target_lag, 0.0f, lc, dt)) return false;
  const float a_self_now = lc_accel_behind(self, self_speed, self_v0, cur_lead, dt);
  const float a_self_after = lc_accel_behind(self, self_speed, self_v0, target_lead, dt);
  float a_new_lag_now = 0.0f, a_new_lag_after = 0.0f;
  if (target_lag.present) {
    // Before the change the target follower sees the target leader beyond the changer's slot.
    LcNeighbor beyond = target_lead;
    beyond.gap = target_lead.gap + self_length + target_lag.gap;
    a_new_lag_now = lc_accel_behind(target_lag.idm, target_lag.speed, target_lag.desired_speed, beyond, dt);
    a_new_lag_after =
        cf_accel(target_lag.idm, target_lag.speed, target_lag.desired_speed, target_lag.gap, self_speed, dt);
  }
  float a_old_lag_now = 0.0f, a_old_lag_after = 0.0f;
  if (old_lag.present) {
    a_old_lag_now = cf_accel(old_lag.idm, old_lag.speed, old_lag.desired_speed, old_lag.gap, self_speed, dt);
    LcNeighbor beyond = cur_lead;
    beyond.gap = cur_lead.gap + self_length + old_lag.gap;
    a_old_lag_after = lc_accel_behind(old_lag.idm, old_lag.speed, old_lag.desired_speed, beyond, dt);
  }
  const float gain = mobil_incentive(a_self_now, a_self_after, a_new_lag_now, a_new_lag_after, a_old_lag_now,
                                     a_old_lag_after, lc.politeness);
  return gain > lc.threshold + bias;
}

/// Slowest deceleration with which a blocked mandatory changer falls behind the target lane's leader [m/s^2].
constexpr float kLcMinFallBehind = 0.5f;

/// Whether a mandatory changer can pass the target lane's vehicle that blocks it (gap: from the changer's
/// front to that vehicle's rear, negative while they overlap) and still change ahead of it before its lane
/// ends (`left_space` ahead, `remaining_s` seconds at its pace): it must be faster, have the room to get
/// fully ahead with that vehicle's secure gap behind it plus its own braking distance, and the time to do so.
LPSIM_HD bool lc_can_overtake(float speed, float leader_speed, float gap, float leader_length_with_gap,
                              float own_length, float leader_secure_gap, float left_space, float brake_gap,
                              float remaining_s) {
  const float dv = speed - leader_speed;
  if (dv <= 0.0f) return false;
  const float dist = lp_fmaxf(gap + leader_length_with_gap + own_length + leader_secure_gap, 0.0f);
  return left_space - brake_gap >= dist && remaining_s >= dist / dv;
}

/// Next speed of a mandatory changer that cannot overtake the target lane's vehicle: it slows towards
/// `follow`, spreading the deceleration over the `remaining_s` seconds left (at least kLcMinFallBehind, at
/// most its decel), so that it drops in behind that vehicle. No bound (1e30) when that needs no slowing.
LPSIM_HD float lc_fall_behind_speed(float speed, float follow, float decel, float remaining_s, float dt) {
  if (follow >= speed) return 1e30f;
  const float b = remaining_s > 0.0f
                      ? lp_fminf(decel, lp_fmaxf(kLcMinFallBehind, (speed - follow) / remaining_s))
                      : decel;
  return lp_fmaxf(0.0f, speed - b * dt);
}

// Salt that separates lane-change draws from every other use of (seed, vehicle, step).
constexpr uint64_t kLaneChangeRngSalt = 0x4C414E4543484E47ull;  // "LANECHNG"

/// Whether a vehicle may attempt a discretionary change this step, drawn with the given probability from
/// (seed, vehicle, step) only. Thinning attempts breaks the lock-step "whole platoon changes at once"
/// artefact of parallel updates while staying identical on every backend.
LPSIM_HD bool lc_attempt_allowed(uint64_t seed, uint64_t vehicle, uint64_t step, float probability) {
  return rng_uniform(seed ^ kLaneChangeRngSalt, vehicle, step) < probability;
}

}  // namespace lpsim

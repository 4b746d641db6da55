// IDM, safe speed and stopping: hand-computed values and properties over RNG-drawn situations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "kernels/idm.hpp"
#include "kernels/rng.hpp"

namespace lpsim {
namespace {

const IdmParams kP = idm_default_params();

// Uniform float in [lo, hi) from the project RNG, keyed so each property test has its own stream.
float draw(uint64_t seed, uint64_t stream, uint64_t counter, float lo, float hi) {
  return lo + (hi - lo) * rng_uniform(seed, stream, counter);
}

TEST(ModelsIdm, DefaultsMatchSumoPassengerCar) {
  EXPECT_FLOAT_EQ(kP.accel, 2.6f);
  EXPECT_FLOAT_EQ(kP.decel, 4.5f);
  EXPECT_FLOAT_EQ(kP.emergency_decel, 9.0f);
  EXPECT_FLOAT_EQ(kP.tau, 1.0f);
  EXPECT_FLOAT_EQ(kP.min_gap, 2.5f);
  EXPECT_FLOAT_EQ(kP.delta, 4.0f);
  EXPECT_EQ(idm_default_substeps(1.0f), 4);
  EXPECT_EQ(idm_default_substeps(0.5f), 2);
  EXPECT_EQ(idm_default_substeps(0.1f), 1);
}

TEST(ModelsIdm, DesiredSpeedIsLaneSpeedTimesFactorCappedByVehicle) {
  const float none = 3.4e38f;  // no desiredMaxSpeed
  EXPECT_FLOAT_EQ(desired_speed(13.89f, 1.1f, 55.56f, none), 13.89f * 1.1f);
  EXPECT_FLOAT_EQ(desired_speed(40.0f, 1.2f, 30.0f, none), 30.0f);
}

TEST(ModelsIdm, DesiredMaxSpeedCapsTheLaneLimitBeforeTheSpeedFactor) {
  // SUMO 1.15's allowed speeds (traci.vehicle.getAllowedSpeed) on a 27.78 m/s lane: a default bicycle
  // (desiredMaxSpeed 20 km/h, maxSpeed 50 km/h, factor 1.06) 5.889; desiredMaxSpeed 4 (factor 0.9383)
  // 3.753; a car with desiredMaxSpeed 10 (factor 1.0104) 10.104.
  EXPECT_NEAR(desired_speed(27.78f, 1.06f, 50.0f / 3.6f, 20.0f / 3.6f), 5.889f, 1e-3f);
  EXPECT_NEAR(desired_speed(27.78f, 0.9383f, 50.0f / 3.6f, 4.0f), 3.753f, 1e-3f);
  EXPECT_NEAR(desired_speed(27.78f, 1.0104f, 55.56f, 10.0f), 10.104f, 1e-3f);
  // Below the desired limit the lane's speed counts: a bicycle on a 15 km/h path.
  EXPECT_NEAR(desired_speed(15.0f / 3.6f, 1.0f, 50.0f / 3.6f, 20.0f / 3.6f), 15.0f / 3.6f, 1e-5f);
}

TEST(ModelsIdm, PowDeltaUsesExactProductsForIntegerExponents) {
  EXPECT_EQ(idm_pow_delta(0.5f, 4.0f), 0.0625f);
  EXPECT_EQ(idm_pow_delta(0.5f, 3.0f), 0.125f);
  EXPECT_EQ(idm_pow_delta(0.5f, 2.0f), 0.25f);
  EXPECT_EQ(idm_pow_delta(0.5f, 1.0f), 0.5f);
  EXPECT_NEAR(idm_pow_delta(0.25f, 2.5f), 0.03125f, 1e-7f);
}

TEST(ModelsIdm, FreeAccelerationHandComputed) {
  // 2.6 * (1 - (10/20)^4) = 2.6 * 0.9375
  EXPECT_NEAR(idm_free_accel(kP, 10.0f, 20.0f), 2.4375f, 1e-6f);
  EXPECT_NEAR(idm_free_accel(kP, 0.0f, 20.0f), 2.6f, 1e-6f);
  EXPECT_NEAR(idm_free_accel(kP, 20.0f, 20.0f), 0.0f, 1e-6f);
  // Far above the desired speed the raw term (-15a at twice v0) is bounded by comfortable braking.
  EXPECT_FLOAT_EQ(idm_free_accel(kP, 40.0f, 20.0f), -4.5f);
  // A zero desired speed does not divide by zero.
  EXPECT_FLOAT_EQ(idm_free_accel(kP, 5.0f, 0.0f), -4.5f);
}

TEST(ModelsIdm, DesiredGapAndLeaderAccelerationHandComputed) {
  EXPECT_NEAR(idm_desired_gap(kP, 10.0f, 10.0f, kP.min_gap), 12.5f, 1e-5f);
  // 2.5 + 10 + 10*5 / (2*sqrt(2.6*4.5)) = 2.5 + 10 + 50 / 6.841053
  EXPECT_NEAR(idm_desired_gap(kP, 10.0f, 5.0f, kP.min_gap), 19.808810f, 1e-4f);
  // Closing in on a faster leader never makes s* smaller than the jam gap.
  EXPECT_NEAR(idm_desired_gap(kP, 0.0f, 10.0f, kP.min_gap), 2.5f, 1e-6f);
  // 2.6 * (1 - 0.0625 - (12.5/25)^2) = 2.6 * 0.6875
  EXPECT_NEAR(idm_accel(kP, 10.0f, 20.0f, 25.0f, 10.0f), 1.7875f, 1e-5f);
  // Standing at exactly the jam gap behind a standing leader: a * (0 - 0 ... ) = a*(1 - 1) = 0.
  EXPECT_NEAR(idm_accel(kP, 0.0f, 20.0f, 2.5f, 0.0f), 0.0f, 1e-6f);
  // Zero gap: strongly negative, finite.
  const float a0 = idm_accel(kP, 5.0f, 20.0f, 0.0f, 0.0f);
  EXPECT_LT(a0, -1000.0f);
  EXPECT_TRUE(std::isfinite(a0));
  // A huge gap is the free road.
  EXPECT_NEAR(idm_accel(kP, 10.0f, 20.0f, 1e7f, 10.0f), idm_free_accel(kP, 10.0f, 20.0f), 1e-5f);
}

TEST(ModelsIdm, StopAccelerationUsesZeroJamGap) {
  // Standing 10 m before the line: s* = 0, so the vehicle may still move up (a = 2.6).
  EXPECT_NEAR(idm_stop_accel(kP, 0.0f, 20.0f, 10.0f), 2.6f, 1e-6f);
  // 10 m/s, 20 m before the line: s* = 10 + 100/6.841053 = 24.61776; 2.6*(1 - 0.0625 - (24.61776/20)^2)
  EXPECT_NEAR(idm_stop_accel(kP, 10.0f, 20.0f, 20.0f), 2.6f * (0.9375f - 1.5150954f), 1e-4f);
}

TEST(ModelsIdm, SubstepIntegrationFromStandstill) {
  // Four sub-steps of 0.25 s: 0.65, then 0.65 * (1 - (v/20)^4) each; the pow terms are < 1e-3.
  const float v = idm_free_speed(kP, 0.0f, 20.0f, 1.0f, 4);
  EXPECT_NEAR(v, 2.6f, 1e-3f);
  EXPECT_LT(v, 2.6f);
  EXPECT_NEAR(idm_free_speed(kP, 0.0f, 20.0f, 0.5f, 2), 1.3f, 1e-4f);
  // One sub-step is plain Euler: v + a*dt.
  EXPECT_NEAR(idm_free_speed(kP, 10.0f, 20.0f, 1.0f, 1), 12.4375f, 1e-5f);
  // substeps < 1 is treated as 1.
  EXPECT_EQ(idm_free_speed(kP, 10.0f, 20.0f, 1.0f, 0), idm_free_speed(kP, 10.0f, 20.0f, 1.0f, 1));
}

TEST(ModelsIdm, FollowSpeedSubstepsShrinkTheGap) {
  // Approaching a standing leader 30 m ahead at 15 m/s: 4 sub-steps brake harder than one Euler step
  // evaluated at the initial gap would predict, because the gap shrinks within the step.
  const float v4 = idm_follow_speed(kP, 15.0f, 20.0f, 30.0f, 0.0f, 1.0f, 4);
  const float v1 = idm_follow_speed(kP, 15.0f, 20.0f, 30.0f, 0.0f, 1.0f, 1);
  EXPECT_LT(v4, 15.0f);
  EXPECT_GE(v4, 0.0f);
  EXPECT_NE(v4, v1);
  // Speed never goes negative even for zero gap.
  EXPECT_EQ(idm_follow_speed(kP, 10.0f, 20.0f, 0.0f, 0.0f, 1.0f, 4), 0.0f);
}

TEST(ModelsIdm, StoppingDistanceHandComputed) {
  // dt 1: speeds 5.5, 1.0 -> 6.5 m.   dt 0.5: speeds 7.75, 5.5, 3.25, 1.0 held 0.5 s -> 8.75 m.
  EXPECT_NEAR(stopping_distance(10.0f, 4.5f, 1.0f), 6.5f, 1e-5f);
  EXPECT_NEAR(stopping_distance(10.0f, 4.5f, 0.5f), 8.75f, 1e-5f);
  EXPECT_EQ(stopping_distance(0.0f, 4.5f, 1.0f), 0.0f);
  EXPECT_EQ(stopping_distance(4.5f, 4.5f, 1.0f), 0.0f);
  // Look-ahead: accelerate one step to 12.6, brake: speeds 8.1, 3.6 -> 12.6 + 11.7 + 2.5 = 26.8.
  EXPECT_NEAR(lookahead_distance(kP, 10.0f, 1.0f), 26.8f, 1e-4f);
}

TEST(ModelsIdm, MaxSpeedWithinBudgetHandComputed) {
  // Budget 13.5 with b = 4.5: speeds 9, 4.5 -> 9.   Budget 20: n = 2, r = (20 - 13.5)/3.
  EXPECT_NEAR(max_speed_within(13.5f, 4.5f, 1.0f), 9.0f, 1e-5f);
  EXPECT_NEAR(max_speed_within(20.0f, 4.5f, 1.0f), 9.0f + 6.5f / 3.0f, 1e-5f);
  // Small budget: one step only, x*dt = budget.
  EXPECT_NEAR(max_speed_within(2.0f, 4.5f, 1.0f), 2.0f, 1e-6f);
  EXPECT_NEAR(max_speed_within(2.0f, 4.5f, 0.5f), 3.125f, 1e-5f);  // speeds 3.125, 0.875 held 0.5 s
  EXPECT_EQ(max_speed_within(0.0f, 4.5f, 1.0f), 0.0f);
  EXPECT_EQ(max_speed_within(-3.0f, 4.5f, 1.0f), 0.0f);
  // The returned speed always fits: x*dt + stopping distance <= budget, over budgets up to 1000 m (the float
  // rounding of this check grows with the budget and stays far below the safe speed's kSafeGapEps there).
  for (int i = 0; i < 317; ++i) {
    const float budget = 0.01f * static_cast<float>(i * i);
    for (float dt : {0.5f, 1.0f}) {
      const float x = max_speed_within(budget, 4.5f, dt);
      EXPECT_LE(x * dt + stopping_distance(x, 4.5f, dt), budget + 1e-4f) << budget << " dt " << dt;
      // ... and is the largest such speed within 0.5%.
      const float y = x * 1.005f + 0.01f;
      EXPECT_GT(y * dt + stopping_distance(y, 4.5f, dt), budget) << budget << " dt " << dt;
    }
  }
}

TEST(ModelsIdm, SafeSpeedHandComputed) {
  // Equal decels, leader at 10 m/s, gap 10: room 6.5, budget 16.5 - 0.001 -> 9 + (3 - 0.001)/3.
  EXPECT_NEAR(safe_speed(10.0f, 10.0f, 4.5f, 4.5f, 1.0f), 9.0f + 2.999f / 3.0f, 1e-4f);
  // A leader braking harder than assumed by the follower shrinks the room: with 9 m/s^2 it stops in 1 m.
  EXPECT_NEAR(safe_speed(10.0f, 10.0f, 9.0f, 4.5f, 1.0f), 4.5f + (10.999f - 4.5f) / 2.0f, 1e-4f);
  // Standing leader, zero gap: stand still.
  EXPECT_EQ(safe_speed(0.0f, 0.0f, 9.0f, 4.5f, 1.0f), 0.0f);
  // Huge gap: effectively unlimited.
  EXPECT_GT(safe_speed(1e5f, 0.0f, 9.0f, 4.5f, 1.0f), 500.0f);
  // Stop points are standing leaders.
  EXPECT_EQ(safe_stop_speed(20.0f, 4.5f, 1.0f), safe_speed(20.0f, 0.0f, 9.0f, 4.5f, 1.0f));
  EXPECT_TRUE(can_stop_before(50.0f, 10.0f, 4.5f, 1.0f));
  EXPECT_FALSE(can_stop_before(5.0f, 15.0f, 4.5f, 1.0f));
  EXPECT_TRUE(can_stop_before(0.0f, 0.0f, 4.5f, 1.0f));
}

// The worst case the safe speed plans for, without IDM's help: the follower takes the safe speed, then
// brakes at its decel every step while the leader brakes at its decel. The gap must stay >= 0 at every
// step, also when the follower brakes much harder than the leader (the follower must not pass "through"
// the leader before both stand).
TEST(ModelsIdm, SafeSpeedBrakingPlanNeverOverlapsTheLeader) {
  int cases = 0;
  for (float dt : {0.5f, 1.0f})
    for (float gap : {0.0f, 0.5f, 3.0f, 10.0f, 40.0f, 150.0f})
      for (float vl : {0.0f, 4.0f, 10.0f, 25.0f})
        for (float bl : {1.0f, 4.5f, 9.0f})
          for (float bf : {1.0f, 4.5f, 9.0f}) {
            ++cases;
            float vf = safe_speed(gap, vl, bl, bf, dt);
            float v_lead = fmaxf(0.0f, vl - bl * dt);
            float g = gap + (v_lead - vf) * dt;
            for (int step = 0; step < 200 && (vf > 0.0f || v_lead > 0.0f); ++step) {
              ASSERT_GE(g, 0.0f) << "gap " << gap << " vl " << vl << " bl " << bl << " bf " << bf << " dt "
                                 << dt;
              vf = fmaxf(0.0f, vf - bf * dt);
              v_lead = fmaxf(0.0f, v_lead - bl * dt);
              g += (v_lead - vf) * dt;
            }
            ASSERT_GE(g, 0.0f) << "gap " << gap << " vl " << vl << " bl " << bl << " bf " << bf << " dt "
                               << dt;
          }
  EXPECT_EQ(cases, 432);
}

TEST(ModelsIdm, FollowAndStopSpeedCombineIdmWithSafety) {
  // Far leader: IDM decides; the safety cap is not binding.
  EXPECT_EQ(follow_speed(kP, 10.0f, 20.0f, 200.0f, 10.0f, 9.0f, 1.0f, 4),
            idm_follow_speed(kP, 10.0f, 20.0f, 200.0f, 10.0f, 1.0f, 4));
  // Leader cut in 3 m ahead at 0 m/s while we drive 10 m/s: safety cap is the binding one.
  const float v = follow_speed(kP, 10.0f, 20.0f, 3.0f, 0.0f, 9.0f, 1.0f, 4);
  EXPECT_LE(v, safe_speed(3.0f, 0.0f, 9.0f, kP.decel, 1.0f));
  EXPECT_EQ(stop_speed(kP, 3.0f, 20.0f, 0.005f, 1.0f, 4), 0.0f);
  // Standing 5 m before the line, the vehicle creeps forward but cannot pass it.
  const float creep = stop_speed(kP, 0.0f, 20.0f, 5.0f, 1.0f, 4);
  EXPECT_GT(creep, 0.0f);
  EXPECT_LE(creep * 1.0f, 5.0f);
}

// A standing vehicle behind a standing leader stays standing up to 1 cm beyond its jam distance (the IDM
// alone would creep by micrometres there), and moves up from farther back; the free speed is left alone
// when the IDM is not run.
TEST(ModelsIdm, StandingInAQueueStaysWithinTheStandstillSlack) {
  float free_speed = -1.0f;
  EXPECT_EQ(follow_speed(kP, 0.0f, 14.0f, kP.min_gap + 0.005f, 0.0f, 9.0f, 1.0f, 4, &free_speed), 0.0f);
  EXPECT_EQ(free_speed, -1.0f);
  // Without the rule the same vehicle creeps (the IDM's own result there is positive).
  EXPECT_GT(idm_follow_speed(kP, 0.0f, 14.0f, kP.min_gap + 0.005f, 0.0f, 1.0f, 4), 0.0f);
  // A little farther back, or a leader that moves, or a moving follower: the IDM decides.
  const float farther = follow_speed(kP, 0.0f, 14.0f, kP.min_gap + 0.05f, 0.0f, 9.0f, 1.0f, 4, &free_speed);
  EXPECT_GT(farther, 0.0f);
  EXPECT_EQ(free_speed, idm_free_speed(kP, 0.0f, 14.0f, 1.0f, 4));
  EXPECT_GT(follow_speed(kP, 0.0f, 14.0f, kP.min_gap + 0.005f, 0.5f, 9.0f, 1.0f, 4), 0.0f);
  EXPECT_EQ(follow_speed(kP, 0.2f, 14.0f, kP.min_gap + 0.005f, 0.0f, 9.0f, 1.0f, 4),
            lp_fminf(idm_follow_speed(kP, 0.2f, 14.0f, kP.min_gap + 0.005f, 0.0f, 1.0f, 4),
                     safe_speed(kP.min_gap + 0.005f, 0.0f, 9.0f, kP.decel, 1.0f)));
}

// The IDM integrated one sub-step at a time, written out longhand with idm_pow_delta and the reciprocals of
// v0 and 2*sqrt(ab) taken once: what the fast paths (exponent picked once per call, free-road chain
// interleaved with the leader's) must reproduce bit for bit.
float reference_free_speed(const IdmParams& p, float speed, float v0, float dt, int n) {
  if (speed == v0 && v0 >= kIdmEps) return v0;
  const float h = dt / static_cast<float>(n);
  const float inv_v0 = 1.0f / lp_fmaxf(v0, kIdmEps);
  float v = speed;
  for (int i = 0; i < n; ++i)
    v = lp_fmaxf(0.0f, v + lp_fmaxf(p.accel * h * (1.0f - idm_pow_delta(v * inv_v0, p.delta)), -p.decel * h));
  return speed <= v0 ? lp_fminf(v, v0) : v;
}

float reference_interaction_speed(const IdmParams& p, float speed, float v0, float gap, float vl, float jam,
                                  float dt, int n) {
  const float h = dt / static_cast<float>(n);
  const float inv_v0 = 1.0f / lp_fmaxf(v0, kIdmEps);
  const float inv_c = 1.0f / (2.0f * sqrtf(p.accel * p.decel));
  float v = speed, s = gap;
  for (int i = 0; i < n; ++i) {
    const float s_star = jam + lp_fmaxf(0.0f, v * p.tau + v * (v - vl) * inv_c);
    const float q = s_star * (1.0f / lp_fmaxf(s, kIdmEps));
    v = lp_fmaxf(0.0f, v + p.accel * h * ((1.0f - idm_pow_delta(v * inv_v0, p.delta)) - q * q));
    s -= lp_fmaxf(0.0f, (v - vl) * h);
  }
  return v;
}

// The same integration with the textbook divisions, in double precision: the reciprocals may only move the
// last bits.
double division_form_interaction_speed(const IdmParams& p, double speed, double v0, double gap, double vl,
                                       double jam, double dt, int n) {
  const double h = dt / n;
  double v = speed, s = gap;
  for (int i = 0; i < n; ++i) {
    const double s_star =
        jam + std::max(0.0, v * p.tau + v * (v - vl) / (2.0 * std::sqrt(p.accel * p.decel)));
    const double q = s_star / std::max(s, static_cast<double>(kIdmEps));
    v = std::max(
        0.0,
        v + p.accel * (1.0 - std::pow(v / std::max(v0, static_cast<double>(kIdmEps)), p.delta) - q * q) * h);
    s -= std::max(0.0, (v - vl) * h);
  }
  return v;
}

uint32_t bits(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

TEST(ModelsIdm, FreeSpeedComputedAlongsideALeaderIsBitIdentical) {
  int cases = 0;
  for (float delta : {4.0f, 2.0f, 3.5f})
    for (int n : {1, 2, 4})
      for (uint64_t k = 0; k < 400; ++k) {
        IdmParams p = kP;
        p.delta = delta;
        const float v0 = draw(11, 1, k, 0.0f, 40.0f);
        // Every fourth case cruises at exactly the desired speed (the free road's shortcut).
        const float speed = k % 4 == 0 ? v0 : draw(11, 2, k, 0.0f, 45.0f);
        const float gap = draw(11, 3, k, 0.0f, 120.0f);
        const float vl = k % 5 == 0 ? 0.0f : draw(11, 4, k, 0.0f, 40.0f);
        const float free_ref = reference_free_speed(p, speed, v0, 1.0f, n);
        ASSERT_EQ(bits(idm_free_speed(p, speed, v0, 1.0f, n)), bits(free_ref)) << k;
        ASSERT_EQ(bits(idm_follow_speed(p, speed, v0, gap, vl, 1.0f, n)),
                  bits(reference_interaction_speed(p, speed, v0, gap, vl, p.min_gap, 1.0f, n)))
            << k;
        float free_follow = -1.0f, free_stop = -1.0f;
        ASSERT_EQ(bits(follow_speed(p, speed, v0, gap, vl, 9.0f, 1.0f, n, &free_follow)),
                  bits(follow_speed(p, speed, v0, gap, vl, 9.0f, 1.0f, n)))
            << k;
        ASSERT_EQ(bits(free_follow), bits(free_ref)) << k;
        ASSERT_EQ(bits(stop_speed(p, speed, v0, gap, 1.0f, n, &free_stop)),
                  bits(stop_speed(p, speed, v0, gap, 1.0f, n)))
            << k;
        ASSERT_EQ(bits(free_stop), bits(free_ref)) << k;
        ++cases;
      }
  EXPECT_EQ(cases, 3600);
}

// The reciprocal form is the IDM: against a double-precision integration with divisions, a sub-step loop
// differs by float rounding only.
TEST(ModelsIdm, ReciprocalFormMatchesTheDivisionFormToRounding) {
  int cases = 0;
  for (int n : {1, 2, 4})
    for (uint64_t k = 0; k < 500; ++k) {
      const float v0 = draw(12, 1, k, 1.0f, 40.0f);
      const float speed = draw(12, 2, k, 0.0f, 45.0f);
      const float gap = draw(12, 3, k, 0.5f, 120.0f);
      const float vl = k % 5 == 0 ? 0.0f : draw(12, 4, k, 0.0f, 40.0f);
      const double ref = division_form_interaction_speed(kP, speed, v0, gap, vl, kP.min_gap, 1.0, n);
      // Relative to the speed reached (at least 1 m/s): rounding error scales with the values computed.
      const double scale = std::max(1.0, std::fabs(ref));
      const float got = idm_follow_speed(kP, speed, v0, gap, vl, 1.0f, n);
      if (ref <= 0.0) {
        EXPECT_LE(got, 1e-3f) << k;
      } else {
        EXPECT_NEAR(got, ref, 1e-4 * scale) << k << " n " << n;
      }
      ++cases;
    }
  EXPECT_EQ(cases, 1500);
}

TEST(ModelsIdm, FinalizeSpeedClampsToPhysicalLimits) {
  EXPECT_FLOAT_EQ(finalize_speed(kP, 10.0f, 50.0f, 1.0f), 12.6f);
  EXPECT_FLOAT_EQ(finalize_speed(kP, 10.0f, 0.0f, 1.0f), 1.0f);  // emergency decel 9
  EXPECT_FLOAT_EQ(finalize_speed(kP, 10.0f, 0.0f, 0.5f), 5.5f);
  EXPECT_FLOAT_EQ(finalize_speed(kP, 5.0f, 0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(finalize_speed(kP, 10.0f, 8.0f, 1.0f), 8.0f);
}

// Property: a follower that starts at or below its safe speed and then uses
// finalize(min(free, follow_speed)) never collides with a leader that accelerates or brakes randomly, up to
// its emergency deceleration (with bursts of full emergency braking), over 1000 steps.
TEST(ModelsIdm, PropertySafeFollowerNeverCollides) {
  const uint64_t seed = 20240601;
  int pairs = 0;
  for (uint64_t pair = 0; pair < 120; ++pair) {
    const float dt = (pair % 2 == 0) ? 1.0f : 0.5f;
    IdmParams f = kP;
    f.decel = draw(seed, pair, 1, 2.0f, 6.0f);
    f.emergency_decel = draw(seed, pair, 2, f.decel, 10.0f);
    f.accel = draw(seed, pair, 3, 1.0f, 4.0f);
    f.tau = draw(seed, pair, 4, 0.5f, 2.0f);
    const float leader_emergency = draw(seed, pair, 5, 1.0f, 10.0f);
    const float leader_accel = draw(seed, pair, 6, 1.0f, 4.0f);
    const float v0 = draw(seed, pair, 7, 5.0f, 40.0f);
    float gap = draw(seed, pair, 8, 0.0f, 80.0f);
    float vl = draw(seed, pair, 9, 0.0f, 35.0f);
    float vf = fminf(draw(seed, pair, 10, 0.0f, 40.0f), safe_speed(gap, vl, leader_emergency, f.decel, dt));
    ++pairs;
    for (uint64_t step = 0; step < 1000; ++step) {
      // Leader: random acceleration in [-emergency, accel]; one step in ten is a full emergency stop.
      const uint64_t k = 100 + step;
      const bool emergency = rng_uniform(seed ^ 0xABCull, pair, k) < 0.1f;
      const float a_l =
          emergency ? -leader_emergency : draw(seed ^ 0xDEFull, pair, k, -leader_emergency, leader_accel);
      const float vl_next = fminf(fmaxf(vl + a_l * dt, 0.0f), 35.0f);
      const float cand =
          fminf(idm_free_speed(f, vf, v0, dt, 4),
                follow_speed(f, vf, v0, gap, vl, leader_emergency, dt, idm_default_substeps(dt)));
      const float vf_next = finalize_speed(f, vf, cand, dt);
      gap += (vl_next - vf_next) * dt;
      ASSERT_GE(gap, 0.0f) << "pair " << pair << " step " << step << " dt " << dt;
      vl = vl_next;
      vf = vf_next;
    }
  }
  EXPECT_EQ(pairs, 120);
}

// Property: from any speed, a vehicle that can physically stop before a line (braking at emergency decel)
// does stop before it, using finalize(stop_speed), and ends up standing close to the line.
TEST(ModelsIdm, PropertyStopsBeforeLineWhenPhysicallyPossible) {
  const uint64_t seed = 77;
  int tested = 0;
  for (uint64_t i = 0; i < 400; ++i) {
    const float dt = (i % 2 == 0) ? 1.0f : 0.5f;
    float v = draw(seed, i, 1, 0.0f, 40.0f);
    float gap = draw(seed, i, 2, 0.0f, 250.0f);
    const float v0 = fmaxf(v, draw(seed, i, 3, 5.0f, 40.0f));
    if (!can_stop_before(gap, v, kP.emergency_decel, dt)) continue;
    ++tested;
    bool stopped = false;
    for (int step = 0; step < 1000 && !(stopped && gap < 0.5f); ++step) {
      const float cand = fminf(idm_free_speed(kP, v, v0, dt, 4), stop_speed(kP, v, v0, gap, dt, 4));
      v = finalize_speed(kP, v, cand, dt);
      gap -= v * dt;
      ASSERT_GE(gap, 0.0f) << "case " << i << " step " << step;
      stopped = stopped || v == 0.0f;
    }
    EXPECT_TRUE(stopped) << "case " << i;
    EXPECT_LT(gap, 0.5f) << "case " << i << " stands too far from the line";
  }
  EXPECT_GT(tested, 150);
}

}  // namespace
}  // namespace lpsim

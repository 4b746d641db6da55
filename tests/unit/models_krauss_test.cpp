// Krauss (SUMO's default car-following model, Euler update): hand-computed values of its safe speeds,
// dawdling and final speed, the model dispatch, and a braking leader followed without collision.
#include <gtest/gtest.h>

#include "kernels/car_following.hpp"
#include "kernels/krauss.hpp"

namespace lpsim {
namespace {

IdmParams krauss_params(float sigma = 0.5f) {
  IdmParams p = idm_default_params();  // SUMO's passenger car: accel 2.6, decel 4.5, emergency 9, tau 1
  p.sigma = sigma;
  p.model = kCarFollowKrauss;
  return p;
}

TEST(ModelsKrauss, SafeStopSpeedBrakesEvenlyToTheGap) {
  // Headway = step (stop points): braking 4.5 per step from x covers x + (x - 4.5) + ... within the gap.
  // gap 20.001 (20 after SUMO's 0.001): n = 2 full braking steps, then r = (20 - 13.5) / 3.
  EXPECT_NEAR(krauss_safe_stop_speed(20.001f, 4.5f, 1.0f, 1.0f), 9.0f + 6.5f / 3.0f, 1e-4f);
  // Headway 1.5 s: h(2) = 2.25*2*1 + 2*4.5*1.5 = 18, r = (20 - 18) / (2 + 1.5).
  EXPECT_NEAR(krauss_safe_stop_speed(20.001f, 4.5f, 1.5f, 1.0f), 9.0f + 2.0f / 3.5f, 1e-4f);
  // Half-second steps: b = 2.25 per step; h(n) = 0.5 n (n-1) 2.25 0.5 + n 2.25 0.5 = 0.5625 n (n+1):
  // g = 10 gives n = 3 (6.75 <= 10 < 11.25), r = (10 - 6.75) / 2.
  EXPECT_NEAR(krauss_safe_stop_speed(10.001f, 4.5f, 0.5f, 0.5f), 6.75f + 3.25f / 2.0f, 1e-4f);
  EXPECT_EQ(krauss_safe_stop_speed(0.001f, 4.5f, 1.0f, 1.0f), 0.0f);
  EXPECT_EQ(krauss_safe_stop_speed(-3.0f, 4.5f, 1.0f, 1.0f), 0.0f);
  // Exactly at a boundary of n (h(3) = 27): the closed form's rounding is settled, r = 0.
  EXPECT_NEAR(krauss_safe_stop_speed(27.001f, 4.5f, 1.0f, 1.0f), 13.5f, 1e-3f);
}

TEST(ModelsKrauss, SafeStopSpeedNeverOvershootsTheGap) {
  // Driving at the safe speed and then braking by decel per step stays within the gap, for any gap.
  for (float gap = 0.01f; gap < 300.0f; gap *= 1.07f) {
    for (float headway : {0.5f, 1.0f, 2.0f}) {
      const float dt = 1.0f;
      const float x = krauss_safe_stop_speed(gap, 4.5f, headway, dt);
      // Distance: x*headway for the first speed (held through the headway), then the Euler braking steps.
      float travelled = x * headway;
      for (float v = x - 4.5f * dt; v > 0.0f; v -= 4.5f * dt) travelled += v * dt;
      EXPECT_LE(travelled, gap + 1e-3f) << "gap " << gap << " headway " << headway;
      EXPECT_GE(x, 0.0f);
    }
  }
}

TEST(ModelsKrauss, FollowSpeedKeepsMinGapAndLeaderBrakingRoom) {
  const IdmParams p = krauss_params();
  // Leader at 10 m/s 30 m ahead (27.5 behind minGap); its Euler braking room at 4.5: 10 + 5.5 + 1 = 6.5 m.
  // g = 27.5 + 6.5 - 0.001: n = 3 (27 <= g < 45), r = (33.999 - 27) / 4.
  EXPECT_NEAR(krauss_safe_follow_speed(p, 10.0f, 27.5f, 10.0f, 4.5f, 1.0f), 13.5f + 6.999f / 4.0f, 1e-4f);
  // The next speed is that, capped by accelerating at 2.6.
  EXPECT_FLOAT_EQ(krauss_follow_speed(p, 10.0f, 30.0f, 10.0f, 4.5f, 1.0f), 12.6f);
  // Standing at minGap behind a standing leader: stays.
  EXPECT_EQ(krauss_follow_speed(p, 0.0f, 2.5f, 0.0f, 4.5f, 1.0f), 0.0f);
  // Inside minGap: brakes at the emergency decel.
  EXPECT_FLOAT_EQ(krauss_follow_speed(p, 12.0f, 1.0f, 0.0f, 4.5f, 1.0f), 3.0f);
}

TEST(ModelsKrauss, SafeFollowSpeedTakesTheBrakingTheSituationNeeds) {
  // tau 3 s, 20 m/s, standing leader 40 m ahead of minGap: the stop speed asks for 9.3 m/s^2 of braking,
  // more than decel. SUMO recomputes: the needed braking 0.5*20^2/40 = 5 (> the leader's 4.5, so the second
  // case, same value here), times 1.2 = 6, within [decel, asked]: 20 - 6 = 14.
  IdmParams p = krauss_params();
  p.tau = 3.0f;
  EXPECT_NEAR(krauss_safe_follow_speed(p, 20.0f, 40.0f, 0.0f, 4.5f, 1.0f), 14.0f, 1e-4f);
  // Without an emergency decel above decel, no recomputation: the stop speed's own value.
  p.emergency_decel = p.decel;
  EXPECT_NEAR(krauss_safe_follow_speed(p, 20.0f, 40.0f, 0.0f, 4.5f, 1.0f), 9.0f + 8.499f / 5.0f, 1e-4f);
  // Needed braking: b1 = v^2 / 2 / (gap + leader's braking distance) when at most the leader's decel.
  EXPECT_NEAR(krauss_needed_decel(50.0f, 10.0f, 9.0f, 4.5f, 9.0f), 50.0f / (50.0f + 81.0f / 9.0f), 1e-5f);
  EXPECT_NEAR(krauss_needed_decel(2.0f, 15.0f, 10.0f, 4.5f, 9.0f), 0.5f * 125.0f / 2.0f, 1e-4f);
  EXPECT_EQ(krauss_needed_decel(0.0f, 15.0f, 10.0f, 4.5f, 9.0f), 9.0f);
}

TEST(ModelsKrauss, StopAndFreeSpeeds) {
  const IdmParams p = krauss_params();
  // Standing 20 m before a line: accelerates by 2.6 (the stop speed, 11.17, is higher).
  EXPECT_FLOAT_EQ(krauss_stop_speed(p, 0.0f, 20.001f, 1.0f), 2.6f);
  EXPECT_NEAR(krauss_stop_speed(p, 12.0f, 20.001f, 1.0f), 9.0f + 6.5f / 3.0f, 1e-4f);
  EXPECT_FLOAT_EQ(krauss_free_speed(p, 10.0f, 13.89f, 1.0f), 12.6f);
  EXPECT_FLOAT_EQ(krauss_free_speed(p, 12.0f, 13.89f, 1.0f), 13.89f);
  EXPECT_FLOAT_EQ(krauss_free_speed(p, 15.0f, 13.89f, 1.0f), 13.89f);  // above the desired speed: drops to it
}

TEST(ModelsKrauss, DawdleScalesWithAccelOrSpeedBelowIt) {
  EXPECT_FLOAT_EQ(krauss_dawdle(10.0f, 2.6f, 0.5f, 0.5f, 1.0f), 10.0f - 0.5f * 2.6f * 0.5f);
  EXPECT_FLOAT_EQ(krauss_dawdle(2.0f, 2.6f, 0.5f, 0.5f, 1.0f), 2.0f - 0.5f * 2.0f * 0.5f);
  EXPECT_FLOAT_EQ(krauss_dawdle(10.0f, 2.6f, 0.5f, 0.5f, 0.5f), 10.0f - 0.5f * 2.6f * 0.5f * 0.5f);
  EXPECT_FLOAT_EQ(krauss_dawdle(10.0f, 2.6f, 0.0f, 0.9f, 1.0f), 10.0f);
  EXPECT_EQ(krauss_dawdle(0.0f, 2.6f, 1.0f, 0.99f, 1.0f), 0.0f);
}

TEST(ModelsKrauss, FinalSpeedDawdlesButNeverBelowComfortableBraking) {
  const IdmParams p = krauss_params(0.5f);
  // Accelerating freely from 10: 12.6, dawdled by 0.5*2.6*0.5.
  EXPECT_FLOAT_EQ(krauss_finalize_speed(p, 10.0f, 12.6f, 0.5f, 1.0f), 12.6f - 0.65f);
  // A candidate above accelerating at accel is capped first.
  EXPECT_FLOAT_EQ(krauss_finalize_speed(p, 10.0f, 30.0f, 0.0f, 1.0f), 12.6f);
  // Braking to 8 from 10: dawdling may go down to 8 - 1.287, still above 10 - 4.5.
  EXPECT_NEAR(krauss_finalize_speed(p, 10.0f, 8.0f, 0.99f, 1.0f), 8.0f - 0.5f * 2.6f * 0.99f, 1e-5f);
  // Braking to 3 from 10 (harder than decel): no dawdling below the safe speed.
  EXPECT_FLOAT_EQ(krauss_finalize_speed(p, 10.0f, 3.0f, 0.99f, 1.0f), 3.0f);
  // Braking from 10 to 6 dawdles at most down to 10 - 4.5.
  EXPECT_FLOAT_EQ(krauss_finalize_speed(krauss_params(1.0f), 10.0f, 6.0f, 0.99f, 1.0f), 5.5f);
  // Never below the emergency decel.
  EXPECT_FLOAT_EQ(krauss_finalize_speed(p, 20.0f, 0.0f, 0.5f, 1.0f), 11.0f);
}

TEST(ModelsKrauss, DispatchFollowsTheTypesModel) {
  const IdmParams idm = idm_default_params();
  const IdmParams krauss = krauss_params(0.0f);
  EXPECT_EQ(cf_free_speed(idm, 10.0f, 13.89f, 1.0f, 4), idm_free_speed(idm, 10.0f, 13.89f, 1.0f, 4));
  EXPECT_EQ(cf_free_speed(krauss, 10.0f, 13.89f, 1.0f, 4), 12.6f);
  EXPECT_EQ(cf_follow_speed(idm, 10.0f, 13.89f, 30.0f, 10.0f, 9.0f, 1.0f, 4),
            follow_speed(idm, 10.0f, 13.89f, 30.0f, 10.0f, 9.0f, 1.0f, 4));
  EXPECT_EQ(cf_follow_speed(krauss, 10.0f, 13.89f, 30.0f, 10.0f, 9.0f, 1.0f, 4),
            krauss_follow_speed(krauss, 10.0f, 30.0f, 10.0f, 4.5f, 1.0f));
  EXPECT_EQ(cf_stop_speed(idm, 10.0f, 13.89f, 20.0f, 1.0f, 4),
            stop_speed(idm, 10.0f, 13.89f, 20.0f, 1.0f, 4));
  EXPECT_EQ(cf_stop_speed(krauss, 10.0f, 13.89f, 20.0f, 1.0f, 4),
            krauss_stop_speed(krauss, 10.0f, 20.0f, 1.0f));
  EXPECT_EQ(cf_finalize_speed(idm, 10.0f, 11.0f, 1.0f, 1, 2, 3), finalize_speed(idm, 10.0f, 11.0f, 1.0f));
  EXPECT_EQ(cf_accel(idm, 10.0f, 13.89f, 30.0f, 10.0f, 1.0f), idm_accel(idm, 10.0f, 13.89f, 30.0f, 10.0f));
  EXPECT_FLOAT_EQ(cf_accel(krauss, 10.0f, 13.89f, 30.0f, 10.0f, 1.0f), 2.6f);
  // The dawdle draw: the same for the same (seed, vehicle, step), different across steps.
  const IdmParams dawdler = krauss_params(1.0f);
  const float a = cf_finalize_speed(dawdler, 10.0f, 12.6f, 1.0f, 7, 3, 100);
  EXPECT_EQ(a, cf_finalize_speed(dawdler, 10.0f, 12.6f, 1.0f, 7, 3, 100));
  EXPECT_LE(a, 12.6f);
  EXPECT_GT(a, 12.6f - 2.6f);
  bool differs = false;
  for (uint32_t step = 101; step < 110; ++step)
    differs |= cf_finalize_speed(dawdler, 10.0f, 12.6f, 1.0f, 7, 3, step) != a;
  EXPECT_TRUE(differs);
}

TEST(ModelsKrauss, FollowerOfABrakingLeaderStopsBehindItWithoutDawdling) {
  // Euler update, both at 15 m/s with 20 m between bumpers; the leader brakes at 4.5 to a stop at t = 4.
  // The follower (sigma 0) must never come closer than 0 and must end standing at about minGap.
  const IdmParams p = krauss_params(0.0f);
  float xl = 20.0f, vl = 15.0f, xf = 0.0f, vf = 15.0f;
  float closest = 1e9f;
  for (int t = 0; t < 30; ++t) {
    const float gap = xl - xf;
    const float cand =
        lp_fminf(krauss_free_speed(p, vf, 30.0f, 1.0f), krauss_follow_speed(p, vf, gap, vl, 4.5f, 1.0f));
    vf = krauss_finalize_speed(p, vf, cand, 0.0f, 1.0f);
    vl = lp_fmaxf(0.0f, vl - 4.5f);
    xl += vl;
    xf += vf;
    closest = lp_fminf(closest, xl - xf);
  }
  EXPECT_GT(closest, 0.0f);
  EXPECT_EQ(vf, 0.0f);
  EXPECT_NEAR(xl - xf, p.min_gap, 0.01f);
}

}  // namespace
}  // namespace lpsim

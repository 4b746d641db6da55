// Lane change: mandatory zone/urgency, gap acceptance (never unsafe), MOBIL incentive, RNG-keyed attempts.
#include <gtest/gtest.h>

#include "kernels/idm.hpp"
#include "kernels/lane_change.hpp"
#include "kernels/rng.hpp"

namespace lpsim {
namespace {

const IdmParams kP = idm_default_params();
const LaneChangeParams kLc = lane_change_default_params();

LcNeighbor neighbor(float gap, float speed, float v0 = 30.0f) { return LcNeighbor{true, gap, speed, v0, kP}; }

TEST(ModelsLaneChange, MandatoryZoneGrowsWithLanesToCrossAndSpeed) {
  EXPECT_FLOAT_EQ(mandatory_lc_zone(0, 10.0f, kLc), 0.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_zone(1, 10.0f, kLc), 50.0f);  // max(50, 10*4)
  EXPECT_FLOAT_EQ(mandatory_lc_zone(2, 10.0f, kLc), 100.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_zone(2, 20.0f, kLc), 160.0f);  // 2 * max(50, 20*4)
  EXPECT_FLOAT_EQ(mandatory_lc_zone(3, 0.0f, kLc), 150.0f);
}

TEST(ModelsLaneChange, MandatoryUrgencyRisesLinearlyToTheLaneEnd) {
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(150.0f, 2, 10.0f, kLc), 0.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(100.0f, 2, 10.0f, kLc), 0.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(50.0f, 2, 10.0f, kLc), 0.5f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(25.0f, 2, 10.0f, kLc), 0.75f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(0.0f, 2, 10.0f, kLc), 1.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(-3.0f, 1, 10.0f, kLc), 1.0f);
  EXPECT_FLOAT_EQ(mandatory_lc_urgency(10.0f, 0, 10.0f, kLc), 0.0f);  // already on a good lane
  // The same distance is more urgent with more lanes to cross.
  EXPECT_LT(mandatory_lc_urgency(60.0f, 2, 10.0f, kLc), mandatory_lc_urgency(60.0f, 3, 10.0f, kLc));
}

TEST(ModelsLaneChange, EmptyTargetLaneIsAccepted) {
  EXPECT_TRUE(lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), lc_no_neighbor(), 0.0f, kLc, 1.0f));
  EXPECT_TRUE(lc_gaps_acceptable(kP, 0.0f, 30.0f, lc_no_neighbor(), lc_no_neighbor(), 1.0f, kLc, 0.5f));
}

TEST(ModelsLaneChange, OverlapOrZeroGapIsRejectedEvenWhenUrgent) {
  EXPECT_FALSE(lc_gaps_acceptable(kP, 0.0f, 30.0f, neighbor(0.0f, 0.0f), lc_no_neighbor(), 1.0f, kLc, 1.0f));
  EXPECT_FALSE(lc_gaps_acceptable(kP, 0.0f, 30.0f, lc_no_neighbor(), neighbor(-1.0f, 0.0f), 1.0f, kLc, 1.0f));
}

TEST(ModelsLaneChange, LargeGapsAtEqualSpeedAreAccepted) {
  EXPECT_TRUE(lc_gaps_acceptable(kP, 15.0f, 30.0f, neighbor(100.0f, 15.0f), neighbor(100.0f, 15.0f), 0.0f,
                                 kLc, 1.0f));
}

TEST(ModelsLaneChange, FastClosingLagIsRejectedEvenWhenUrgent) {
  // Lag at 20 m/s, 3 m behind a changer doing 10 m/s: its safe speed is 3.999 < 20 - 4.5.
  EXPECT_FALSE(lc_lag_gap_safe(kP, 10.0f, neighbor(3.0f, 20.0f), 1.0f));
  EXPECT_FALSE(
      lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), neighbor(3.0f, 20.0f), 1.0f, kLc, 1.0f));
  // The same lag far behind is fine.
  EXPECT_TRUE(lc_lag_gap_safe(kP, 10.0f, neighbor(60.0f, 20.0f), 1.0f));
}

TEST(ModelsLaneChange, ChangerTooFastForTargetLeaderIsRejected) {
  // Changer at 25 m/s, target leader standing 10 m ahead: cannot stay safe braking comfortably.
  EXPECT_FALSE(lc_lead_gap_safe(kP, 25.0f, neighbor(10.0f, 0.0f), 1.0f));
  EXPECT_FALSE(
      lc_gaps_acceptable(kP, 25.0f, 30.0f, neighbor(10.0f, 0.0f), lc_no_neighbor(), 1.0f, kLc, 1.0f));
  EXPECT_TRUE(lc_lead_gap_safe(kP, 5.0f, neighbor(10.0f, 0.0f), 1.0f));
}

TEST(ModelsLaneChange, UrgentChangeAcceptsSmallerLagGap) {
  // Changer and lag at 10 m/s, lag v0 30: lag IDM accel behind the changer at gap g is
  // 2.6 * (1 - (1/3)^4 - (12.5/g)^2). At g = 8.5 this is about -3.06: below -b_safe (2) but above -decel
  // (4.5).
  const LcNeighbor lag = neighbor(8.5f, 10.0f);
  const float a_lag = idm_accel(kP, 10.0f, 30.0f, 8.5f, 10.0f);
  EXPECT_NEAR(a_lag, 2.6f * (1.0f - 1.0f / 81.0f - (12.5f / 8.5f) * (12.5f / 8.5f)), 1e-4f);
  EXPECT_TRUE(lc_lag_gap_safe(kP, 10.0f, lag, 1.0f));
  EXPECT_FALSE(lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), lag, 0.0f, kLc, 1.0f));
  EXPECT_FALSE(lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), lag, 0.3f, kLc, 1.0f));
  EXPECT_TRUE(lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), lag, 1.0f, kLc, 1.0f));
  // A gap of 7 m needs about -5.6 m/s^2 from the lag: rejected at any urgency.
  EXPECT_FALSE(
      lc_gaps_acceptable(kP, 10.0f, 30.0f, lc_no_neighbor(), neighbor(7.0f, 10.0f), 1.0f, kLc, 1.0f));
}

TEST(ModelsLaneChange, MobilIncentiveHandComputed) {
  EXPECT_NEAR(mobil_incentive(0.0f, 1.0f, 0.0f, -0.5f, 0.0f, 0.2f, 0.5f), 0.85f, 1e-6f);
  EXPECT_NEAR(mobil_incentive(0.0f, 1.0f, 0.0f, -0.5f, 0.0f, 0.2f, 0.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(mobil_incentive(1.0f, 1.0f, 0.0f, -3.0f, 0.0f, 0.0f, 1.0f), -3.0f, 1e-6f);
}

TEST(ModelsLaneChange, DiscretionaryChangeToPassASlowLeader) {
  const LcNeighbor slow_lead = neighbor(20.0f, 5.0f);
  // Free target lane: the gain is large.
  EXPECT_TRUE(discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, slow_lead, lc_no_neighbor(),
                                          lc_no_neighbor(), lc_no_neighbor(), 0.0f, kLc, 1.0f));
  // Target lane blocked by an even slower, closer leader: no gain.
  EXPECT_FALSE(discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, slow_lead, lc_no_neighbor(),
                                           neighbor(15.0f, 2.0f), lc_no_neighbor(), 0.0f, kLc, 1.0f));
  // Free road ahead on both lanes: nothing to gain, threshold not reached.
  EXPECT_FALSE(discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, lc_no_neighbor(), lc_no_neighbor(),
                                           lc_no_neighbor(), lc_no_neighbor(), 0.0f, kLc, 1.0f));
  // A huge bias (e.g. keep-right against this direction) suppresses the change.
  EXPECT_FALSE(discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, slow_lead, lc_no_neighbor(),
                                           lc_no_neighbor(), lc_no_neighbor(), 100.0f, kLc, 1.0f));
}

TEST(ModelsLaneChange, PolitenessWeighsTheNewFollowersLoss) {
  // Small own gain (leader ahead is a bit slower) against a new follower that would have to brake.
  const LcNeighbor cur_lead = neighbor(40.0f, 12.0f);
  const LcNeighbor target_lag = neighbor(18.0f, 15.0f);
  LaneChangeParams selfish = kLc;
  selfish.politeness = 0.0f;
  LaneChangeParams polite = kLc;
  polite.politeness = 1.0f;
  const bool selfish_changes = discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, cur_lead, lc_no_neighbor(),
                                                           lc_no_neighbor(), target_lag, 0.0f, selfish, 1.0f);
  const bool polite_changes = discretionary_change_wanted(kP, 15.0f, 30.0f, 5.0f, cur_lead, lc_no_neighbor(),
                                                          lc_no_neighbor(), target_lag, 0.0f, polite, 1.0f);
  EXPECT_TRUE(selfish_changes);
  EXPECT_FALSE(polite_changes);
}

TEST(ModelsLaneChange, AttemptDrawIsKeyedAndHasTheRequestedFrequency) {
  EXPECT_EQ(lc_attempt_allowed(1, 2, 3, 0.5f), lc_attempt_allowed(1, 2, 3, 0.5f));
  int allowed = 0;
  for (uint64_t step = 0; step < 20000; ++step) {
    EXPECT_FALSE(lc_attempt_allowed(42, 7, step, 0.0f));
    EXPECT_TRUE(lc_attempt_allowed(42, 7, step, 1.0f));
    allowed += lc_attempt_allowed(42, 7, step, 0.3f) ? 1 : 0;
  }
  EXPECT_NEAR(allowed / 20000.0, 0.3, 0.02);
  // Different vehicles draw differently (not all in lock-step).
  int differ = 0;
  for (uint64_t v = 0; v < 100; ++v)
    differ += lc_attempt_allowed(42, v, 5, 0.5f) != lc_attempt_allowed(42, v + 1, 5, 0.5f);
  EXPECT_GT(differ, 20);
}

// Property: whenever a change is accepted (any urgency), the new follower behind the changer and the changer
// behind its new leader, all using finalize(min(free, follow_speed)), never collide over 300 steps while the
// changer and the new leader brake randomly up to their emergency decel.
TEST(ModelsLaneChange, PropertyAcceptedChangesNeverCauseCollisions) {
  const uint64_t seed = 99;
  int accepted = 0;
  for (uint64_t c = 0; c < 3000 && accepted < 150; ++c) {
    const float dt = (c % 2 == 0) ? 1.0f : 0.5f;
    auto u = [&](uint64_t k, float lo, float hi) { return lo + (hi - lo) * rng_uniform(seed, c, k); };
    const float vs = u(1, 0.0f, 30.0f);
    const LcNeighbor lead = neighbor(u(2, 0.0f, 40.0f), u(3, 0.0f, 30.0f));
    const LcNeighbor lag = neighbor(u(4, 0.0f, 40.0f), u(5, 0.0f, 30.0f));
    const float urgency = u(6, 0.0f, 1.0f);
    if (!lc_gaps_acceptable(kP, vs, 30.0f, lead, lag, urgency, kLc, dt)) continue;
    ++accepted;
    float v_lead = lead.speed, v_self = vs, v_lag = lag.speed;
    float gap_front = lead.gap, gap_back = lag.gap;
    for (uint64_t step = 0; step < 300; ++step) {
      const uint64_t k = 10 + step;
      const float a_lead = u(k * 2, -kP.emergency_decel, kP.accel);
      const float v_lead_next = fminf(fmaxf(v_lead + a_lead * dt, 0.0f), 30.0f);
      const float self_cand =
          fminf(idm_free_speed(kP, v_self, 30.0f, dt, 4),
                follow_speed(kP, v_self, 30.0f, gap_front, v_lead, kP.emergency_decel, dt, 4));
      // The changer may also brake hard on its own (emergency braking is allowed for it).
      const float self_brake = rng_uniform(seed ^ 0x55ull, c, k) < 0.1f ? 0.0f : self_cand;
      const float v_self_next = finalize_speed(kP, v_self, self_brake, dt);
      const float lag_cand =
          fminf(idm_free_speed(kP, v_lag, 30.0f, dt, 4),
                follow_speed(kP, v_lag, 30.0f, gap_back, v_self, kP.emergency_decel, dt, 4));
      const float v_lag_next = finalize_speed(kP, v_lag, lag_cand, dt);
      gap_front += (v_lead_next - v_self_next) * dt;
      gap_back += (v_self_next - v_lag_next) * dt;
      ASSERT_GE(gap_front, 0.0f) << "case " << c << " step " << step;
      ASSERT_GE(gap_back, 0.0f) << "case " << c << " step " << step;
      v_lead = v_lead_next;
      v_self = v_self_next;
      v_lag = v_lag_next;
    }
  }
  EXPECT_GE(accepted, 100);
}

}  // namespace
}  // namespace lpsim

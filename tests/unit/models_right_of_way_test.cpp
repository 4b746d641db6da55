// Right of way: link rules, arrival times, yield time windows, right-before-left and all-way stops.
#include <gtest/gtest.h>

#include "kernels/right_of_way.hpp"

namespace lpsim {
namespace {

TEST(ModelsRightOfWay, LinkRulesFromStateCharacters) {
  for (char c : {'M', 'G', 'O', 'y', 'Y'}) EXPECT_EQ(link_rule(c), LinkRule::Priority) << c;
  for (char c : {'m', 'g', 'o', 'Z'}) EXPECT_EQ(link_rule(c), LinkRule::Yield) << c;
  EXPECT_EQ(link_rule('s'), LinkRule::StopThenYield);
  EXPECT_EQ(link_rule('='), LinkRule::RightBeforeLeft);
  EXPECT_EQ(link_rule('w'), LinkRule::AllwayStop);
  for (char c : {'r', 'u', '?', '\0'}) EXPECT_EQ(link_rule(c), LinkRule::Closed) << c;
}

TEST(ModelsRightOfWay, EarliestArrivalTimeHandComputed) {
  EXPECT_FLOAT_EQ(earliest_arrival_time(100.0f, 10.0f, 0.0f, 10.0f), 10.0f);
  EXPECT_NEAR(earliest_arrival_time(25.0f, 0.0f, 2.0f, 20.0f), 5.0f, 1e-5f);  // 25 = t^2
  EXPECT_NEAR(earliest_arrival_time(200.0f, 0.0f, 2.0f, 20.0f), 15.0f,
              1e-5f);  // 10 s up to 20 m/s (100 m) + 5 s
  EXPECT_NEAR(earliest_arrival_time(30.0f, 10.0f, 2.0f, 30.0f), -5.0f + sqrtf(55.0f),
              1e-5f);  // 10t + t^2 = 30
  EXPECT_FLOAT_EQ(earliest_arrival_time(0.0f, 0.0f, 0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(earliest_arrival_time(-2.0f, 5.0f, 1.0f, 10.0f), 0.0f);
  EXPECT_EQ(earliest_arrival_time(10.0f, 0.0f, 0.0f, 10.0f), kNeverArrives);
  // Already above its desired speed: constant speed.
  EXPECT_FLOAT_EQ(earliest_arrival_time(40.0f, 20.0f, 2.0f, 10.0f), 2.0f);
}

TEST(ModelsRightOfWay, YieldTimeWindow) {
  const ApproachingFoe far{100.0f, 10.0f, 0.0f, 10.0f};    // arrives after 10 s
  const ApproachingFoe near{30.0f, 10.0f, 0.0f, 10.0f};    // arrives after 3 s
  const ApproachingFoe standing{5.0f, 0.0f, 2.6f, 14.0f};  // could arrive after sqrt(5/1.3) = 1.96 s
  EXPECT_FALSE(foe_conflicts(far, 3.0f, 2.0f));
  EXPECT_TRUE(foe_conflicts(near, 3.0f, 2.0f));
  EXPECT_TRUE(foe_conflicts(standing, 3.0f, 0.0f));
  EXPECT_FALSE(foe_conflicts(standing, 1.0f, 0.5f));
  const ApproachingFoe foes[] = {far, near};
  EXPECT_TRUE(yield_may_enter(3.0f, foes, 1, 2.0f));
  EXPECT_FALSE(yield_may_enter(3.0f, foes, 2, 2.0f));
  EXPECT_TRUE(yield_may_enter(3.0f, nullptr, 0, 2.0f));
  // A foe already on the conflict point always blocks.
  const ApproachingFoe inside{0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_FALSE(yield_may_enter(0.1f, &inside, 1, 0.0f));
}

TEST(ModelsRightOfWay, RightBeforeLeftOnlyYieldsToTheRight) {
  const ApproachingFoe near{20.0f, 10.0f, 0.0f, 10.0f};
  const ApproachingFoe foes[] = {near};
  const bool from_left[] = {false};
  const bool from_right[] = {true};
  EXPECT_TRUE(right_before_left_may_enter(3.0f, foes, from_left, 1, 1.0f));
  EXPECT_FALSE(right_before_left_may_enter(3.0f, foes, from_right, 1, 1.0f));
  // From the right but far enough away.
  const ApproachingFoe far{200.0f, 10.0f, 0.0f, 10.0f};
  EXPECT_TRUE(right_before_left_may_enter(3.0f, &far, from_right, 1, 1.0f));
}

TEST(ModelsRightOfWay, AllwayStopFirstComeFirstServedTiesByLane) {
  const AllwayWaiter me{100, 7};
  EXPECT_TRUE(allway_precedes(AllwayWaiter{99, 9}, me));
  EXPECT_TRUE(allway_precedes(AllwayWaiter{100, 3}, me));
  EXPECT_FALSE(allway_precedes(AllwayWaiter{100, 8}, me));
  EXPECT_FALSE(allway_precedes(AllwayWaiter{101, 0}, me));
  EXPECT_FALSE(allway_precedes(me, me));

  const AllwayWaiter later[] = {{101, 0}, {100, 8}};
  const AllwayWaiter earlier[] = {{101, 0}, {100, 2}};
  EXPECT_TRUE(allway_stop_may_enter(true, me, later, 2, false));
  EXPECT_FALSE(allway_stop_may_enter(true, me, earlier, 2, false));
  EXPECT_FALSE(allway_stop_may_enter(false, me, later, 2, false));  // must stop first
  EXPECT_FALSE(allway_stop_may_enter(true, me, later, 2, true));    // junction occupied
  EXPECT_TRUE(allway_stop_may_enter(true, me, nullptr, 0, false));
  // Exactly one of several simultaneous arrivals goes.
  const AllwayWaiter all[] = {{50, 4}, {50, 1}, {50, 9}};
  int goes = 0;
  for (int i = 0; i < 3; ++i) {
    AllwayWaiter others[2];
    int n = 0;
    for (int j = 0; j < 3; ++j)
      if (j != i) others[n++] = all[j];
    if (allway_stop_may_enter(true, all[i], others, n, false)) {
      ++goes;
      EXPECT_EQ(all[i].lane_index, 1);
    }
  }
  EXPECT_EQ(goes, 1);
}

TEST(ModelsRightOfWay, FoesOfLinksWithoutPriorityAreSeenWithinTheVisibilityDistance) {
  for (char c : {'m', 'g', 'o', 's', '=', 'w'}) {
    EXPECT_TRUE(foes_unseen(c, 4.6f)) << c;
    EXPECT_FALSE(foes_unseen(c, 4.5f)) << c;
    EXPECT_FALSE(foes_unseen(c, 0.0f)) << c;
  }
  // Prioritised links (the zipper counts as one in SUMO), and signal states that stop or commit anyway.
  for (char c : {'M', 'G', 'O', 'Z', 'y', 'Y', 'r', 'u'}) EXPECT_FALSE(foes_unseen(c, 50.0f)) << c;
}

// SUMO's gap test at a minor link (MSLink::blockedByFoe), with the numbers SUMO 1.15's --link-output shows
// for a Krauss car standing 0.1 m before the line of the T junction in tests/sumo/impatience_test.cpp
// (internal lane 9.03 m at 6.51 m/s): it arrives in 0.04 s at 2.70 m/s and leaves 3.05 s later.
TEST(ModelsRightOfWay, LinkPassageAsSumoEstimatesIt) {
  const LinkPassage p = link_passage(0.1f, 0.0f, 2.6f, 1.0f, 13.89f, 9.03f, 6.51f, 5.0f);
  EXPECT_NEAR(p.arrival, 0.04f, 0.01f);
  EXPECT_NEAR(p.arrival_speed, 2.70f, 0.01f);
  EXPECT_FLOAT_EQ(p.leave_speed, 6.51f);
  EXPECT_NEAR(p.leave - p.arrival, 14.03f / (0.5f * (2.70f + 6.51f)), 0.02f);
  // Behind a leader still in the junction it leaves no faster than its next step's speed: SUMO's 2.60.
  const LinkPassage q = link_passage_capped(p, 2.6f, 9.03f, 5.0f);
  EXPECT_FLOAT_EQ(q.leave_speed, 2.6f);
  EXPECT_NEAR(q.leave - q.arrival, 14.03f / (0.5f * (2.70f + 2.6f)), 0.02f);
}

TEST(ModelsRightOfWay, FoeBlocksThePassageAsInSumo) {
  const LinkPassage own = link_passage(0.1f, 0.0f, 2.6f, 1.0f, 13.89f, 9.03f, 6.51f, 5.0f);
  // Without impatience only the time window counts: a foe arriving within leave + 1 s blocks, a later
  // one that can still stop does not, on a merge or not.
  EXPECT_TRUE(foe_blocks_passage(own, 4.5f, AnnouncedFoe{30.0f, 12.0f, 2.6f, 12.0f, 4.5f}, 0.0f, true, 1.0f));
  EXPECT_FALSE(
      foe_blocks_passage(own, 4.5f, AnnouncedFoe{60.0f, 12.0f, 2.6f, 12.0f, 4.5f}, 0.0f, true, 1.0f));
  // A little impatience: the foe braking at impatience x decel cannot stop, so on a merge it arrives
  // faster than the car leaves and blocks; on a crossing it only arrives a little later and does not.
  EXPECT_TRUE(foe_blocks_passage(own, 4.5f, AnnouncedFoe{60.0f, 12.0f, 2.6f, 12.0f, 4.5f}, 0.1f, true, 1.0f));
  EXPECT_FALSE(
      foe_blocks_passage(own, 4.5f, AnnouncedFoe{60.0f, 12.0f, 2.6f, 12.0f, 4.5f}, 0.1f, false, 1.0f));
  // Enough impatience for the foe to stop: it is taken as arriving 30 s later at speed 0.
  EXPECT_FALSE(
      foe_blocks_passage(own, 4.5f, AnnouncedFoe{60.0f, 12.0f, 2.6f, 12.0f, 4.5f}, 0.5f, true, 1.0f));
  // A standing foe never arrives.
  EXPECT_FALSE(foe_blocks_passage(own, 4.5f, AnnouncedFoe{5.0f, 0.0f, 2.6f, 12.0f, 4.5f}, 0.0f, true, 1.0f));
}

}  // namespace
}  // namespace lpsim

// The rules of kernels/scheduled_stop.hpp: when a vehicle has reached its stop, and the step it leaves.
#include "kernels/scheduled_stop.hpp"

#include <gtest/gtest.h>

namespace lpsim {
namespace {

TEST(ScheduledStop, ReachedAtTheStopsEndOrWhollyWithinItBehindAnother) {
  // A 20 m bus stop [200, 220]: a 12 m bus at its end (within SUMO's 0.5 m), or wholly within it.
  EXPECT_TRUE(stop_reached(220.0f, 12.0f, 200.0f, 220.0f));
  EXPECT_TRUE(stop_reached(219.6f, 12.0f, 200.0f, 220.0f));
  EXPECT_TRUE(stop_reached(215.0f, 12.0f, 200.0f, 220.0f));
  EXPECT_FALSE(stop_reached(211.0f, 12.0f, 200.0f, 220.0f));
  // Behind a bus standing at the end, a 5 m car fits wholly within the stop; a second bus does not.
  EXPECT_TRUE(stop_reached(205.5f, 5.0f, 200.0f, 220.0f));
  EXPECT_FALSE(stop_reached(205.5f, 12.0f, 200.0f, 220.0f));
  // Past the end: not this stop.
  EXPECT_FALSE(stop_reached(221.0f, 5.0f, 200.0f, 220.0f));
  // A stop on a lane position (start 0.2 m before the end) is reached only at its end.
  EXPECT_TRUE(stop_reached(99.9f, 5.0f, 99.8f, 100.0f));
  EXPECT_FALSE(stop_reached(95.0f, 5.0f, 99.8f, 100.0f));
}

TEST(ScheduledStop, ReleasedAfterItsDurationCountedFromTheStepThatReachedIt) {
  // SUMO: a bus reaching its stop at t = 23 with duration 20 moves again in the step that ends at 43: step
  // index 42 from a begin of 0 with 1 s steps (the step that reached it was 22).
  EXPECT_EQ(stop_release_step(22, 20, 0), 42u);
  // Until a time (the step that ends at it): not before, whatever the duration.
  EXPECT_EQ(stop_release_step(106, 0, 149), 149u);
  EXPECT_EQ(stop_release_step(106, 50, 149), 156u);
  // A stop whose time has passed still stands one step (SUMO: ended = started + 1).
  EXPECT_EQ(stop_release_step(478, 0, 449), 479u);
  EXPECT_EQ(stop_release_step(478, 0, 0), 479u);
}

}  // namespace
}  // namespace lpsim

// The room a lane offers behind a junction (kernels/junction_space.hpp), read from the lane map as SUMO's
// junction-blocking rule counts it: the rear of the first vehicle at a standstill less the room the moving
// vehicles behind it take (length + min gap each), or the lane's length less the room all its vehicles
// take; the speed of the vehicle nearest the lane's start; and every vehicle counted as moving when asked.
#include "kernels/junction_space.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace lpsim {
namespace {

// One lane of `cells` metres in a padded map.
struct OneLane {
  explicit OneLane(uint32_t cells) : begin{0, cells}, num_cells{cells}, length{static_cast<float>(cells)} {
    map.assign(cells + kLaneMapPadding, 0);
    net.num_lanes = 1;
    net.lane_cell_begin = begin.data();
    net.lane_num_cells = num_cells.data();
    net.lane_length = length.data();
  }
  // A vehicle's body over cells [rear, front] at `speed`.
  void put(uint32_t rear, uint32_t front, float speed) {
    for (uint32_t c = rear; c <= front; ++c) map[c] = encode_cell_speed(speed);
  }
  LaneRoom room(float min_gap, bool count_standing = true) const {
    return room_on_lane(map.data(), net, 0, min_gap, count_standing);
  }
  std::vector<uint32_t> begin, num_cells;
  std::vector<float> length;
  std::vector<uint8_t> map;
  NetView net{};
};

TEST(JunctionSpace, EmptyLaneOffersItsLength) {
  const OneLane lane(40);
  const LaneRoom r = lane.room(2.5f);
  EXPECT_TRUE(r.empty);
  EXPECT_FALSE(r.standing);
  EXPECT_FLOAT_EQ(r.space, 40.0f);
}

TEST(JunctionSpace, MovingVehiclesTakeTheirLengthAndGap) {
  OneLane lane(40);
  lane.put(3, 8, 5.0f);     // a 5 m car (6 cells) at 5 m/s
  lane.put(20, 32, 12.0f);  // a 12 m bus (13 cells) at 12 m/s
  const LaneRoom r = lane.room(2.5f);
  EXPECT_FALSE(r.empty);
  EXPECT_FALSE(r.standing);
  EXPECT_FLOAT_EQ(r.space, 40.0f - (5.0f + 2.5f) - (12.0f + 2.5f));
  EXPECT_FLOAT_EQ(r.last_speed, 5.0f);  // the one nearest the lane's start
}

TEST(JunctionSpace, RoomEndsAtTheFirstStandingVehicle) {
  OneLane lane(60);
  lane.put(2, 7, 3.0f);    // moving, behind the queue
  lane.put(25, 30, 0.0f);  // the queue's tail, standing
  lane.put(34, 39, 0.0f);
  const LaneRoom r = lane.room(2.5f);
  EXPECT_TRUE(r.standing);
  EXPECT_FLOAT_EQ(r.space, 25.0f - (5.0f + 2.5f));
  // Counted as moving (the vehicles inside a junction): every vehicle takes its room.
  const LaneRoom all = lane.room(2.5f, false);
  EXPECT_FALSE(all.standing);
  EXPECT_FLOAT_EQ(all.space, 60.0f - 3 * (5.0f + 2.5f));
}

TEST(JunctionSpace, TouchingVehiclesOfDifferentSpeedsAreTwoVehicles) {
  OneLane lane(30);
  lane.put(0, 5, 2.0f);
  lane.put(6, 11, 1.0f);  // directly ahead of the first, slower
  const LaneRoom r = lane.room(1.0f);
  EXPECT_FLOAT_EQ(r.space, 30.0f - 2 * (5.0f + 1.0f));
  EXPECT_FLOAT_EQ(r.last_speed, 2.0f);
}

TEST(JunctionSpace, StandingVehicleAtTheLaneStartLeavesNoRoom) {
  OneLane lane(10);
  lane.put(0, 5, 0.0f);
  const LaneRoom r = lane.room(2.5f);
  EXPECT_TRUE(r.standing);
  EXPECT_FLOAT_EQ(r.space, 0.0f);
}

}  // namespace
}  // namespace lpsim

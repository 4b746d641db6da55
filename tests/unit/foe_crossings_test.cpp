// Where a foe's internal lane crosses a connection's path, on a hand-built junction: a crossing foe blocks
// up to the crossing plus clearance, a merging or non-crossing foe along its whole via lane.
#include "engine/foe_crossings.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lpsim {
namespace {

// Lane 0: the approach (normal). Internal lanes, 20 m each: 1 (own path, west to east along y = 0),
// 2 (south to north through x = 10), 3 (merging into the own path's end), 4 (parallel, y = 5).
// Connection k leaves lane 0 via lane k + 1; only the via lanes and their shapes matter here.
Network junction() {
  Network net;
  net.edge_is_internal = {0, 1};
  net.lane_id = {"a_0", ":j_0_0", ":j_1_0", ":j_2_0", ":j_3_0"};
  net.lane_edge = {0, 1, 1, 1, 1};
  net.lane_length = {50, 20, 20, 20, 20};
  net.lane_cell_begin = {0, 50, 70, 90, 110, 130};
  net.lane_conn_begin = {0, 4, 4, 4, 4, 4};
  const std::vector<std::vector<float>> xs = {{-50, 0}, {0, 20}, {10, 10}, {0, 20}, {0, 20}};
  const std::vector<std::vector<float>> ys = {{0, 0}, {0, 0}, {-10, 10}, {5, 0}, {5, 5}};
  for (size_t l = 0; l < xs.size(); ++l) {
    net.lane_shape_begin.push_back(static_cast<uint32_t>(net.shape_x.size()));
    net.shape_x.insert(net.shape_x.end(), xs[l].begin(), xs[l].end());
    net.shape_y.insert(net.shape_y.end(), ys[l].begin(), ys[l].end());
  }
  net.lane_shape_begin.push_back(static_cast<uint32_t>(net.shape_x.size()));
  net.conn_from_lane = {0, 0, 0, 0};
  net.conn_via_lane = {1, 2, 3, 4};
  return net;
}

TEST(FoeCrossings, CrossingFoeBlocksUpToTheCrossingMergingOrParallelFoeAlongItsLane) {
  const Network net = junction();
  // Connection 0 yields to 1 (crossing at 10 m of its 20), 2 (merging at the end) and 3 (never crossing).
  const std::vector<uint32_t> begin = {0, 3, 3, 3, 3};
  const std::vector<uint32_t> foes = {1, 2, 3};
  const std::vector<uint16_t> cells = foe_block_cells(net, begin, foes);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0], 12);  // 10 m to the crossing + 2 m clearance
  EXPECT_EQ(cells[1], 20);
  EXPECT_EQ(cells[2], 20);
}

TEST(FoeCrossings, ShapeLengthIsScaledToTheLaneLength) {
  Network net = junction();
  net.lane_length[2] = 30.0f;  // the crossing lies halfway along the lane: at 15 m
  net.lane_cell_begin = {0, 50, 70, 100, 120, 140};
  const std::vector<uint16_t> cells = foe_block_cells(net, {0, 1, 1, 1, 1}, {1});
  EXPECT_EQ(cells[0], 17);
}

}  // namespace
}  // namespace lpsim

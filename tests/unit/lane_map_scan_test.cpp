// The lane-map scans (word-wise on the host) find exactly what a cell-by-cell scan finds, for every range
// of sparse and dense lanes, including ranges shorter than a word and ends that are not word-aligned; and
// footprint fills (word stores on the host) write exactly the cells of their range; the standing test
// equals decoding the encoded speed; and distances convert to cells as a cast does, capped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "kernels/lane_map.hpp"
#include "kernels/rng.hpp"

namespace lpsim {
namespace {

int32_t naive_first(const std::vector<uint8_t>& cells, int32_t first, int32_t last) {
  for (int32_t c = first; c <= last; ++c)
    if (cells[c] != 0) return c;
  return -1;
}

int32_t naive_last(const std::vector<uint8_t>& cells, int32_t first, int32_t last) {
  for (int32_t c = last; c >= first; --c)
    if (cells[c] != 0) return c;
  return -1;
}

TEST(LaneMapScan, WordScansEqualCellByCellScans) {
  // Two lanes of 37 and 70 cells behind a 3-cell lane, so lane starts are not word-aligned either.
  const std::vector<uint32_t> begin = {0, 3, 40, 110}, cells_of = {3, 37, 70};
  NetView net{};
  net.num_lanes = 3;
  net.lane_cell_begin = begin.data();
  net.lane_num_cells = cells_of.data();
  int checked = 0, found = 0;
  for (uint64_t trial = 0; trial < 60; ++trial) {
    // Occupancy from very sparse (one cell in 40) to dense (one in 2).
    const uint32_t one_in = 2 + static_cast<uint32_t>(trial % 40);
    // Padded as the engine's maps are, with occupied cells: the scans must not see past their range.
    std::vector<uint8_t> map(begin.back() + kLaneMapPadding, 1);
    for (uint32_t i = 0; i < begin.back(); ++i)
      map[i] = (rng_bits(7, trial, i) % one_in == 0) ? static_cast<uint8_t>(1 + i % 200) : 0;
    for (int32_t lane = 0; lane < 3; ++lane) {
      const int32_t cells = static_cast<int32_t>(begin[lane + 1] - begin[lane]);
      const std::vector<uint8_t> lane_cells_copy(map.begin() + begin[lane], map.begin() + begin[lane + 1]);
      for (int32_t first = 0; first < cells; ++first)
        for (int32_t last = first - 1; last < cells; ++last) {
          const int32_t a = first_occupied(map.data(), net, lane, first, last);
          ASSERT_EQ(a, naive_first(lane_cells_copy, first, last)) << lane << " " << first << ".." << last;
          ASSERT_EQ(last_occupied(map.data(), net, lane, first, last),
                    naive_last(lane_cells_copy, first, last))
              << lane << " " << first << ".." << last;
          ++checked;
          found += a >= 0;
        }
    }
  }
  EXPECT_GT(checked, 100000);
  EXPECT_GT(found, checked / 2);  // most ranges hold a vehicle: both outcomes are exercised
}

TEST(LaneMapScan, FillWritesExactlyItsRange) {
  const std::vector<uint32_t> begin = {0, 5, 45, 90}, cells_of = {5, 40, 45};
  NetView net{};
  net.num_lanes = 3;
  net.lane_cell_begin = begin.data();
  net.lane_num_cells = cells_of.data();
  int filled = 0;
  for (int32_t lane = 0; lane < 3; ++lane) {
    const int32_t cells = static_cast<int32_t>(begin[lane + 1] - begin[lane]);
    for (int32_t first = 0; first < cells; ++first)
      for (int32_t last = first; last < cells; ++last) {
        std::vector<uint8_t> map(begin.back(), 7);
        fill_cells(map.data(), net, lane, static_cast<uint32_t>(first), static_cast<uint32_t>(last), 200);
        for (uint32_t i = 0; i < map.size(); ++i) {
          const int32_t c = static_cast<int32_t>(i) - static_cast<int32_t>(begin[lane]);
          const bool inside = c >= first && c <= last;
          ASSERT_EQ(map[i], inside ? 200 : 7) << lane << " " << first << ".." << last << " cell " << i;
          filled += inside;
        }
      }
  }
  EXPECT_GT(filled, 10000);
}

TEST(LaneMapScan, StandingTestEqualsTheDecodedCellSpeed) {
  int standing = 0, moving = 0;
  // Every float from 0 to 1 m/s in steps of 2^-20, the neighbours of 0.25 and a spread of larger speeds.
  std::vector<float> speeds = {0.0f, -0.0f, 0.25f, std::nextafter(0.25f, 0.0f), std::nextafter(0.25f, 1.0f),
                               70.0f};
  for (int k = 0; k <= (1 << 20); ++k) speeds.push_back(static_cast<float>(k) / static_cast<float>(1 << 20));
  for (uint64_t k = 0; k < 1000; ++k) speeds.push_back(0.25f + rng_uniform(5, 1, k) * 80.0f);
  for (float v : speeds) {
    const bool by_decoding = decode_cell_speed(encode_cell_speed(v)) == 0.0f;
    ASSERT_EQ(encodes_as_standing(v), by_decoding) << v;
    (by_decoding ? standing : moving) += 1;
  }
  EXPECT_EQ(standing, 2 + 1 + (1 << 18));  // 0, -0, 0.25's lower neighbour, and [0, 0.25) of the sweep
  EXPECT_GT(moving, 1000);
}

TEST(LaneMapScan, MetresAsCellsFloorsAndCapsHugeDistances) {
  EXPECT_EQ(metres_as_cells(0.0f), 0);
  EXPECT_EQ(metres_as_cells(5.99f), 5);
  EXPECT_EQ(metres_as_cells(1000.0f), 1000);
  // The largest float below the cap converts exactly; the cap and anything beyond (NaN too) give the cap.
  const float below = std::nextafter(static_cast<float>(kMaxCellSpan), 0.0f);
  EXPECT_EQ(metres_as_cells(below), static_cast<int32_t>(below));
  EXPECT_EQ(metres_as_cells(static_cast<float>(kMaxCellSpan)), kMaxCellSpan);
  EXPECT_EQ(metres_as_cells(3e38f), kMaxCellSpan);
  EXPECT_EQ(metres_as_cells(std::nanf("")), kMaxCellSpan);
  // With lanes capped at kMaxLaneCells, a front cell plus a capped reach still fits an int32.
  EXPECT_LT(int64_t{kMaxLaneCells} + 1 + kMaxCellSpan, int64_t{INT32_MAX});
}

}  // namespace
}  // namespace lpsim

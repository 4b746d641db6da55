// SUMO's check of stop and stopping-place positions (stop_position_valid), against what sumo 1.15 made of
// each case on a 100 m lane: negative positions count from the lane's end without friendlyPos; friendlyPos
// moves the stretch onto the lane (a stopping place keeps at least 0.1 m, a stop may be a point).
#include <gtest/gtest.h>

#include <optional>

#include "demand/stop_resolution.hpp"

namespace lpsim {
namespace {

struct Case {
  double start, end;
  bool friendly;
  std::optional<std::pair<double, double>> sumo;  // where SUMO put it; nullopt: SUMO refused it
};

void expect_as_sumo(const Case& c, double min_length) {
  double start = c.start, end = c.end;
  const bool valid = stop_position_valid(start, end, 100.0, min_length, c.friendly);
  SCOPED_TRACE(std::to_string(c.start) + ".." + std::to_string(c.end) + (c.friendly ? " friendly" : ""));
  ASSERT_EQ(valid, c.sumo.has_value());
  if (!valid) return;
  EXPECT_NEAR(start, c.sumo->first, 1e-9);
  EXPECT_NEAR(end, c.sumo->second, 1e-9);
}

TEST(StopPosition, StoppingPlacesAsSumoPlacesThem) {
  using P = std::pair<double, double>;
  for (const Case& c :
       {Case{-30, -10, false, P{70, 90}}, Case{-100, 20, false, P{0, 20}},
        Case{-100.5, 20, false, std::nullopt}, Case{-100.5, 20, true, P{0, 20}},
        Case{90, 120, false, std::nullopt}, Case{90, 120, true, P{90, 100}},
        Case{50, 40, false, std::nullopt}, Case{50, 40, true, P{39.9, 40}}, Case{0, 0, false, std::nullopt},
        Case{0, 0, true, P{0, 0.1}}, Case{0, 0.1, false, P{0, 0.1}}, Case{100, 100, false, std::nullopt},
        Case{100, 100, true, P{99.9, 100}}})
    expect_as_sumo(c, 0.1);
}

TEST(StopPosition, StopsMayBePointsAndMoveOntoTheLaneOnlyWhenFriendly) {
  using P = std::pair<double, double>;
  for (const Case& c : {Case{50, 50, false, P{50, 50}}, Case{100, 100, false, P{100, 100}},
                        Case{100.5, 100.5, false, std::nullopt}, Case{119.8, 120, false, std::nullopt},
                        Case{119.8, 120, true, P{100, 100}}, Case{60, 50, false, std::nullopt},
                        Case{60, 50, true, P{50, 50}}, Case{-150, 20, true, P{0, 20}}})
    expect_as_sumo(c, 0.0);
}

TEST(StopPosition, AStopAtTheVeryEndOfAShortLaneIsValid) {
  // The case that refused the DLR bus network: 0.1 m at the end of an 11.95 m lane, valid in SUMO even
  // without friendlyPos (11.95 - 0.1 is 11.85 in double arithmetic).
  double start = 11.85, end = 11.95;
  EXPECT_TRUE(stop_position_valid(start, end, 11.95, 0.1, false));
  EXPECT_EQ(start, 11.85);
  EXPECT_EQ(end, 11.95);
}

}  // namespace
}  // namespace lpsim

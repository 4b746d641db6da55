#pragma once
// Where a position along a lane lies in net coordinates, for FCD output.
//
// SUMO draws a lane along its shape polyline, whose 2D length may differ from the lane's nominal length
// (the length used for driving). A lane position p is mapped to the shape offset p * shape_length /
// lane_length, as SUMO's MSLane does with its length-geometry factor. at() gives the heading of the shape
// segment holding that offset, in navigational degrees (0 = north, clockwise, in [0, 360)).
//
// SUMO's FCD angle is the direction from a vehicle's back to its front bumper, which differs from the
// segment heading on bends. vehicle_heading() reproduces it: the back lies one vehicle length behind the
// front along the lane, continuing onto the previous lane when that lane is unambiguous (always for
// internal junction lanes, which have exactly one incoming lane). Where the previous lane is ambiguous the
// back is clamped to the lane start, a chord that still follows the bend.
#include <cstdint>
#include <vector>

#include "net/network.hpp"

namespace lpsim {

struct LanePoint {
  double x = 0, y = 0;
  double angle = 0;  // navigational degrees
};

/// Navigational angle (0 = north, clockwise, [0, 360)) of the direction (dx, dy) in net coordinates.
double navigational_degrees(double dx, double dy);

class LaneGeometry {
 public:
  /// Precomputes the cumulative segment lengths of every lane shape in `net` (kept by reference).
  explicit LaneGeometry(const Network& net);

  /// Point and heading at `pos` metres from the start of `lane`. Positions outside [0, lane length] are
  /// clamped to the shape's ends. A lane with a one-point shape yields that point, heading 0; a lane
  /// without shape points yields (0, 0), heading 0.
  LanePoint at(uint32_t lane, double pos) const;

  /// Navigational heading from the back (pos - vehicle_length) to the front (pos) of a vehicle on `lane`.
  double vehicle_heading(uint32_t lane, double pos, double vehicle_length) const;

  /// The single lane leading into `lane` (through a connection or as its internal lane), or kNone when
  /// there is none or more than one.
  int32_t unique_predecessor(uint32_t lane) const { return predecessor_[lane]; }

  /// 2D length of the lane's shape polyline.
  double shape_length(uint32_t lane) const;

 private:
  const Network& net_;
  std::vector<double> cumulative_;    // per shape point: shape length from the lane's first point
  std::vector<int32_t> predecessor_;  // per lane: unique incoming lane, kNone if none or several
};

}  // namespace lpsim

#include "converters/lane_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lpsim {

double navigational_degrees(double dx, double dy) {
  // atan2 gives the mathematical angle (0 = east, counter-clockwise); navigation turns it to 0 = north,
  // clockwise.
  double degrees = 90.0 - std::atan2(dy, dx) * 180.0 / std::numbers::pi;
  if (degrees < 0) degrees += 360.0;
  if (degrees >= 360.0) degrees -= 360.0;
  return degrees;
}

LaneGeometry::LaneGeometry(const Network& net) : net_(net), cumulative_(net.shape_x.size(), 0.0) {
  for (uint32_t lane = 0; lane < net.num_lanes(); ++lane) {
    const uint32_t first = net.lane_shape_begin[lane], end = net.lane_shape_begin[lane + 1];
    double length = 0;
    for (uint32_t i = first; i < end; ++i) {
      if (i > first) {
        length += std::hypot(double(net.shape_x[i]) - net.shape_x[i - 1], double(net.shape_y[i]) - net.shape_y[i - 1]);
      }
      cumulative_[i] = length;
    }
  }
}

double LaneGeometry::shape_length(uint32_t lane) const {
  const uint32_t first = net_.lane_shape_begin[lane], end = net_.lane_shape_begin[lane + 1];
  return end > first ? cumulative_[end - 1] : 0.0;
}

LanePoint LaneGeometry::at(uint32_t lane, double pos) const {
  const uint32_t first = net_.lane_shape_begin[lane], end = net_.lane_shape_begin[lane + 1];
  if (end == first) return {};
  if (end - first == 1) return {net_.shape_x[first], net_.shape_y[first], 0.0};

  const double total = cumulative_[end - 1];
  const double lane_length = net_.lane_length[lane];
  double offset = lane_length > 0 ? pos * total / lane_length : pos;
  offset = std::clamp(offset, 0.0, total);

  // The segment [i-1, i] whose end is the first at or beyond the offset: at a vertex the incoming segment
  // gives the heading, and zero-length segments (duplicate points) are passed over.
  const auto cum_begin = cumulative_.begin() + first + 1, cum_end = cumulative_.begin() + end;
  uint32_t i = static_cast<uint32_t>(std::lower_bound(cum_begin, cum_end, offset) - cumulative_.begin());
  if (i >= end) i = end - 1;
  while (i + 1 < end && cumulative_[i] == cumulative_[i - 1]) ++i;

  const double x0 = net_.shape_x[i - 1], y0 = net_.shape_y[i - 1];
  const double dx = double(net_.shape_x[i]) - x0, dy = double(net_.shape_y[i]) - y0;
  const double segment = cumulative_[i] - cumulative_[i - 1];
  const double t = segment > 0 ? (offset - cumulative_[i - 1]) / segment : 0.0;
  return {x0 + dx * t, y0 + dy * t, navigational_degrees(dx, dy)};
}

}  // namespace lpsim

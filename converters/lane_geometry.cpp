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

namespace {

constexpr int32_t kAmbiguous = -2;

void add_predecessor(std::vector<int32_t>& predecessor, uint32_t lane, uint32_t from) {
  int32_t& p = predecessor[lane];
  if (p == kNone)
    p = static_cast<int32_t>(from);
  else if (p != static_cast<int32_t>(from))
    p = kAmbiguous;
}

}  // namespace

LaneGeometry::LaneGeometry(const Network& net)
    : net_(net), cumulative_(net.shape_x.size(), 0.0), predecessor_(net.num_lanes(), kNone) {
  // A connection from -> to crossing internal lane `via` makes `from` precede `via` and `via` precede `to`.
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    const uint32_t from = net.conn_from_lane[c], to = net.conn_to_lane[c];
    const int32_t via = net.conn_via_lane[c];
    if (via != kNone) {
      add_predecessor(predecessor_, static_cast<uint32_t>(via), from);
      add_predecessor(predecessor_, to, static_cast<uint32_t>(via));
    } else {
      add_predecessor(predecessor_, to, from);
    }
  }
  for (int32_t& p : predecessor_)
    if (p == kAmbiguous) p = kNone;

  for (uint32_t lane = 0; lane < net.num_lanes(); ++lane) {
    const uint32_t first = net.lane_shape_begin[lane], end = net.lane_shape_begin[lane + 1];
    double length = 0;
    for (uint32_t i = first; i < end; ++i) {
      if (i > first) {
        length += net.shape_segment_length(i);
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

double LaneGeometry::vehicle_heading(uint32_t lane, double pos, double vehicle_length) const {
  const LanePoint front = at(lane, pos);
  const double back_pos = pos - vehicle_length;
  LanePoint back;
  if (back_pos >= 0 || predecessor_[lane] == kNone) {
    back = at(lane, std::max(back_pos, 0.0));
  } else {
    const uint32_t previous = static_cast<uint32_t>(predecessor_[lane]);
    back = at(previous, net_.lane_length[previous] + back_pos);
  }
  if (back.x == front.x && back.y == front.y) return front.angle;
  return navigational_degrees(front.x - back.x, front.y - back.y);
}

}  // namespace lpsim

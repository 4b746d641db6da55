#include "engine/foe_crossings.hpp"

#include <algorithm>
#include <cmath>

namespace lpsim {

namespace {

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

double shape_length(const Network& net, uint32_t lane) {
  double length = 0.0;
  for (uint32_t i = net.lane_shape_begin[lane] + 1; i < net.lane_shape_begin[lane + 1]; ++i)
    length += net.shape_segment_length(i);
  return length;
}

// Distance along lane a's shape to its last crossing with lane b's shape, or -1 if they do not cross.
double last_crossing(const Network& net, uint32_t a, uint32_t b) {
  double last = -1.0, along = 0.0;
  for (uint32_t i = net.lane_shape_begin[a] + 1; i < net.lane_shape_begin[a + 1]; ++i) {
    const double ax = net.shape_x[i - 1], ay = net.shape_y[i - 1];
    const double rx = net.shape_x[i] - ax, ry = net.shape_y[i] - ay;
    const double segment = net.shape_segment_length(i);
    for (uint32_t j = net.lane_shape_begin[b] + 1; j < net.lane_shape_begin[b + 1]; ++j) {
      const double bx = net.shape_x[j - 1], by = net.shape_y[j - 1];
      const double sx = net.shape_x[j] - bx, sy = net.shape_y[j] - by;
      const double denom = cross(rx, ry, sx, sy);
      if (std::fabs(denom) < 1e-12) continue;  // parallel
      const double t = cross(bx - ax, by - ay, sx, sy) / denom;
      const double u = cross(bx - ax, by - ay, rx, ry) / denom;
      if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) last = std::max(last, along + t * segment);
    }
    along += segment;
  }
  return last;
}

bool is_internal(const Network& net, int32_t lane) {
  return lane >= 0 && net.edge_is_internal[net.lane_edge[static_cast<uint32_t>(lane)]] != 0;
}

}  // namespace

std::vector<uint16_t> foe_block_cells(const Network& net, const std::vector<uint32_t>& foe_begin,
                                      const std::vector<uint32_t>& foe_list) {
  std::vector<uint16_t> cells(foe_list.size(), 0);
  const bool shapes = net.lane_shape_begin.size() == net.num_lanes() + 1;
  for (size_t c = 0; c + 1 < foe_begin.size(); ++c) {
    // The connection's own path inside the junction: its via lane and, past an internal junction, the next.
    int32_t path[2] = {net.conn_via_lane[c], -1};
    if (path[0] >= 0) {
      const uint32_t b = net.lane_conn_begin[static_cast<uint32_t>(path[0])];
      if (b < net.lane_conn_begin[static_cast<uint32_t>(path[0]) + 1] &&
          is_internal(net, net.conn_via_lane[b]))
        path[1] = net.conn_via_lane[b];
    }
    for (uint32_t k = foe_begin[c]; k < foe_begin[c + 1]; ++k) {
      const int32_t fvia = net.conn_via_lane[foe_list[k]];
      if (fvia < 0) continue;
      const uint32_t f = static_cast<uint32_t>(fvia);
      const uint64_t lane_cells = net.lane_cell_begin[f + 1] - net.lane_cell_begin[f];
      uint64_t block = lane_cells;
      double last = -1.0;
      for (int32_t own : path)
        if (shapes && own >= 0) last = std::max(last, last_crossing(net, f, static_cast<uint32_t>(own)));
      const double geometric = shapes ? shape_length(net, f) : 0.0;
      if (last >= 0.0 && geometric > 0.0) {
        // Shapes and lengths can differ (SUMO's length attribute wins): measure the crossing along the lane.
        const double at = last * net.lane_length[f] / geometric + kCrossingClearance;
        block = std::min<uint64_t>(lane_cells, static_cast<uint64_t>(std::ceil(at)));
      }
      cells[k] = static_cast<uint16_t>(std::min<uint64_t>(block, 0xFFFF));
    }
  }
  return cells;
}

}  // namespace lpsim

#include "engine/routing_speeds.hpp"

#include <algorithm>
#include <cmath>

namespace lpsim {
namespace {

constexpr double kSpeedUnits = 16777216.0;  // 2^24 per m/s

}  // namespace

int64_t LaneSpeedSums::to_units(float v) { return std::llround(static_cast<double>(v) * kSpeedUnits); }

void LaneSpeedSums::add(uint32_t lane, uint32_t vehicles, int64_t speed_units) {
  if (count[lane] == 0) lanes.push_back(lane);
  count[lane] += vehicles;
  speed[lane] += speed_units;
}

void LaneSpeedSums::clear() {
  for (const uint32_t l : lanes) {
    count[l] = 0;
    speed[l] = 0;
  }
  lanes.clear();
}

RoutingSpeeds::RoutingSpeeds(const Network& net, int steps, double weight)
    : net_(net),
      steps_(steps > 0 ? steps : 0),
      weight_(weight),
      speed_(net.num_edges()),
      driven_(net.num_edges(), 0) {
  for (uint32_t e = 0; e < net.num_edges(); ++e) speed_[e] = mean_speed(e, nullptr);
  if (steps_ > 0) {
    past_.resize(static_cast<size_t>(net.num_edges()) * static_cast<size_t>(steps_));
    for (uint32_t e = 0; e < net.num_edges(); ++e)
      std::fill_n(past_.begin() + static_cast<std::ptrdiff_t>(e) * steps_, steps_, speed_[e]);
  }
}

void RoutingSpeeds::forget_samples() {
  for (const uint32_t e : driven_edges_) {
    driven_[e] = 0;
    speed_[e] = mean_speed(e, nullptr);
    if (steps_ > 0) std::fill_n(past_.begin() + static_cast<std::ptrdiff_t>(e) * steps_, steps_, speed_[e]);
  }
  driven_edges_.clear();
  next_ = 0;
  samples_ = 0;
}

double RoutingSpeeds::mean_speed(uint32_t e, const LaneSpeedSums* lanes) const {
  double weighted = 0, vehicles = 0;
  const uint32_t first = net_.edge_first_lane[e];
  for (uint32_t l = first; l < first + net_.edge_num_lanes[e]; ++l) {
    const uint32_t n = lanes ? lanes->count[l] : 0;
    if (n == 0) {
      weighted += net_.lane_speed[l];
      vehicles += 1;
    } else {
      weighted += static_cast<double>(lanes->speed[l]) / kSpeedUnits;
      vehicles += n;
    }
  }
  if (e < net_.edge_other_lanes.size()) {
    weighted += net_.edge_other_lane_speeds[e];
    vehicles += net_.edge_other_lanes[e];
  }
  return vehicles > 0 ? weighted / vehicles : net_.edge_speed[e];
}

void RoutingSpeeds::add_sample(const LaneSpeedSums& lanes) {
  bool more = false;
  for (const uint32_t l : lanes.lanes) {
    const uint32_t e = net_.lane_edge[l];
    if (driven_[e]) continue;
    driven_[e] = 1;
    driven_edges_.push_back(e);
    more = true;
  }
  if (more) std::sort(driven_edges_.begin(), driven_edges_.end());
  for (const uint32_t e : driven_edges_) {
    const double now = mean_speed(e, &lanes);
    if (steps_ > 0) {
      double& oldest =
          past_[static_cast<size_t>(e) * static_cast<size_t>(steps_) + static_cast<size_t>(next_)];
      speed_[e] += (now - oldest) / steps_;
      oldest = now;
    } else if (now != speed_[e]) {
      speed_[e] = speed_[e] * weight_ + now * (1.0 - weight_);
    }
  }
  if (steps_ > 0) next_ = (next_ + 1) % steps_;
  ++samples_;
}

}  // namespace lpsim

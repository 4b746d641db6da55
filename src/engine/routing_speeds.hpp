#pragma once
// The edge speeds SUMO's rerouting device routes on (MSRoutingEngine): every adaptation interval each edge's
// current mean speed is sampled and averaged, over the last `steps` samples (a moving average) or
// exponentially (steps 0: old * weight + new * (1 - weight)). An edge's mean speed is SUMO's
// MSEdge::getMeanSpeed: over its lanes, each lane's mean vehicle speed weighted by its vehicle count, an
// empty lane counting once at its speed limit (the lanes LPSim leaves out, sidewalks and rails, too).
// Sampled from integer sums, so that the averages do not depend on the order the vehicles are met in.
#include <cstdint>
#include <vector>

#include "backends/state_bytes.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Vehicles on each lane at one moment (front on it) and their speeds' sum, in units of 2^-24 m/s.
struct LaneSpeedSums {
  std::vector<uint32_t> count;
  std::vector<int64_t> speed;
  std::vector<uint32_t> lanes;  // those with a vehicle, in the order first met

  explicit LaneSpeedSums(uint32_t num_lanes = 0) : count(num_lanes, 0), speed(num_lanes, 0) {}
  void add(uint32_t lane, float v) { add(lane, 1, to_units(v)); }
  void add(uint32_t lane, uint32_t vehicles, int64_t speed_units);
  void clear();
  static int64_t to_units(float v);
};

class RoutingSpeeds {
 public:
  /// Every edge starts at its mean speed when empty.
  RoutingSpeeds(const Network& net, int steps, double weight);

  /// One sample of every edge's mean speed from the lanes' vehicles now. Only edges that have had a vehicle
  /// are sampled (SUMO's "delayed" edges): an edge never driven keeps its empty speed, which every sample
  /// of it would give.
  void add_sample(const LaneSpeedSums& lanes);
  /// The averaged speed of each edge (normal and internal), m/s.
  const std::vector<double>& speeds() const { return speed_; }
  /// Samples taken so far.
  uint64_t samples() const { return samples_; }
  /// Every edge back at its free-flow speed, as made (before a saved state is read into it).
  void forget_samples();
  /// The edges driven so far, with their speeds and samples: every other edge keeps its free-flow speed, as
  /// this object was made with.
  template <class A>
  void visit_state(A& a) {
    if constexpr (A::kReads) forget_samples();
    a(driven_edges_);
    a(next_);
    a(samples_);
    const size_t steps = static_cast<size_t>(steps_);
    std::vector<double> speeds, rows;
    // A sample of an edge that was empty then is its empty speed: the rows are saved as where they differ
    // from it.
    auto xor_empty = [&](size_t i, uint32_t e) {
      xor_each(rows.data() + i * steps, steps, mean_speed(e, nullptr));
    };
    if constexpr (!A::kReads)
      for (size_t i = 0; i < driven_edges_.size(); ++i) {
        const uint32_t e = driven_edges_[i];
        speeds.push_back(speed_[e]);
        rows.insert(rows.end(), past_.begin() + static_cast<std::ptrdiff_t>(e * steps),
                    past_.begin() + static_cast<std::ptrdiff_t>((e + 1) * steps));
        xor_empty(i, e);
      }
    a(speeds);
    a.sparse(rows);
    if constexpr (A::kReads) {
      if (speeds.size() != driven_edges_.size() || rows.size() != driven_edges_.size() * steps)
        a.fail("the rerouting device's speeds do not match its driven edges");
      for (size_t i = 0; i < driven_edges_.size(); ++i) {
        const uint32_t e = driven_edges_[i];
        if (e >= speed_.size() || driven_[e])
          a.fail("the rerouting device's driven edges are not this network's");
        driven_[e] = 1;
        speed_[e] = speeds[i];
        xor_empty(i, e);
        std::copy(rows.begin() + static_cast<std::ptrdiff_t>(i * steps),
                  rows.begin() + static_cast<std::ptrdiff_t>((i + 1) * steps),
                  past_.begin() + static_cast<std::ptrdiff_t>(e * steps));
      }
    }
  }
  /// SUMO's MSEdge::getMeanSpeed of edge e from `lanes`.
  double mean_speed(uint32_t e, const LaneSpeedSums* lanes) const;

 private:
  const Network& net_;
  int steps_;
  double weight_;
  std::vector<double> speed_;
  std::vector<double> past_;  // steps_ samples per edge: [e * steps_ + k]
  int next_ = 0;              // the ring position the next sample replaces
  uint64_t samples_ = 0;
  std::vector<uint8_t> driven_;         // per edge: it has had a vehicle
  std::vector<uint32_t> driven_edges_;  // those edges, ascending
};

}  // namespace lpsim

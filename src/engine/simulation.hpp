#pragma once
// The Simulation owns the run state of one scenario: the double-buffered lane map, per-vehicle state, the
// insertion queues and output counters. Each step() runs the kernels/ passes through a backend (the CPU
// backend is a ParallelFor loop over the same functions the CUDA kernels wrap). It never formats text: the
// runner in src/app samples it and hands the samples to the writers in converters/.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "demand/demand.hpp"
#include "engine/engine_net.hpp"
#include "engine/parallel_for.hpp"
#include "engine/samples.hpp"
#include "kernels/gpu_stepper.hpp"
#include "kernels/step_view.hpp"
#include "net/network.hpp"

namespace lpsim {

struct SimulationOptions {
  double begin = 0;
  double step_length = 1.0;
  uint64_t seed = 23423;
  int threads = 1;
  double time_to_teleport = 300;  // s; <= 0: never
  bool gpu = false;  // run the step's passes on the CUDA device (engine/device_select picks it)
  // Accumulate the per-lane edgeData/laneData counters (lane_counters()). Off when no such output is
  // requested: the CPU backend then skips their atomics (the GPU backend keeps them).
  bool lane_counters = true;
};

class Simulation {
 public:
  Simulation(const Network& net, const Demand& demand, const SimulationOptions& options);

  void step();
  double time() const { return static_cast<double>(time_ms_) / 1000.0; }
  uint32_t step_index() const { return step_; }
  /// Nothing running, nothing waiting to be inserted and no future departure.
  bool finished() const;

  struct Counts {
    uint64_t loaded = 0, inserted = 0, running = 0, waiting = 0, arrived = 0, teleports = 0;
    uint64_t removed = 0;  // never inserted for a reason (departure before begin, route without car lanes)
    uint64_t vehicle_updates = 0;
  };
  const Counts& counts() const { return counts_; }

  /// Positions of running vehicles now.
  void sample_fcd(FcdFrame& frame) const;
  /// edgeData/laneData counters accumulated since the last reset.
  const LaneCounters& lane_counters() const { return lane_counters_; }
  void reset_lane_counters() { lane_counters_.clear(); }
  /// Trips that ended since the last call, in order of arrival then vehicle index.
  std::vector<TripRecord> take_finished_trips();
  SummaryRow summary_row() const;

  /// Test support: recomputes the lane map from every running vehicle's footprint and reports the first
  /// cell two vehicles share or a mismatch with the engine's map ("" when consistent).
  std::string check_lane_map() const;
  /// Test support: read access to vehicle state.
  uint8_t status(uint32_t v) const { return status_[v]; }
  int32_t lane(uint32_t v) const { return lane_[v]; }
  float pos(uint32_t v) const { return pos_[v]; }
  float speed(uint32_t v) const { return speed_[v]; }
  uint32_t route_pos(uint32_t v) const { return route_pos_[v]; }
  /// What bounded the vehicle's speed in its last plan (StopReason in kernels/step_view.hpp).
  uint8_t limit_reason(uint32_t v) const { return limit_reason_[v]; }
  /// Current character of a connection's signal link (or its state when unsignalised).
  char link_state(uint32_t conn) const;
  const std::vector<uint32_t>& active() const { return active_; }

 private:
  struct StepContextBuilder;
  void build_context();
  void update_signals();
  TripView trip_view() const;
  void enqueue_due(int64_t until_ms);
  void insert_waiting(uint8_t* map);
  bool try_insert(uint32_t v, uint8_t* map);
  void handle_departures_from_road();
  void record_trip(uint32_t v, bool teleported);
  void rebuild_active();

  const Network& net_;
  const Demand& demand_;
  SimulationOptions opt_;
  EngineNet engine_net_;
  ParallelFor pool_;
  int64_t time_ms_ = 0, dt_ms_ = 1000;
  uint32_t step_ = 0;
  Counts counts_;
  float max_accel_ = 2.6f, max_emergency_decel_ = 9.0f, min_decel_ = 4.5f;

  // Lane maps: map_[cur_] is the state now; the other is written by the step.
  std::vector<uint8_t> map_[2];
  int cur_ = 0;
  std::vector<char> link_state_;
  std::vector<LaneApproach> approach_;
  // Reverse of the junction response: for each connection, the connections that must yield to it (CSR).
  std::vector<uint64_t> claims_, merge_requests_;
  LaneCounters lane_counters_;

  // Per-vehicle state (see VehicleView) and plan scratch (see PlanView).
  std::vector<uint8_t> status_, lane_change_dir_, arrives_, held_at_line_, limit_reason_, claim_prio_;
  std::vector<uint32_t> best_rp_, best_mask_, new_rp_, first_rp_, route_pos_, stopped_steps_, waiting_steps_, waiting_count_, arrival_step_;
  std::vector<float> speed_, pos_, old_pos_, time_loss_, route_length_;
  std::vector<int32_t> lane_, prev_, prev2_, old_lane_, old_prev_, old_prev2_;
  std::vector<float> new_speed_, new_pos_, stop_pos_;
  std::vector<int32_t> new_lane_, new_prev_, new_prev2_, claim0_, claim1_, stop_lane_;
  std::vector<uint8_t> teleport_pending_;
  // Departure records for tripinfo.
  std::vector<float> depart_time_, depart_pos_, depart_speed_;
  std::vector<int32_t> depart_lane_;

  // Insertion: vehicles due to depart wait in per-edge FIFO queues; only each queue's head is tried.
  uint32_t next_departure_ = 0;
  std::vector<std::vector<uint32_t>> queue_;  // per edge
  std::vector<uint32_t> queue_head_;          // per edge
  std::vector<uint32_t> queued_edges_;        // edges with a non-empty queue, ascending
  uint64_t waiting_ = 0;

  std::vector<uint32_t> active_;   // vehicles the passes visit, ascending
  std::vector<uint32_t> inserted_now_, scratch_;
  std::vector<TripRecord> finished_;
  double depart_delay_sum_ = 0, travel_time_sum_ = 0;

  // GPU backend (options.gpu): created at the first step; runs the passes on the device instead of pool_.
  std::unique_ptr<GpuStepper> gpu_;
};

}  // namespace lpsim

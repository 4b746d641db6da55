#pragma once
// The Simulation owns the run state of one scenario: the double-buffered lane map, the state of the vehicles
// on the road (by slot), the insertion queues and output counters. Each step() runs the kernels/ passes
// through a backend (the CPU backend is a ParallelFor loop over the same functions the CUDA kernels wrap). It
// never formats text: the runner in src/app samples it and hands the samples to the writers in converters/.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "demand/demand.hpp"
#include "engine/engine_net.hpp"
#include "engine/parallel_for.hpp"
#include "engine/samples.hpp"
#include "engine/slot_pool.hpp"
#include "kernels/gpu_stepper.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/step_view.hpp"
#include "net/network.hpp"

namespace lpsim {

struct SimulationOptions {
  double begin = 0;
  double step_length = 1.0;
  uint64_t seed = 23423;
  int threads = 1;
  double time_to_teleport = 300;  // s; <= 0: never
  // Run the step on the CUDA device (engine/device_select picks it). The device then owns the vehicle state
  // and lane maps; the host keeps the insertion queues and reads back only what outputs and teleports need.
  bool gpu = false;
  // Accumulate the per-lane edgeData/laneData counters (lane_counters()). Off when no such output is
  // requested: the passes then skip their atomics.
  bool lane_counters = true;
  // Every this many steps the vehicles on the road are renumbered by lane (slot_order), so that the passes
  // visit the vehicles of a lane, and neighbouring lanes, together; 0: never. Results do not depend on it.
  uint32_t slot_sort_interval = 16;
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
  /// edgeData/laneData counters accumulated since the start.
  const LaneCounters& lane_counters() const;
  /// Trips that ended since the last call, in order of arrival then vehicle index.
  std::vector<TripRecord> take_finished_trips();
  SummaryRow summary_row() const;

  /// Test support: recomputes the lane map from every running vehicle's footprint and reports the first
  /// cell two vehicles share or a mismatch with the engine's map ("" when consistent).
  std::string check_lane_map() const;
  /// Test support: read access to vehicle state (on the GPU backend, each step's state is fetched from the
  /// device at the first such call). A vehicle off the road reports lane -1, position and speed 0.
  uint8_t status(uint32_t v) const;
  int32_t lane(uint32_t v) const;
  float pos(uint32_t v) const;
  float speed(uint32_t v) const;
  /// What bounded the vehicle's speed in its last plan (StopReason in kernels/step_view.hpp).
  uint8_t limit_reason(uint32_t v) const;
  /// Current character of a connection's signal link (or its state when unsignalised).
  char link_state(uint32_t conn) const;
  /// Slots handed out so far: the length of the per-slot state columns (the most vehicles on the road at
  /// once, counting those that left it in the last two steps).
  uint32_t slots_used() const { return slots_.peak(); }
  /// The vehicles the passes visit (on the road, or left it this step), ascending.
  const std::vector<uint32_t>& active() const;
  /// Test support: the vehicles that teleported in the last step (and whether that ended their trip).
  const std::vector<TeleportMove>& teleports_of_last_step() const { return moves_; }
  /// The teleports that started in the last step, in vehicle order (the runner warns of each, as SUMO).
  const std::vector<TeleportEvent>& teleport_events() const { return teleport_events_; }

 private:
  VehicleView vehicle_view();
  StepParams step_params() const;
  StepContext context(const uint8_t* map_now, uint8_t* map_next);
  void step_cpu();
  void step_gpu();
  void update_signals(int64_t time_ms);
  TripView trip_view() const;
  DepartView depart_view() const;
  void enqueue_due(int64_t until_ms);
  void insert_waiting(int map_index);
  void handle_vehicle_ends(std::vector<VehicleEnd>& ends);
  void record_trip(const VehicleEnd& e, bool teleported);
  void rebuild_active(uint64_t running);
  void take_slot(SlotInit& init);
  void release_retired_slots();
  void sort_slots();
  void check_kept(size_t kept) const;
  const std::vector<uint32_t>& added_slots();
  int32_t slot_of(uint32_t v) const;
  /// Test support: vehicle v's entry of a slot column, or `off_road` while it holds no slot.
  template <class T>
  T on_road(const std::vector<T>& column, uint32_t v, T off_road) const {
    const int32_t k = slot_of(v);
    return k >= 0 ? column[static_cast<size_t>(k)] : off_road;
  }
  const std::vector<uint64_t>& active_by_vehicle() const;
  void sync_sample() const;
  void sync_host() const;

  const Network& net_;
  const Demand& demand_;
  SimulationOptions opt_;
  EngineNet engine_net_;
  ParallelFor pool_;
  int64_t time_ms_ = 0, dt_ms_ = 1000;
  uint32_t step_ = 0;
  Counts counts_;
  float max_accel_ = 2.6f, max_emergency_decel_ = 9.0f, min_decel_ = 4.5f;

  // Lane maps: map_[cur_] is the state now; the other is written by the step. On the GPU backend the
  // device's copies are the real ones (these are refreshed by sync_host for tests).
  std::vector<uint8_t> map_[2];
  int cur_ = 0;
  std::vector<char> link_state_;
  std::vector<int64_t> signal_next_switch_ms_;  // per signal: when the phase link_state_ shows ends
  std::vector<LaneApproach> approach_;
  // Reverse of the junction response: for each connection, the connections that must yield to it (CSR).
  std::vector<uint64_t> claims_, merge_requests_;
  LaneCounters lane_counters_;

  // State of the vehicles on the road, by slot (see VehicleView): as long as the slots ever used.
  SlotPool slots_;
  std::vector<uint8_t> status_, lane_change_dir_, held_at_line_, limit_reason_;
  std::vector<uint32_t> vehicle_, best_rp_, best_mask_, route_pos_, stopped_steps_, waiting_steps_,
      waiting_count_, arrival_step_, conn_rp_, trip_type_, trip_route_begin_, trip_route_size_;
  std::vector<float> speed_, pos_, old_pos_, time_loss_, route_length_, trip_speed_factor_;
  std::vector<int32_t> lane_, prev_, prev2_, old_lane_, old_prev_, old_prev2_, conn_lane_, conn_;
  // Slots whose vehicle left the road in the previous step (free after this step's passes), and in this one.
  std::vector<uint32_t> retiring_, retiring_next_;
  // This step's insertions, each with the slot it took (the GPU backend initialises them on the device).
  std::vector<SlotInit> inits_;
  std::vector<uint32_t> added_;  // added_slots()

  // Per vehicle (host only): its status off the road (pending, arrived or removed, teleporting = queued to
  // re-enter), where a teleported vehicle re-enters, and the trip counters it carries over the teleport.
  // (Its slot while on the road is looked up in the active list: slot_of.)
  std::vector<uint8_t> trip_status_;
  std::vector<uint32_t> resume_rp_;
  struct Carried {
    float route_length, time_loss;
    uint32_t waiting_steps, waiting_count;
  };
  std::unordered_map<uint32_t, Carried> carried_;
  // Plan scratch (see PlanView): one entry per position in the active list, grown with it.
  struct PlanColumns {
    std::vector<float> new_speed, new_pos, stop_pos, lookahead;
    std::vector<int32_t> new_lane, new_prev, new_prev2, claim0, claim1, stop_lane;
    std::vector<uint8_t> arrives, claim_prio;
    std::vector<uint32_t> new_rp, first_rp;
    void reserve_slots(size_t n);
    PlanView view();
  } plan_;
  // Departure records for tripinfo.
  std::vector<float> depart_time_, depart_pos_, depart_speed_;
  std::vector<int32_t> depart_lane_;

  // Insertion: vehicles due to depart wait in per-edge FIFO queues; only each queue's head is tried.
  uint32_t next_departure_ = 0;
  // Entries: vehicle index | kInsertTeleported (a teleported vehicle re-entering) | kQueuedAtLaneStart.
  struct EdgeQueue {
    std::vector<uint32_t> entries;  // those before head have been inserted
    uint32_t head = 0;
    uint32_t lanes = 0;  // the edge's car lanes (none: its departures are removed)
  };
  std::vector<EdgeQueue> queue_;        // per edge
  std::vector<uint32_t> queued_edges_;  // edges with a non-empty queue, ascending
  uint64_t waiting_ = 0;

  std::vector<uint32_t> active_;  // slots the passes visit, ascending (GPU backend: kept on the device)
  mutable std::vector<uint32_t> active_vehicles_;  // active(): their vehicles
  // The active list as vehicle << 32 | slot, ascending (active_by_vehicle()): outputs list vehicles in
  // vehicle order, whatever slots they hold.
  mutable std::vector<uint64_t> by_vehicle_;
  mutable uint32_t by_vehicle_step_ = 0xFFFFFFFFu;  // the step by_vehicle_ was sorted for
  uint32_t num_active_ = 0;
  uint32_t teleport_steps_ = 0;  // stopped steps before a teleport (0: never)
  std::vector<uint32_t> scratch_;
  // sort_slots' scratch.
  std::vector<uint32_t> slot_order_, slot_new_;
  std::vector<uint64_t> slot_keys_;
  std::vector<uint8_t> slot_bytes_;
  std::vector<uint32_t> kept_;  // active slots that stay active after the step (member: no page faults)
  // This step's queue heads handed to insertion (InsertBatch), and what came back.
  std::vector<uint32_t> batch_edge_, batch_begin_, batch_entry_, batch_rp_, batch_inserted_;
  std::vector<int32_t> batch_lane_;
  std::vector<float> batch_pos_, batch_speed_;
  std::vector<VehicleEnd> ends_;
  std::vector<TeleportMove> moves_;
  std::vector<TeleportEvent> teleport_events_;
  std::vector<TripRecord> finished_;
  double depart_delay_sum_ = 0, travel_time_sum_ = 0;

  // GPU backend (options.gpu): created at the first step from the host state, then the owner of it.
  std::unique_ptr<GpuStepper> gpu_;
  // Test and output support on the GPU backend: the step whose state was last fetched into the host arrays.
  mutable uint32_t synced_step_ = 0xFFFFFFFFu, sampled_step_ = 0xFFFFFFFFu;
};

}  // namespace lpsim

#pragma once
// The CUDA backend as host code sees it: plain C++, no CUDA types, so the engine includes it without nvcc.
// The backend an executable links defines the two functions at the end: kernels/cuda_step.cu (built by nvcc,
// or against the host emulation in tests/cuda_emulation), or src/engine/no_cuda_backend.cpp ("built without
// CUDA").
//
// The device owns the run state (vehicle columns, both lane maps, signal states, the active list, the
// edgeData counters); the host keeps the insertion queues, the trip records and the outputs. Per step only
// small things cross the bus: the step's tally and its arrivals and teleports (device to host), teleport
// decisions and the queue heads to insert (host to device), and which of those were inserted (back).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kernels/insert_vehicle.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

struct SignalTable;

/// Whether a CUDA device can run the step's kernels, and which one (or why not).
struct CudaDeviceStatus {
  bool usable = false;
  std::string description;  // usable: device name and compute capability; otherwise the reason
};

/// Array sizes the step's views do not carry themselves (they are raw pointers).
struct GpuStepSizes {
  uint32_t num_vehicles = 0;
  uint32_t num_slots = 0;  // length of the host's slot columns when the stepper is made
  uint32_t num_edges = 0;
  uint32_t num_connections = 0;
  uint32_t num_types = 0;
  uint64_t num_route_edges = 0;
};

/// The per-lane edgeData/laneData counter columns, in LaneCounters' order (src/engine/samples.hpp).
constexpr int kNumLaneCounters = 9;

/// A slot number that names no slot in the active list (GpuStepper::sort_slots).
constexpr uint32_t kNotActive = 0xFFFFFFFFu;

/// What the host learns after a step's passes.
struct GpuStepOutcome {
  uint32_t kept = 0;             // vehicles staying in the active list
  uint32_t running = 0;          // of those, running
  std::vector<VehicleEnd> ends;  // arrivals and teleports of the step, in no particular order
};

/// Runs the step on a device that holds the whole run state.
class GpuStepper {
 public:
  virtual ~GpuStepper() = default;
  /// Starts a step without waiting for it: signal states, then clear / approach / plan / commit over the
  /// active list, reading lane map `map_now` (0 or 1) and writing the other; then each vehicle's end of step.
  /// `steps_done` is the step count after this step (arrivals are stamped with it). The host may meanwhile
  /// do work that does not depend on the step's outcome.
  virtual void start_step(const StepParams& params, int map_now, uint32_t steps_done) = 0;
  /// Waits for the step started last and reports its outcome.
  virtual void finish_step(GpuStepOutcome& out) = 0;
  /// Applies the host's decisions for this step's teleports.
  virtual void apply_teleports(const std::vector<TeleportMove>& moves, uint32_t steps_done) = 0;
  /// Inserts from the batch's queue heads into lane map `map` (the host's InsertBatch arrays: inputs are
  /// read, outputs written back). `p`'s counter pointers are ignored: the device's own are used.
  virtual void insert(const InsertBatch& batch, uint32_t num_entries, const InsertParams& p, int map) = 0;
  /// Starts the vehicles of `inits` in their slots, then makes the next active list: the slots kept (their
  /// order unchanged) merged with `added` (the inits' slots, ascending, none of them kept). Both ascending,
  /// so the list stays ascending.
  virtual void rebuild_active(const std::vector<SlotInit>& inits, const std::vector<uint32_t>& added) = 0;
  /// Renumbers the active slots densely from 0 by lane, ties by slot (Simulation::sort_slots): every slot
  /// column is moved, and the active list becomes 0..n-1. Each of `slots` (numbers before) is replaced by its
  /// new number, or kNotActive if it was not in the active list.
  virtual void sort_slots(std::vector<uint32_t>& slots) = 0;
  /// The active list (slots) and each active slot's vehicle, status, lane, position and speed (outputs).
  virtual void sample(std::vector<uint32_t>& active, std::vector<uint32_t>& vehicle,
                      std::vector<uint8_t>& status, std::vector<int32_t>& lane, std::vector<float>& pos,
                      std::vector<float>& speed) = 0;
  /// Adds the device's counters to `columns` (kNumLaneCounters host columns of num_lanes each) and zeroes
  /// them.
  virtual void drain_counters(int64_t* const* columns) = 0;
  /// Copies the first `num_slots` entries of every slot column into the host arrays of `host`, lane map `map`
  /// into host.map_next, and the signal states into `link_state`.
  virtual void download_state(const StepContext& host, uint32_t num_slots, int map, char* link_state) = 0;
};

/// Whether the step can run on a GPU here: this build has the CUDA backend, and device 0 is present, has a
/// recent enough driver and can run this build's kernels. `description` names the device, or says why not
/// ("built without CUDA", a driver error...).
CudaDeviceStatus cuda_device_status();
/// A stepper on device 0 holding the network, types and trips of `host`, its state after the host's first
/// insertion (both lane maps, sizes.num_slots entries of the slot columns) and the active list (slots). With
/// `lane_counters` the passes count into the device's own counters (drain_counters), without it they skip the
/// counting. Throws std::runtime_error naming the failed CUDA call and its file:line, or, in a build without
/// CUDA, saying so.
std::unique_ptr<GpuStepper> make_cuda_stepper(const StepContext& host, const SignalTable& signals,
                                              const GpuStepSizes& sizes, const DepartView& depart,
                                              const uint8_t* other_map, int map_now,
                                              const std::vector<uint32_t>& active, bool lane_counters);

}  // namespace lpsim

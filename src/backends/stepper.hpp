#pragma once
// What a backend is to the engine: the owner of the run state of the vehicles on the road and the runner of
// the step's phases over it. The engine's Simulation (src/engine) keeps the host's bookkeeping (slots handed
// out, insertion queues, trip records) and calls the phases in one sequence for every backend:
//
//   update_signals, start_step, clear_footprints, approach, plan, commit, (count_emissions),
//   start_end_of_step (host work that does not depend on the step's outcome), finish_end_of_step,
//   apply_teleports, insert, start_vehicles, sort_slots (every so many steps)
//
// so that a later phase (a ghost exchange between approach and plan, a claims exchange before commit,
// migration after commit, a co-simulation hand-over at the end of step) is one more call in one place.
//
// The CPU backend (backends/cpu) runs each phase as a parallel loop over the kernels/ functions on host
// arrays; the CUDA backend (backends/cuda) launches the same functions as kernels on state kept on the
// device, asynchronously where nothing waits for them. The host reads the state only through fetch(): one
// explicit call, which on the CPU returns its arrays and on a device copies what is asked for.
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/insert_vehicle.hpp"
#include "kernels/lane_counters.hpp"
#include "kernels/signal_step.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

/// All the per-lane counters a backend drains (LaneCounter order, kernels/lane_counters.hpp): the traffic
/// measures, kept when a traffic output asks for them, then the emissions pass's sums, kept when an
/// emissions output does.
inline constexpr int kNumLaneCounters = int{kCountEmissionFirst} + int{kNumEmissionSums};

/// The trip table as a backend reads it (pointers into the engine's host table, valid until it changes:
/// Stepper::update_trips hands over the new ones).
struct TripTableView {
  TripView trips;
  DepartView depart;
  uint32_t num_vehicles = 0;
  uint64_t num_route_edges = 0;
  uint64_t num_stops = 0;  // entries of the stop table (TripView::stop_*), fixed for a run
};

/// Everything a backend needs to set up a run; the pointers outlive the stepper (the Simulation owns them).
struct StepperSetup {
  NetView net{};
  SignalTable signals{};
  TypeView types{};
  uint32_t num_types = 0;
  uint32_t num_edges = 0;
  uint32_t num_connections = 0;
  // Reverse of the junction response: for each connection, the connections that must yield to it (CSR).
  const uint32_t* yielder_begin = nullptr;  // [num_connections + 1]
  const uint32_t* yielder = nullptr;
  TripTableView trips;
  // Accumulate the per-lane edgeData/laneData counters; without them the passes skip their atomics.
  bool lane_counters = true;
  // Track how long fronts stand on junction lanes (StepContext::junction_stand_*), for SUMO's
  // --ignore-junction-blocker; without it the passes skip that work.
  bool junction_stands = false;
  // The vehicle types' emission columns (their sums pointer unused), and whether the emissions pass runs
  // (count_emissions) and its sums are kept.
  EmissionView emission_types{};
  bool emission_sums = false;
  int threads = 1;  // CPU backend: threads of its team
  int device = 0;   // CUDA backend: the device, counted modulo the devices present (ranks share them)
};

/// What changed in the trip table since the backend last saw it (Stepper::update_trips).
struct TripChanges {
  uint32_t first_new_vehicle = 0;     // vehicles from here on were appended
  uint64_t first_new_route_edge = 0;  // route edges from here on were appended
  std::vector<uint32_t> new_routes;   // earlier vehicles whose route_begin / route_length changed
  bool stops_moved = false;           // some stop's route position changed
};

/// What the host learns after a step's passes.
struct StepOutcome {
  uint32_t kept = 0;             // vehicles staying in the active list
  uint32_t running = 0;          // of those, running
  std::vector<VehicleEnd> ends;  // arrivals and teleports of the step, in no particular order
};

/// The state as the host reads it (outputs and tests): host pointers, valid until the next call that
/// changes the state. Slot columns are indexed by slot; `active` lists the slots the passes visit.
struct HostState {
  const uint32_t* active = nullptr;
  uint32_t num_active = 0;
  VehicleView veh{};  // Sample: vehicle, status, lane, pos, speed and stop_release only; else every column
  const uint8_t* map = nullptr;      // Full: the lane map now (the CPU backend gives it whatever was asked)
  const char* link_state = nullptr;  // Full: every signal link's character now
};

/// A footprint written into (value > 0: 1 + the speed code) or cleared from (value 0) a lane map: what one
/// part of a partitioned run sends the others that hold its lanes.
struct FootprintWrite {
  Footprint fp;
  float length;
  uint8_t value;

  /// Field by field for a state (state_archive.hpp): the padding after `value` is not part of it.
  template <class A>
  void visit_state(A& a) {
    a(fp);
    a(length);
    a(value);
  }
};

enum class StateParts {
  Sample,   // what outputs read every step: the active list and each active slot's vehicle, status, lane,
            // position, speed and stop_release (the summary's stopped vehicles)
  Columns,  // every slot column up to the slots in use (a partitioned run's exchanges)
  Full,     // everything (tests): every slot column, the lane map, the signals
};

class Stepper;

/// Makes a backend's stepper for a run: make_cpu_stepper (backends/cpu) or make_cuda_stepper (backends/cuda).
using StepperFactory = std::unique_ptr<Stepper> (*)(const StepperSetup& setup);

class Stepper {
 public:
  virtual ~Stepper() = default;

  /// Signal states at `time_ms` (a fixed-time signal is rewritten only when its phase has ended). Actuated
  /// signals read their loops from lane map `map_now`, the state at map_time_ms (dt_ms before time_ms, or
  /// time_ms itself before the first step).
  virtual void update_signals(int64_t time_ms, int64_t map_time_ms, int map_now) = 0;
  /// Begins a step over the current active list, reading lane map `map_now` (0 or 1), writing the other.
  virtual void start_step(const StepParams& params, int map_now) = 0;
  /// The passes (kernels/vehicle_step.hpp), each over the active list.
  virtual void clear_footprints() = 0;
  virtual void approach() = 0;
  virtual void plan() = 0;
  virtual void commit() = 0;
  /// The emissions pass (kernels/emission_step.hpp), after commit; only in runs set up with emission_sums.
  virtual void count_emissions() = 0;
  /// Starts each vehicle's end of step (arrived, teleporting, staying active). `steps_done` is the step count
  /// after this step. The host may do work meanwhile that does not depend on the step's outcome.
  virtual void start_end_of_step(uint32_t steps_done) = 0;
  /// Waits for the step's end and reports it (the outcome stays valid until the next step).
  virtual StepOutcome& finish_end_of_step() = 0;
  /// The host's decisions for this step's teleports.
  virtual void apply_teleports(const std::vector<TeleportMove>& moves, uint32_t steps_done) = 0;
  /// Inserts from the batch's queue heads into lane map `map` (the host's arrays: inputs read, outputs
  /// written back). The counters in `p` are ignored: the backend counts into its own.
  virtual void insert(const InsertBatch& batch, uint32_t num_entries, const InsertParams& p, int map) = 0;
  /// Starts the vehicles of `inits` in their slots (growing the slot columns to hold them), then makes the
  /// next active list: the slots kept by the last end of step (in order) merged with `added` (the inits'
  /// slots, ascending, none of them kept).
  virtual void start_vehicles(const std::vector<SlotInit>& inits, const std::vector<uint32_t>& added) = 0;
  /// Renumbers the active slots densely from 0 by lane, ties by slot (Simulation::sort_slots): every slot
  /// column is moved and the active list becomes 0..n-1. Each of `slots` (numbers before) is replaced by its
  /// new number, or kNotActive if it was not in the active list.
  virtual void sort_slots(std::vector<uint32_t>& slots) = 0;

  /// The trip table changed (vehicles appended, routes replaced): `now` is where it lies now.
  virtual void update_trips(const TripTableView& now, const TripChanges& changes) = 0;
  /// Running vehicles given a new route (their trips' new entries were handed over by update_trips first).
  virtual void set_routes(const std::vector<SlotRoute>& routes) = 0;

  /// The state for the host to read. `num_slots`: the slots handed out (Full copies that many).
  virtual const HostState& fetch(StateParts parts, uint32_t num_slots) = 0;
  // Partitioned runs (src/engine/part_link.cpp): what the exchanges between the parts read and write.
  /// Writes `writes` into lane map `map`, on the lanes `held` marks only (the others have no cells here).
  virtual void write_footprints(int map, const std::vector<FootprintWrite>& writes, const uint8_t* held) = 0;
  /// This step's entries of `lanes` in the approach table (written by the approach pass) and in the claim
  /// table (by the plan pass).
  virtual void read_approaches(const std::vector<uint32_t>& lanes, std::vector<LaneApproach>& out) = 0;
  virtual void read_claims(const std::vector<uint32_t>& lanes, std::vector<uint64_t>& out) = 0;
  /// Sets the approach entries of `lanes`; merges claims into theirs (the larger wins, as among vehicles).
  virtual void write_approaches(const std::vector<uint32_t>& lanes, const std::vector<LaneApproach>& in) = 0;
  virtual void merge_claims(const std::vector<uint32_t>& lanes, const std::vector<uint64_t>& in) = 0;
  /// Signal link characters [begin, begin + count) of the link table.
  virtual void read_link_states(uint32_t begin, uint32_t count, char* out) = 0;
  virtual void write_link_states(uint32_t begin, uint32_t count, const char* in) = 0;
  /// Vehicles that drove in from another part take `slots` (growing the slot columns): their columns as
  /// pack_vehicle wrote them, one after another; their last footprint is the part's they left to clear.
  /// start_vehicles then adds the slots to the active list.
  virtual void adopt_vehicles(const std::vector<uint32_t>& slots, const std::vector<uint8_t>& packed) = 0;
  /// Vehicles that drove into another part: their slots only clear their last footprint in the next step.
  virtual void mark_migrated(const std::vector<uint32_t>& slots) = 0;

  /// Adds the counters counted since the last call to `columns` (kNumLaneCounters columns of num_lanes, in
  /// LaneCounters' order) and starts counting from zero. Only the columns it keeps (setup's lane_counters,
  /// emission_sums) are touched: the others may be null.
  virtual void drain_counters(int64_t* const* columns) = 0;

  // Checkpoints, between steps: the run state the next step reads (slot columns of the first `num_slots`
  // slots, active list, the current lane map, signals, lane tables, counters) as bytes, and back into a
  // backend made with the same setup; every backend in the CPU backend's list and layout, so that a state
  // moves between them. std::runtime_error for bytes that do not fit the setup.
  virtual std::vector<uint8_t> save_state(uint32_t num_slots) = 0;
  virtual void load_state(const std::vector<uint8_t>& state, uint32_t num_slots) = 0;
};

}  // namespace lpsim

#pragma once
// The Simulation runs one scenario: each step() is one sequence of phases (signals, clear, approach, plan,
// commit, end of step, insertion, slot sort) that a backend (backends/stepper.hpp: CPU or CUDA) runs over the
// state it owns, and the host bookkeeping between them: the slots handed out, the insertion queues, the trip
// ledger and the counts. It never formats text: a Run (app/) samples it and hands the samples to the writers
// in converters/.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backends/cpu/cpu_stepper.hpp"
#include "backends/stepper.hpp"
#include "demand/trip_table.hpp"
#include "engine/boundary_link.hpp"
#include "engine/engine_net.hpp"
#include "engine/host_books.hpp"
#include "engine/insertion_control.hpp"
#include "engine/rerouting_device.hpp"
#include "engine/samples.hpp"
#include "engine/vehicle_commands.hpp"
#include "engine/vehicle_query.hpp"
#include "net/network.hpp"
#include "partition/part_plan.hpp"
#include "transport/transport.hpp"

namespace lpsim {

struct SimulationOptions {
  double begin = 0;        // s
  int64_t step_ms = 1000;  // the step length, in the one form the engine keeps it: whole milliseconds
  uint64_t seed = 23423;
  int threads = 1;
  double time_to_teleport = 300;  // s; <= 0: never
  // s a vehicle on a wrong lane (one that does not lead on along its route) of a road faster than
  // highway_min_speed may wait before it teleports (SUMO's --time-to-teleport.highways); <= 0: never
  double time_to_teleport_highways = 0;
  double highway_min_speed = 69.0 / 3.6;  // m/s
  double time_to_impatience = 180;  // s for a waiting vehicle's impatience to grow from 0 to 1; <= 0: never
  // SUMO's --max-depart-delay: a departure not inserted in a step that ends more than this after its depart
  // time is dropped (Counts::discarded); < 0: never. Vehicles re-entering after a teleport are never dropped.
  double max_depart_delay = -1;  // s
  // SUMO's --ignore-junction-blocker: a vehicle standing this long on a junction lane (not at a scheduled
  // stop) no longer blocks the foes crossing its path; < 0: never (the step then tracks nothing for it).
  double ignore_junction_blocker = -1;  // s
  // The backend the step runs on, chosen by the caller: the CPU's, or the CUDA device's
  // (make_cuda_stepper), which then owns the run state while the host keeps the insertion queues and the
  // trip ledger and fetches only what outputs and teleports need.
  StepperFactory backend = make_cpu_stepper;
  int gpu_device = 0;  // which of the machine's GPUs (modulo their count): a part's local rank
  // Accumulate the per-lane edgeData/laneData counters (collect_lane_counters()). Off when no such output is
  // requested: the passes then skip their atomics.
  bool lane_counters = true;
  // Run the emissions pass and keep its per-lane sums with the lane counters (emissions edgeData/laneData).
  // Off by default: the step then has no emissions pass. With volumetric_fuel, fuel is summed in nl, not ng
  // (SUMO's --emissions.volumetric-fuel).
  bool emission_sums = false;
  bool volumetric_fuel = false;
  // Every this many steps the vehicles on the road are renumbered by lane (slot_order), so that the passes
  // visit the vehicles of a lane, and neighbouring lanes, together; 0: never. Results do not depend on it.
  uint32_t slot_sort_interval = 16;
  // One part of a partitioned run (both set, or neither: the whole network in one part). The plan and the
  // transport outlive the Simulation. Part 0 is the one the outputs read (it gathers the others' samples);
  // every other part runs serve_part() until part 0's Simulation is destroyed.
  const PartPlan* part = nullptr;
  Transport* transport = nullptr;
  // A part's process: the signal it received and has not acted on (0: none). Each part reports it to part 0
  // with the step, so that a job whose ranks are signalled one by one stops together
  // (BoundaryLink::signal()).
  std::function<int()> pending_signal;
  // Co-simulation: the lanes another simulator drives, 1 per lane of the network (null: none; outlives the
  // Simulation; one part only). A vehicle whose front reaches one, or whose trip departs on one, leaves this
  // simulation (Simulation::hand_outs()).
  const std::vector<uint8_t>* outside_lanes = nullptr;
  // SUMO's rerouting device: when the vehicles that have it (Demand::rerouting) re-route, and on what speeds.
  ReroutingOptions rerouting;
};

class OutsideLink;  // engine/outside_link.hpp

/// The summary's sums over the running vehicles (speeds in units of 2^-24 m/s, and of the desired speed).
struct SpeedSums {
  uint64_t running = 0, halting = 0, stopped = 0;
  int64_t speed = 0, relative = 0;
};

/// The stop table's durations and until times in steps (TripView::stop_duration_steps, stop_until_step).
struct StopSteps {
  std::vector<uint32_t> duration, until;
};

class Simulation {
 public:
  /// The simulation owns its trips (a TripTable made of `demand`), which can grow while it runs.
  Simulation(const Network& net, Demand demand, const SimulationOptions& options);
  ~Simulation();

  void step();
  /// A part other than part 0 of a partitioned run: steps and answers part 0's requests until part 0 ends
  /// the run (its Simulation is destroyed). A TransportError when part 0 or another part fails.
  void serve_part();
  double time() const { return static_cast<double>(time_ms_) / 1000.0; }
  int64_t time_ms() const { return time_ms_; }
  /// The step length in seconds (options.step_ms / 1000).
  double step_length() const { return static_cast<double>(opt_.step_ms) / 1000.0; }
  uint32_t step_index() const { return step_; }
  /// Nothing running, nothing waiting to be inserted and no future departure.
  bool finished() const;

  /// The trips: those loaded and those added since (ids and types for the outputs).
  const Demand& demand() const { return trips_.demand(); }
  /// The index of the trip (vehicle) with id `id`, or -1; its id is demand().vehicle_id[index].
  int64_t vehicle_index(const std::string& id) const { return trips_.find(id); }
  /// Applies a driver's commands between steps, in order (engine/vehicle_commands.hpp), and says what became
  /// of each:
  /// - Add: a trip that queues for insertion at its first edge when its depart time has come (at once if it
  ///   has passed); its outcome names its index. Refused when TripTable::add refuses it.
  /// - SetRoute: the vehicle drives `edges` from now on, the first of them the edge it is on (a running
  ///   vehicle: on an internal lane, the edge it came from, and the second the one it is entering) or queued
  ///   at (waiting to depart or to re-enter after a teleport), each edge reachable from the one before.
  /// - Remove: the vehicle leaves the run. On the road (or teleporting) its trip ends where it is, counted
  ///   as arrived with a trip record marked removed (SUMO's TraCI remove); before it departed it is
  ///   cancelled (summary: ended, not arrived).
  /// In a partitioned run a collective call (part 0's commands count; every part returns the outcomes).
  std::vector<CommandOutcome> apply_commands(const std::vector<VehicleCommand>& commands);

  using Counts = RunCounts;
  /// The run's counts (in a partitioned run, part 0 sums the parts').
  const Counts& counts() const;

  /// Positions of running vehicles now (in a partitioned run part 0 gathers every part's: a collective call
  /// that the other parts serve).
  void sample_fcd(FcdFrame& frame);
  /// edgeData/laneData counters accumulated since the start (the emission sums only with emission_sums),
  /// collected from the backend; in a partitioned run part 0 gathers every part's (its call is a collective
  /// step that the other parts serve).
  const LaneCounters& collect_lane_counters();
  /// Wall time spent in step() so far (in a partitioned run part 0's, which waits for the others).
  double step_seconds() const { return step_seconds_; }
  /// Trips that ended since the last call, in order of arrival then vehicle index.
  std::vector<TripRecord> take_finished_trips();
  /// Records of the trips that have not ended, for SUMO's tripinfo write-unfinished, as of `end` (the time
  /// SUMO's run ends): every vehicle on the road or teleporting (kTripRunning, its counters so far), and with
  /// `undeparted` every trip due by `end` that never departed (kTripUndeparted). In vehicle order; in a
  /// partitioned run part 0 gathers every part's (the others return nothing).
  std::vector<TripRecord> unfinished_trips(double end, bool undeparted);
  /// The summary's row now (in a partitioned run a collective call, as sample_fcd()).
  SummaryRow summary_row();

  /// Checkpoints, between steps: the run's whole state as bytes (versioned and checked by the caller), and
  /// back into a Simulation made from the same scenario and options, which then steps on exactly as the
  /// saved one would have, on either backend. In a partitioned run both are collective calls: part 0 gathers
  /// every part's state (the others return nothing) and hands each part its own back, re-cut for them when
  /// other parts saved it (state_recut.hpp). std::runtime_error for what has no saved state yet (a
  /// co-simulation) and, naming `what`, for a state that does not fit this run.
  std::vector<uint8_t> save_state();
  void load_state(const std::vector<uint8_t>& state, const std::string& what);

  /// Test support: recomputes the lane map from every running vehicle's footprint and reports the first
  /// cell two vehicles share or a mismatch with the engine's map ("" when consistent).
  std::string check_lane_map() const;
  /// The vehicles' state now, read by vehicle (this part's vehicles in a partitioned run): every slot column
  /// (StateParts::Columns), or with the signals and the lane map too (Full). Valid until the state changes
  /// (the next step, apply_commands()).
  VehicleQuery query(StateParts parts = StateParts::Columns) const;
  /// Slots handed out so far: the length of the per-slot state columns (the most vehicles on the road at
  /// once, counting those that left it in the last two steps).
  uint32_t slots_used() const { return books_.slots.peak(); }
  /// The vehicles the passes visit (on the road, or left it this step), ascending.
  const std::vector<uint32_t>& active() const;
  /// Test support: the vehicles that teleported in the last step (and whether that ended their trip).
  const std::vector<TeleportMove>& teleports_of_last_step() const { return moves_; }
  /// The teleports that started in the last step, in vehicle order (the runner warns of each, as SUMO).
  const std::vector<TeleportEvent>& teleport_events() const;

  /// The co-simulation's boundary (SimulationOptions::outside_lanes): the vehicles handed out to the other
  /// simulator and taken back from it. std::logic_error in a run without outside lanes.
  OutsideLink& outside_link();
  /// Every trip's account off the road (a vehicle's status while it holds no slot: kMigrated while handed
  /// out to the other simulator), its departure record (lane -1: it has not departed here) and the counters
  /// a teleporting or handed-out vehicle carries.
  const TripLedger& ledger() const { return books_.ledger; }
  /// Where this run's lanes meet lanes driven elsewhere; in a partitioned run part 0's has every part's
  /// stats as of the last step (PartStats) and the first signal another part's process reported.
  const BoundaryLink& link() const { return *link_; }

 private:
  void sync_trips();
  std::vector<TripRecord> own_unfinished_trips(double end, bool undeparted) const;
  void handle_vehicle_ends(std::vector<VehicleEnd>& ends);
  void sort_slots();
  // The rerouting device's new routes into the trip table, and into the slots of those on the road.
  void apply_new_routes(const std::vector<NewRoute>& routes);
  template <class A>
  void visit_state(A& a, std::vector<uint8_t>& backend);
  // The summary's sums over every part's running vehicles (in a partitioned run a collective call).
  SpeedSums speed_sums();
  /// The backend's state (a device backend copies it at most once per change of its state).
  const HostState& state(StateParts parts) const { return stepper_->fetch(parts, books_.slots.size()); }
  const std::vector<uint64_t>& active_by_vehicle() const;

  const Network& net_;
  TripTable trips_;
  SimulationOptions opt_;  // the step length in opt_.step_ms
  EngineNet engine_net_;
  int64_t time_ms_ = 0;
  uint32_t step_ = 0;
  double step_seconds_ = 0;
  // The step's parameters that hold for the whole run (the step and its time are set per step).
  StepParams params_{};
  int cur_ = 0;  // the lane map the state is in (the next step reads it)

  // Host bookkeeping: slots handed out, the queues, every trip's account, the counts.
  HostBooks books_;
  StopSteps stop_steps_;
  std::vector<TeleportMove> moves_;
  LaneCounters lane_counters_;
  std::vector<double> fuel_divisor_;  // per type: EmissionView::fuel_divisor

  std::unique_ptr<Stepper> stepper_;  // made from the members above, gone before them
  // Where this run's lanes meet lanes driven elsewhere (other parts, another simulator); made from the
  // stepper and the books, gone before them.
  std::unique_ptr<BoundaryLink> link_;
  std::unique_ptr<InsertionControl> insertion_;  // made from the link and the books, gone before them
  std::unique_ptr<ReroutingDevice> reroute_;     // null: no vehicle has the rerouting device

  // What outputs and tests derive from the backend's state, kept per version of it: the state changes in
  // step(), apply_commands() and the constructor's insertions, each counting a new version.
  uint64_t version_ = 0;
  struct ActiveOrder {
    // The active list as vehicle << 32 | slot, ascending (active_by_vehicle()): outputs list vehicles in
    // vehicle order, whatever slots they hold.
    std::vector<uint64_t> keys;
    uint64_t version = ~uint64_t{0};  // the state version keys were sorted for
    std::vector<uint32_t> vehicles;   // active(): their vehicles
  };
  mutable ActiveOrder active_order_;
};

}  // namespace lpsim

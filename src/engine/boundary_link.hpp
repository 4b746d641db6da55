#pragma once
// Where the lanes a Simulation drives meet lanes driven elsewhere: by the other parts of a partitioned run
// (part_link.hpp) or by another simulator in a co-simulation (outside_link.hpp). Simulation::step calls its
// link at the step's named points and never asks which kind it has; the link of a run of one part alone,
// this base class, does nothing there and answers the run's totals from the run's own books.
//
// Both kinds of boundary work alike: what elsewhere has on lanes this side holds is written into this side's
// lane map and erased before that map is next written (each side's clear pass erases only its own
// vehicles'); a vehicle whose front reaches a lane driven elsewhere leaves at the end of that step
// (hand_out), its last footprint erased here like the others.
#include <cstdint>
#include <vector>

#include "backends/stepper.hpp"
#include "demand/trip_table.hpp"
#include "engine/engine_net.hpp"
#include "engine/host_books.hpp"
#include "engine/state_archive.hpp"
#include "net/network.hpp"
#include "transport/transport.hpp"

namespace lpsim {

/// What a boundary link reaches of the run it belongs to (each outlives the link).
struct LinkScope {
  const Network& net;
  const EngineNet& engine_net;
  const TripTable& trips;
  Stepper& stepper;
  HostBooks& books;
};

/// What part 0 asks the other parts of a partitioned run to do with it (Simulation::serve_part).
enum PartRequest : uint8_t {
  kRequestStep = 1,
  kRequestSample = 2,
  kRequestCounters = 3,
  kRequestSpeedSums = 4,
  kRequestStop = 5,
  kRequestUnfinished = 6,
  kRequestSaveState = 7,
  kRequestLoadState = 8,
  kRequestCommands = 9
};

/// What one part of a partitioned run spent and sent, cumulative.
struct PartStats {
  uint64_t steps = 0;
  uint64_t vehicle_updates = 0;
  uint64_t migrations = 0;      // vehicles that drove out of it into another part
  uint64_t bytes_sent = 0;      // by the step's exchanges
  uint64_t rounds = 0;          // the step's exchanges
  double step_seconds = 0;      // wall time of its steps, exchanges included
  double exchange_seconds = 0;  // of that, in the step's exchanges (waiting for the others included)
  double gather_seconds = 0;    // wall time answering part 0's requests and reporting to it
};

/// A running vehicle as the outputs sample it.
struct SampleEntry {
  uint32_t vehicle;
  int32_t lane;
  float pos, speed;
  uint32_t stop_release;
};

class BoundaryLink {
 public:
  explicit BoundaryLink(const LinkScope& run) : run_(run) {}
  virtual ~BoundaryLink() = default;
  BoundaryLink(const BoundaryLink&) = delete;
  BoundaryLink& operator=(const BoundaryLink&) = delete;

  // --- The step's points, in the order it reaches them. ---
  /// Before anything: part 0 asks the other parts to step with it.
  virtual void begin_step() {}
  /// After the signals were updated (and at the begin time): signals others run that this side reads.
  virtual void after_signals() {}
  /// After the clear pass, before the step writes lane map `map`: what was written into it from elsewhere is
  /// erased, and what elsewhere has there at the end of this step is written.
  virtual void before_writing(int map) { erase_foreign(map); }
  /// After the approach pass of step `step`, which read lane map `read_map`.
  virtual void after_approach(uint32_t /*step*/, int /*read_map*/) {}
  /// After the plan pass of step `step`: the claims on lanes others hold.
  virtual void after_plan(uint32_t /*step*/) {}
  /// After the end of step (teleports applied), which wrote lane map `map`: the vehicles whose front is on a
  /// lane driven elsewhere leave (hand_out), and what comes in from elsewhere arrives.
  virtual void after_end_of_step(int /*map*/) {}
  /// After the insertions into lane map `map` (and at the begin time).
  virtual void after_insertion(int /*map*/) {}
  /// Appends to `added` the slots taken by vehicles that came in from elsewhere in this step; returns how
  /// many came in less how many left.
  virtual int64_t settle_crossings(std::vector<uint32_t>& added);
  /// The end of a step that took `seconds` of wall time so far.
  virtual void count_step(double /*seconds*/) {}
  /// After a step (and at the begin time): what part 0 sums for the run as a whole.
  virtual void report() {}

  // --- Where a trip goes. ---
  /// Edge `edge` is this part's: it queues the departures and re-entries there.
  virtual bool owns_edge(uint32_t /*edge*/) const { return true; }
  /// Vehicles are queued at `edge` here: this part's, and not driven by another simulator.
  virtual bool queues_at(uint32_t edge) const { return owns_edge(edge); }
  /// Trip v is due to depart at `edge`: true when it departs elsewhere, which then has it.
  virtual bool takes_departure(uint32_t /*v*/, uint32_t /*edge*/) { return false; }
  /// A vehicle that teleported (`end`) re-enters at route position `rp` on `edge`: true when the link queues
  /// it (elsewhere, or here in an order common to every part).
  virtual bool takes_reentry(const VehicleEnd& /*end*/, uint32_t /*rp*/, uint32_t /*edge*/) { return false; }
  /// Whether the step's departures go to departed(), for part 0 to sum them in the order one part would.
  virtual bool records_departures() const { return false; }
  virtual void departed(uint64_t /*order*/, double /*delay*/) {}

  // --- The run as a whole: in a partitioned run part 0 answers for every part. ---
  virtual int parts() const { return 1; }
  /// This side's outputs are the run's: part 0, or a run of one part.
  virtual bool leads() const { return true; }
  virtual bool idle() const { return run_.books.idle(); }
  virtual const RunCounts& counts() const { return run_.books.counts; }
  virtual std::vector<TripRecord> take_finished() { return run_.books.ledger.take_finished(); }
  virtual const std::vector<TeleportEvent>& teleport_events() const { return run_.books.teleport_events; }
  virtual double depart_delay_sum() const { return run_.books.ledger.depart_delay_sum(); }
  virtual double travel_time_sum() const { return run_.books.ledger.travel_time_sum(); }
  /// Part 0 of a partitioned run: every part's stats as of the last step (empty in a run of one part).
  virtual std::vector<PartStats> part_stats() const { return {}; }
  /// Part 0 of a partitioned run: the first signal another part's process reported (in part order), once
  /// one did; 0 before, and in a run of one part.
  virtual int signal() const { return 0; }
  /// The running vehicles of the whole run as of state `version`, ascending by vehicle.
  virtual const std::vector<SampleEntry>& running_vehicles(uint64_t version);

  // --- Collective calls: every part makes them together; in one part they return at once. ---
  /// Part 0 asks the others to serve `what` with it.
  virtual void request(PartRequest /*what*/) {}
  /// A part other than part 0: what part 0 asks next.
  virtual PartRequest next_request();
  /// Every part's `mine`, in part order, at part 0; nothing at the other parts.
  virtual std::vector<Bytes> gather(const Bytes& mine, const char* /*what*/) { return {mine}; }
  /// Every part's `mine`, in part order, at every part.
  virtual std::vector<Bytes> allgather(const Bytes& mine, const char* /*what*/) { return {mine}; }
  /// Part 0's `root` at every part.
  virtual Bytes broadcast(const Bytes& root, const char* /*what*/) { return root; }
  /// Part 0's `each[p]` at part p (`each` is read at part 0 only).
  virtual Bytes scatter(const std::vector<Bytes>& each, const char* /*what*/) { return each.at(0); }

  // --- Checkpoints, between steps: what the link carries from one step to the next (nothing in a run of
  // one part); `map` is the lane map the last step wrote, the one a state holds. ---
  virtual void save_state(StateOut& /*a*/, int /*map*/) {}
  virtual void load_state(StateIn& /*a*/, int /*map*/) {}

  // --- Commands, between steps. ---
  /// A vehicle a command removed from the road: its footprint `fp` leaves lane map `map` (the one the next
  /// step reads) on the lanes this side holds, and from what this side has still to send of it.
  virtual void erase_removed(int map, const FootprintWrite& fp);

  /// Footprints written into lane map `map` from elsewhere and not yet erased (value 0: their erasures).
  const std::vector<FootprintWrite>& foreign_footprints(int map) const { return foreign_[map]; }

 protected:
  /// Writes `writes` into lane map `map` (on the lanes this side holds) and keeps their erasures.
  void write_foreign(int map, const std::vector<FootprintWrite>& writes);
  /// Erases what was written into lane map `map` from elsewhere, and the last footprints of the vehicles that
  /// left for elsewhere (their slots no longer clear them).
  void erase_foreign(int map);
  /// The one hand-out path: visit(state, slot, footprint, length) sees every running vehicle of lane map
  /// `map`'s state in slot order, and each one it returns true for leaves: its slot stops (marked migrated,
  /// freed after the next step) and its footprint is erased when `map` is next written. The slots that left.
  template <class Visit>
  std::vector<uint32_t> hand_out(int map, Visit visit);
  /// This side's running vehicles, in slot order.
  std::vector<SampleEntry> own_running() const;
  /// The footprints written from elsewhere into lane map `map` (the one a state holds) and not yet erased.
  /// The other map's are not: a resumed run starts with that map cleared.
  template <class A>
  void visit_foreign(A& a, int map) {
    a(foreign_[map]);
    if constexpr (A::kReads) foreign_[1 - map].clear();
  }

  LinkScope run_;
  const uint8_t* held_lanes_ = nullptr;  // 1 per lane this side writes into its lane map
  uint32_t left_ = 0;                    // vehicles that left in this step
  std::vector<SampleEntry> sample_;      // running_vehicles(), as of state version sample_version_
  uint64_t sample_version_ = ~uint64_t{0};

 private:
  std::vector<FootprintWrite> foreign_[2];
};

template <class Visit>
std::vector<uint32_t> BoundaryLink::hand_out(int map, Visit visit) {
  const HostState& st = run_.stepper.fetch(StateParts::Columns, run_.books.slots.size());
  const float* length = run_.trips.demand().types.length.data();
  std::vector<uint32_t> gone;
  for (uint32_t i = 0; i < st.num_active; ++i) {
    const uint32_t k = st.active[i];
    if (st.veh.status[k] != kRunning) continue;
    const Footprint fp = current_footprint(st.veh, k);
    const float len = length[st.veh.trip_type[k]];
    if (!visit(st, k, fp, len)) continue;
    foreign_[map].push_back(FootprintWrite{fp, len, 0});
    gone.push_back(k);
  }
  if (!gone.empty()) run_.stepper.mark_migrated(gone);
  for (const uint32_t k : gone) run_.books.retiring_next.push_back(k);
  left_ = static_cast<uint32_t>(gone.size());
  return gone;
}

}  // namespace lpsim

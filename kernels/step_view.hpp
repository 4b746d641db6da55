#pragma once
// Plain views the step kernels work on: raw pointers to structure-of-arrays columns and sizes, 32-bit
// values only, so the same code runs on the host (CPU backend) and, compiled by nvcc, on the device.
// The engine (src/engine) owns the arrays and fills these views; kernels never allocate.
#include <stdint.h>

#include "kernels/emissions.hpp"
#include "kernels/hd.hpp"

namespace lpsim {

/// The network, read-only during a run.
struct NetView {
  uint32_t num_lanes;
  // [num_lanes+1] first cell of each lane in the lane map; [num_lanes]: the map's cells. A part of a
  // partitioned run holds only some lanes' cells (its own, then its ghosts'): the others are never read.
  const uint32_t* lane_cell_begin;
  const uint32_t* lane_num_cells;  // cells of each lane
  const float* lane_length;        // m
  const float* lane_speed;         // m/s
  const uint32_t* lane_edge;
  const uint8_t* lane_internal;     // 1: junction-internal lane
  const int32_t* lane_left;         // lane to the left on the same edge (index+1), -1 if none
  const int32_t* lane_right;        // lane to the right on the same edge, -1 if none
  const uint8_t* lane_rank;         // rank among the edge's vehicle lanes (0: rightmost), 255 from there on
  const uint32_t* lane_conn_begin;  // [num_lanes+1] outgoing connections
  const uint32_t* edge_first_lane;
  const uint8_t* edge_num_lanes;
  const uint32_t* conn_to_lane;
  const int32_t* conn_via_lane;  // -1: direct
  const uint32_t* conn_to_edge;
  const uint32_t* conn_from_lane;
  const int32_t* conn_signal;  // -1: not signalised
  const int16_t* conn_link_index;
  const char* conn_state;          // SUMO connection state (M m = s w ...)
  const uint32_t* conn_foe_begin;  // [num_conns+1] connections this one must yield to (junction response)
  const uint32_t* conn_foe;
  // Per conn_foe entry: cells of the foe's via lane, from its start, within which a vehicle still blocks the
  // connection (up to where the two paths cross, plus clearance).
  const uint16_t* conn_foe_block_cells;
  const uint8_t* conn_keep_clear;     // 1: entered only with room to leave the junction (Network's doc)
  const uint32_t* signal_link_begin;  // [num_signals+1] offset of each signal's links in link_state
  const uint32_t* lane_permissions;   // vClass mask of each lane (src/core/vclass.hpp)
  // Speed limits by vehicle class (<restriction> of the edge's type): [lane_restriction_begin[l],
  // lane_restriction_begin[l+1]) in restriction_vclass/restriction_speed. Null: none anywhere.
  const uint32_t* lane_restriction_begin;
  const uint32_t* restriction_vclass;
  const float* restriction_speed;
};

/// What a NetView column is indexed by: its length follows from the counts and the begin tables.
enum class NetExtent : uint8_t {
  kLanes,
  kLanesPlusOne,
  kEdges,
  kConnections,
  kConnectionsPlusOne,
  kFoes,            // conn_foe_begin[connections]
  kSignalsPlusOne,  // the signal program's link_begin
  kRestrictions     // lane_restriction_begin[lanes]; the three restriction columns are null when none
};

/// The one list of the network columns (as visit_vehicle_columns): f(extent, column...) for each pointer
/// column of every view given (num_lanes is not one).
template <class F, class... Nets>
void visit_net_columns(F&& f, Nets&... n) {
  f(NetExtent::kLanesPlusOne, n.lane_cell_begin...);
  f(NetExtent::kLanes, n.lane_num_cells...);
  f(NetExtent::kLanes, n.lane_length...);
  f(NetExtent::kLanes, n.lane_speed...);
  f(NetExtent::kLanes, n.lane_edge...);
  f(NetExtent::kLanes, n.lane_internal...);
  f(NetExtent::kLanes, n.lane_left...);
  f(NetExtent::kLanes, n.lane_right...);
  f(NetExtent::kLanes, n.lane_rank...);
  f(NetExtent::kLanesPlusOne, n.lane_conn_begin...);
  f(NetExtent::kEdges, n.edge_first_lane...);
  f(NetExtent::kEdges, n.edge_num_lanes...);
  f(NetExtent::kConnections, n.conn_to_lane...);
  f(NetExtent::kConnections, n.conn_via_lane...);
  f(NetExtent::kConnections, n.conn_to_edge...);
  f(NetExtent::kConnections, n.conn_from_lane...);
  f(NetExtent::kConnections, n.conn_signal...);
  f(NetExtent::kConnections, n.conn_link_index...);
  f(NetExtent::kConnections, n.conn_state...);
  f(NetExtent::kConnectionsPlusOne, n.conn_foe_begin...);
  f(NetExtent::kFoes, n.conn_foe...);
  f(NetExtent::kFoes, n.conn_foe_block_cells...);
  f(NetExtent::kConnections, n.conn_keep_clear...);
  f(NetExtent::kSignalsPlusOne, n.signal_link_begin...);
  f(NetExtent::kLanes, n.lane_permissions...);
  f(NetExtent::kLanesPlusOne, n.lane_restriction_begin...);
  f(NetExtent::kRestrictions, n.restriction_vclass...);
  f(NetExtent::kRestrictions, n.restriction_speed...);
}
static_assert(sizeof(NetView) == 29 * sizeof(void*), "NetView changed: update visit_net_columns");

/// The speed limit of lane `l` for a vehicle of vClass mask `vclass`: its class's restriction where the
/// lane's edge type has one, else the lane's speed (SUMO's MSLane::getVehicleMaxSpeed). The mask must
/// equal the restriction's, so "ignoring" (every bit) matches only a restriction for "ignoring".
LPSIM_HD float lane_speed_for(const NetView& net, uint32_t l, uint32_t vclass) {
  if (net.lane_restriction_begin != nullptr)
    for (uint32_t i = net.lane_restriction_begin[l]; i < net.lane_restriction_begin[l + 1]; ++i)
      if (net.restriction_vclass[i] == vclass) return net.restriction_speed[i];
  return net.lane_speed[l];
}

/// Vehicle types, read-only.
struct TypeView {
  const float* length;
  const float* min_gap;
  const float* accel;
  const float* decel;
  const float* emergency_decel;
  const float* max_speed;
  const float* desired_max_speed;  // SUMO's desiredMaxSpeed, before the speed factor (FLT_MAX: none)
  const float* tau;
  const float* delta;
  const float* sigma;           // Krauss's dawdling
  const uint8_t* model;         // CarFollowModel (kernels/idm.hpp)
  const uint32_t* vclass_mask;  // the type may use lanes whose permissions share a bit with it
};

/// The one list of the type columns (as visit_vehicle_columns): f(column...) for each, of every view given,
/// a TypeView or the demand's VehicleTypes, whose columns have the same names.
template <class F, class... Types>
void visit_type_columns(F&& f, Types&... t) {
  f(t.length...);
  f(t.min_gap...);
  f(t.accel...);
  f(t.decel...);
  f(t.emergency_decel...);
  f(t.max_speed...);
  f(t.desired_max_speed...);
  f(t.tau...);
  f(t.delta...);
  f(t.sigma...);
  f(t.model...);
  f(t.vclass_mask...);
}
static_assert(sizeof(TypeView) == 12 * sizeof(void*), "TypeView changed: update visit_type_columns");

/// The per-lane sums of an emissions edgeData/laneData output, column by column (Pollutant order for the
/// masses). Integers, so that the sums do not depend on the order vehicles add in; units fine enough that
/// rounding each step's share stays far below the output's precision and coarse enough that a lane's sum
/// over a long run of a large network stays far within 2^63 (ng: 9,200 t of CO2 on one lane).
enum EmissionSum : int {
  kEmissionMicroseconds,  // vehicle-time on the lane (any part of the body on it), us
  kEmissionMicrometres,   // distance driven while on it (time on it x speed), um
  kEmissionNanograms,     // first of kNumPollutants masses, ng (fuel by volume: nl)
  kNumEmissionSums = kEmissionNanograms + kNumPollutants
};

/// The sum column of the mass of `pollutant` (Pollutant).
LPSIM_HD constexpr int emission_mass_sum(int pollutant) { return kEmissionNanograms + pollutant; }

/// Vehicle types' emission parameters (read-only) and the per-lane sums the emissions pass adds to.
struct EmissionView {
  const uint8_t* model;      // EmissionModel (kernels/emissions.hpp)
  const double* coeff;       // kCoefficientsPerClass per type
  const double* coast_incl;  // CoastingParams per type
  const double* coast_mass_term;
  const double* fuel_divisor;   // per type: kHbefaScale, or times the fuel density for fuel by volume
  const double* shut_off_stop;  // s: the engine is off at a scheduled stop planned longer than this
  // kNumEmissionSums columns of num_lanes each (column k from sums + k * num_lanes); null: not counted.
  int64_t* sums;
  uint32_t num_lanes;
};

/// The one list of the emission view's per-type columns (as visit_type_columns): f(values per type,
/// column...) for each, of every view given (the sums are not one).
template <class F, class... Views>
void visit_emission_columns(F&& f, Views&... e) {
  f(1, e.model...);
  f(kCoefficientsPerClass, e.coeff...);
  f(1, e.coast_incl...);
  f(1, e.coast_mass_term...);
  f(1, e.fuel_divisor...);
  f(1, e.shut_off_stop...);
}
static_assert(sizeof(EmissionView) == 8 * sizeof(void*),
              "EmissionView changed: update visit_emission_columns");

/// Per-vehicle static data, read-only.
struct TripView {
  const uint32_t* type;
  const uint32_t* route_begin;
  const uint32_t* route_length;
  const uint32_t* route_edges;
  const float* speed_factor;
  const uint8_t* arrival_pos_kind;  // ArrivalPos
  const float* arrival_pos;
  // Scheduled stops (<stop>) of all trips, one table for the run; a slot holds the range of its trip's
  // that it has still to make (VehicleView::next_stop, stops_end).
  const uint32_t* stop_route_pos;       // position in the trip's route of the stop's edge
  const uint32_t* stop_lane;            // the lane it stops on
  const float* stop_start;              // m: the stretch of the lane within which it stops
  const float* stop_end;                // m: the front stops here, or behind vehicles stopped there
  const uint32_t* stop_duration_steps;  // steps it stands at least
  const uint32_t* stop_until_step;      // step before which it does not leave (0: none)
};

/// What a TripView column is indexed by.
enum class TripExtent : uint8_t { kTrips, kRouteEdges, kStops };

/// The one list of the trip columns (as visit_net_columns): f(extent, column...) for each, of every view
/// given.
template <class F, class... Trips>
void visit_trip_columns(F&& f, Trips&... t) {
  f(TripExtent::kTrips, t.type...);
  f(TripExtent::kTrips, t.route_begin...);
  f(TripExtent::kTrips, t.route_length...);
  f(TripExtent::kRouteEdges, t.route_edges...);
  f(TripExtent::kTrips, t.speed_factor...);
  f(TripExtent::kTrips, t.arrival_pos_kind...);
  f(TripExtent::kTrips, t.arrival_pos...);
  f(TripExtent::kStops, t.stop_route_pos...);
  f(TripExtent::kStops, t.stop_lane...);
  f(TripExtent::kStops, t.stop_start...);
  f(TripExtent::kStops, t.stop_end...);
  f(TripExtent::kStops, t.stop_duration_steps...);
  f(TripExtent::kStops, t.stop_until_step...);
}
static_assert(sizeof(TripView) == 13 * sizeof(void*), "TripView changed: update visit_trip_columns");

// kMigrated: the vehicle drove into another part of a partitioned run, which runs it from there on; its
// slot here stays one more step to clear its last footprint, as after an arrival.
enum VehicleStatus : uint8_t { kPending = 0, kRunning = 1, kArrived = 2, kTeleporting = 3, kMigrated = 4 };

/// Where a vehicle's body lies: front bumper `pos` on `lane`, the tail continuing back over `prev` and
/// `prev2` (the lanes driven before) when the vehicle is longer than what lies ahead of their ends.
struct Footprint {
  int32_t lane;  // -1: none (not on the road)
  int32_t prev;
  int32_t prev2;
  float pos;
};

/// VehicleView::emission_flags. After a lane change SUMO stops counting the vehicle on the lanes its back
/// still covers (its back's lanes drop it): the low bits count how many of its tail lanes (prev, then prev2)
/// it entered since its last lane change, and so still count (2: both; a lane change sets 0, each lane
/// entered adds one).
enum EmissionFlags : uint8_t {
  kEmissionTailLanes = 3,     // mask of the tail lanes still counted: 0, 1 or 2
  kEmissionAtStop = 4,        // standing at a scheduled stop (its engine decided when it got there)
  kEmissionEngineOff = 8,     // ... with the engine off for the whole stop
  kEmissionFlagsOnEntry = 2,  // a vehicle entering the road: its tail lanes count
};

/// Mutable state of the vehicles on the road, indexed by slot: a vehicle takes a free slot when it is
/// inserted and gives it back one step after it leaves the road (the step that clears its last footprint),
/// so these columns scale with the vehicles running, not with the whole demand. A vehicle's thread is the
/// only one that reads or writes its slot; other vehicles see it only through the lane map, so these need no
/// double buffer.
struct VehicleView {
  uint8_t* status;
  uint32_t* vehicle;    // the vehicle in the slot (index into TripView, RNG key, claim tie-break)
  uint32_t* route_pos;  // index in the route of the current (or, on an internal lane, last) normal edge
  float* speed;
  int32_t* lane;
  int32_t* prev;
  int32_t* prev2;
  float* pos;
  int32_t* old_lane;  // footprint one step ago (cleared from the lane-map buffer being written)
  int32_t* old_prev;
  int32_t* old_prev2;
  float* old_pos;
  uint32_t* stopped_steps;  // consecutive steps below 0.1 m/s (teleport clock)
  uint32_t* waiting_steps;  // all steps below 0.1 m/s (tripinfo waitingTime)
  uint32_t* waiting_count;  // times it came to a halt
  float* time_loss;         // s
  float* route_length;      // m driven
  uint32_t* arrival_step;
  uint8_t* lane_change_dir;  // last lane change: 0 none, 1 left, 2 right (for outputs)
  uint8_t* held_at_line;     // last plan stopped at the lane end for a red light or a full next lane
  uint8_t* limit_reason;     // what bounded the last plan's speed (StopReason), for diagnostics and tests
  // Cache of best lanes (a pure function of vehicle, route position and next stop): kBestLaneEntries per
  // slot, slot k's at [k * kBestLaneEntries, (k + 1) * kBestLaneEntries).
  uint32_t* best_rp;    // route position an entry was computed for (0xFFFFFFFF: none yet)
  uint32_t* best_mask;  // best lanes of that route edge
  // Cache of the connection taken at the end of the current lane (a pure function of vehicle, lane and route
  // position), which a vehicle waiting at its lane's end asks for every step.
  int32_t* conn_lane;  // lane the entry was computed for (-1: none yet)
  uint32_t* conn_rp;   // route position it was computed for
  int32_t* conn;       // choose_connection's result there
  // The trip's fields the passes read, copied from TripView when the slot is taken, so that a pass reads
  // them next to the rest of the slot instead of chasing the vehicle index into the whole demand's columns.
  uint32_t* trip_type;
  float* trip_speed_factor;
  uint32_t* trip_route_begin;  // first of its route's edges in TripView::route_edges
  uint32_t* trip_route_size;   // edges in its route
  // Its scheduled stops: the next one to make, in TripView's stop table (== stops_end: none left).
  uint32_t* next_stop;
  uint32_t* stops_end;
  uint32_t* stop_release;  // standing at next_stop until this step (0: not at a stop)
  uint32_t* stop_steps;    // steps stood at stops (tripinfo stopTime)
  // The emissions pass's own state (kernels/emission_step.hpp), kept only while it runs: the speed at the
  // step's start (the commit pass overwrites `speed` before it), and EmissionFlags.
  float* emission_speed;
  uint8_t* emission_flags;
};

/// Where the vehicle in `slot` lies now (its footprint as the last step wrote it into the lane map).
LPSIM_HD Footprint current_footprint(const VehicleView& veh, uint32_t slot) {
  return Footprint{veh.lane[slot], veh.prev[slot], veh.prev2[slot], veh.pos[slot]};
}

constexpr uint32_t kBestLaneEntries = 2;  // a power of two

/// A slot number that names no slot in the active list (Stepper::sort_slots).
constexpr uint32_t kNotActive = 0xFFFFFFFFu;

/// The one list of the slot columns: calls f(entries per slot, view.column...) for every column of
/// VehicleView, the same column of each view given (one view, or two to pair a device and a host copy).
/// Storage, growth, the slot sort, the device copies and the host's fetched copies all walk this list, so
/// that a column added to VehicleView and here reaches every one of them. Host code only: the passes name
/// columns directly.
template <class F, class... Views>
void visit_vehicle_columns(F&& f, Views&... v) {
  f(1u, v.status...);
  f(1u, v.vehicle...);
  f(1u, v.route_pos...);
  f(1u, v.speed...);
  f(1u, v.lane...);
  f(1u, v.prev...);
  f(1u, v.prev2...);
  f(1u, v.pos...);
  f(1u, v.old_lane...);
  f(1u, v.old_prev...);
  f(1u, v.old_prev2...);
  f(1u, v.old_pos...);
  f(1u, v.stopped_steps...);
  f(1u, v.waiting_steps...);
  f(1u, v.waiting_count...);
  f(1u, v.time_loss...);
  f(1u, v.route_length...);
  f(1u, v.arrival_step...);
  f(1u, v.lane_change_dir...);
  f(1u, v.held_at_line...);
  f(1u, v.limit_reason...);
  f(kBestLaneEntries, v.best_rp...);
  f(kBestLaneEntries, v.best_mask...);
  f(1u, v.conn_lane...);
  f(1u, v.conn_rp...);
  f(1u, v.conn...);
  f(1u, v.trip_type...);
  f(1u, v.trip_speed_factor...);
  f(1u, v.trip_route_begin...);
  f(1u, v.trip_route_size...);
  f(1u, v.next_stop...);
  f(1u, v.stops_end...);
  f(1u, v.stop_release...);
  f(1u, v.stop_steps...);
  f(1u, v.emission_speed...);
  f(1u, v.emission_flags...);
}
static_assert(sizeof(VehicleView) == 36 * sizeof(void*), "VehicleView changed: update visit_vehicle_columns");

enum StopReason : uint8_t {
  kFree = 0,
  kLeader = 1,
  kWrongLane = 2,
  kSignal = 3,
  kHaltRule = 4,
  kNoRoom = 5,
  kYield = 6,
  kMergeGap = 7,
  kSwap = 8,
  kStop = 9  // approaching or standing at a scheduled stop
};

/// What a vehicle decided this step, between the plan and the commit passes. Indexed by the vehicle's
/// position in the step's active list (not by its slot or by vehicle): these columns scale with the vehicles
/// on the road, not with the whole demand, and are read in active-list order.
struct PlanView {
  float* new_speed;
  int32_t* new_lane;  // lane of the front after the move
  float* new_pos;
  int32_t* new_prev;
  int32_t* new_prev2;
  int32_t* claim_lane0;  // lanes entered from their start this step (up to 2), -1 if none
  int32_t* claim_lane1;
  float* stop_pos;  // fallback if a claim is lost: front position on the pre-claim lane
  int32_t* stop_lane;
  uint8_t* arrives;    // 1: reaches its arrival position this step
  uint32_t* new_rp;    // route position after the move
  uint32_t* first_rp;  // route position on claim_lane0 (kept if only the second claim is lost)
  // Priority of this vehicle's claims (1 entering a lane, 0 changing lanes near a start).
  uint8_t* claim_prio;
  // Written by the approach pass for the plan pass of the same step, so that the plan does not compute it
  // again: the vehicle's look-ahead distance. (The connection at its lane's end is shared through the
  // slot's cache instead: current_lane_connection.)
  float* lookahead;
};

/// The one list of the plan columns (as visit_vehicle_columns): one entry per active-list position each.
template <class F, class... Views>
void visit_plan_columns(F&& f, Views&... v) {
  f(1u, v.new_speed...);
  f(1u, v.new_lane...);
  f(1u, v.new_pos...);
  f(1u, v.new_prev...);
  f(1u, v.new_prev2...);
  f(1u, v.claim_lane0...);
  f(1u, v.claim_lane1...);
  f(1u, v.stop_pos...);
  f(1u, v.stop_lane...);
  f(1u, v.arrives...);
  f(1u, v.new_rp...);
  f(1u, v.first_rp...);
  f(1u, v.claim_prio...);
  f(1u, v.lookahead...);
}
static_assert(sizeof(PlanView) == 14 * sizeof(void*), "PlanView changed: update visit_plan_columns");

/// Claims and merge requests keep the step in their top 24 bits: a backend zeroes both tables at the start of
/// every step that is a multiple of this, so that the marks of the steps before the wrap cannot outrank the
/// steps after it. Zeroing them at any step changes nothing else (a step reads only its own marks).
LPSIM_HD constexpr bool step_marks_wrap(uint32_t step) { return step > 0 && (step & 0xFFFFFFu) == 0; }

/// Claims on lane entries: one 64-bit word per lane; the largest value of the current step wins.
/// value = step << 40 | (0xFF - priority) << 32 | (0xFFFFFFFF - vehicle): higher priority, then lower index.
LPSIM_HD uint64_t claim_key(uint32_t step, uint32_t priority, uint32_t vehicle) {
  return (static_cast<uint64_t>(step & 0xFFFFFFu) << 40) |
         (static_cast<uint64_t>(0xFFu - (priority & 0xFFu)) << 32) |
         static_cast<uint64_t>(0xFFFFFFFFu - vehicle);
}

/// The first vehicle on a lane as seen by junction right-of-way checks (valid when step matches).
struct LaneApproach {
  uint32_t step;
  int32_t conn;      // connection it intends to take at the lane's end, -1 unknown
  float dist;        // front bumper to the lane end [m]
  float speed;       // m/s
  uint32_t waiting;  // consecutive steps stopped (deadlock breaking)
  uint32_t held;     // 1: standing at the line for a red light or a full next lane (not a foe now)
  float reach;       // distance within which it announces its arrival (SUMO's request horizon) [m]
  float v_max;       // its desired speed on the lane [m/s]
};

/// Everything one step needs besides the arrays above.
struct StepParams {
  uint32_t step;  // step counter from 0
  // Time whose signal states the step obeys: its end. SUMO switches lights at the start of the step that
  // produces time t's state, so a light turning green at t already lets vehicles move in that step.
  int64_t signal_time_ms;
  float dt;  // s
  uint64_t seed;
  int32_t substeps;           // IDM integration sub-steps
  float max_accel;            // largest accel over all types (bounds how far an unseen vehicle can get)
  float max_emergency_decel;  // largest emergency decel over all types (hardest a leader may brake)
  uint32_t teleport_steps;    // 0: never teleport
  uint32_t impatience_steps;  // stopped steps for a vehicle's impatience to grow from 0 to 1; 0: never
  // SUMO's --ignore-junction-blocker in steps: foes no longer wait for vehicles standing this long on a
  // junction lane (read only where the step tracks junction stands, StepContext::junction_stand_now).
  uint32_t ignore_blocker_steps;
  // SUMO's --time-to-teleport.highways in steps (0: never): a vehicle standing this long at the front of a
  // lane that does not lead on along its route, on a road whose limit exceeds highway_min_speed, teleports.
  uint32_t highway_teleport_steps;
  float highway_min_speed;  // m/s
};

/// Stopped steps after which a vehicle may start a teleport for some reason (0: never).
LPSIM_HD uint32_t first_teleport_steps(const StepParams& p) {
  if (p.teleport_steps == 0) return p.highway_teleport_steps;
  if (p.highway_teleport_steps == 0) return p.teleport_steps;
  return p.teleport_steps < p.highway_teleport_steps ? p.teleport_steps : p.highway_teleport_steps;
}

/// A junction lane's entry of StepContext::junction_stand_*: no vehicle's front stood there.
constexpr uint32_t kNoJunctionStand = 0xFFFFFFFFu;

/// A vehicle that arrived or started a teleport in a step, as the host sees it (trip record, teleport).
struct VehicleEnd {
  uint32_t vehicle;
  uint32_t slot;
  uint32_t kind;  // kEndArrived or kEndTeleport (kernels/vehicle_step.hpp)
  int32_t lane;
  float pos;
  float speed;
  float route_length;
  float time_loss;
  uint32_t route_pos;
  uint32_t waiting_steps;
  uint32_t waiting_count;
  uint32_t limit_reason;  // StopReason of its last plan (why a teleporting vehicle was stuck)
  uint32_t next_stop;     // the scheduled stops it carries over a teleport
  uint32_t stop_steps;
};

/// What becomes of a teleporting vehicle (decided on the host, which owns the insertion queues).
struct TeleportMove {
  uint32_t vehicle;
  uint32_t slot;
  uint32_t ends_trip;  // 1: past the end of its route, its trip ends; 0: re-enters at the next route edge
};

/// A vehicle entering the road in a free slot (after insertion), with the trip counters it carries over
/// from before a teleport (zero for a departure).
struct SlotInit {
  uint32_t slot;
  uint32_t vehicle;
  uint32_t route_pos;
  int32_t lane;
  float pos;
  float speed;
  float route_length;
  float time_loss;
  uint32_t waiting_steps;
  uint32_t waiting_count;
  uint32_t next_stop;  // its scheduled stops still to make: [next_stop, stops_end) of TripView's table
  uint32_t stops_end;
  uint32_t stop_steps;
};

/// A running vehicle's new route (rerouting): where its edges start in TripView::route_edges, how many, and
/// the position on it of the edge the vehicle is on (or, on an internal lane, last left).
struct SlotRoute {
  uint32_t slot;
  uint32_t route_begin;
  uint32_t route_size;
  uint32_t route_pos;
};

}  // namespace lpsim

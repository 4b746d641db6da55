#pragma once
// What the engine hands to the output writers (converters/*_writer): plain sampled values, no text.
// The engine fills these off the step's hot path (at the output period); writers format them as SUMO XML.
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/step_view.hpp"

namespace lpsim {

/// Vehicle positions at one time step (FCD). Vehicles are listed in ascending vehicle index.
struct FcdFrame {
  double time = 0;
  std::vector<uint32_t> vehicle;  // index into Demand
  std::vector<uint32_t> lane;     // index into Network lanes (may be an internal lane)
  std::vector<float> pos;         // m from the lane start to the front bumper
  std::vector<float> speed;       // m/s
};

/// Per-lane counters accumulated over one edgeData/laneData interval. Integer counters so that the sum is
/// the same whatever order threads add in (bit-identical results on any backend).
struct LaneCounters {
  std::vector<int64_t> sampled_steps;      // vehicle-steps spent on the lane
  std::vector<int64_t> travelled_mm;       // distance driven on the lane, millimetres
  std::vector<int64_t> waiting_steps;      // vehicle-steps with speed < 0.1 m/s
  std::vector<int64_t> time_loss_ms;       // sum over vehicle-steps of dt * (1 - v / v_desired), milliseconds
  std::vector<int64_t> occupied_mm_steps;  // sum over vehicle-steps of (vehicle length on the lane) in mm
  std::vector<int64_t> departed, arrived, entered, left;
  // The emissions pass's sums (EmissionSum order: time in us, distance in um, masses in ng), kept only for
  // emissions edgeData/laneData (empty otherwise).
  std::vector<int64_t> emission[kNumEmissionSums];

  /// Every traffic column to `lanes` zeros, and the emission columns too with `emission_sums` (else empty).
  void resize(size_t lanes, bool emission_sums = false);
  void clear();
  template <class A>
  void visit_state(A& a) {
    a.sparse(sampled_steps);
    a.sparse(travelled_mm);
    a.sparse(waiting_steps);
    a.sparse(time_loss_ms);
    a.sparse(occupied_mm_steps);
    a.sparse(departed);
    a.sparse(arrived);
    a.sparse(entered);
    a.sparse(left);
    for (std::vector<int64_t>& e : emission) a.sparse(e);
  }
};

struct MeanDataInterval {
  double begin = 0, end = 0;  // s
  double step_length = 1;     // s
  const LaneCounters* counters = nullptr;
};

/// Why a vehicle teleported, as SUMO words it: stopped too long in a jam, waiting to yield at a junction, or
/// on a lane that does not lead on along its route.
enum class TeleportCause : uint8_t { Jam, Yield, WrongLane };

/// A vehicle that started a teleport in the last step, on `lane`.
struct TeleportEvent {
  uint32_t vehicle = 0;
  uint32_t lane = 0;
  TeleportCause cause = TeleportCause::Jam;
  bool highway = false;  // by --time-to-teleport.highways (SUMO's cause then adds ", highway")
};

/// One finished trip (tripinfo). Times in seconds.
struct TripRecord {
  uint32_t vehicle = 0;
  double depart = 0, depart_delay = 0, arrival = 0;
  uint32_t depart_lane = 0, arrival_lane = 0;
  float depart_pos = 0, depart_speed = 0, arrival_pos = 0, arrival_speed = 0;
  double route_length = 0;  // m actually driven along the route
  double waiting_time = 0;  // s with speed < 0.1 m/s
  uint32_t waiting_count = 0;
  double stop_time = 0;  // s stood at scheduled stops (not counted as waiting or as lost time)
  double time_loss = 0;  // s
  float speed_factor = 1;
  bool teleported = false;
  bool removed = false;  // a remove command took it out (SUMO's vaporized="traci")
  // SUMO's write-unfinished / write-undeparted records, written at the end: kTripRunning for a trip still
  // on its way (arrival fields unknown), kTripUndeparted for one due by the end that never departed.
  uint8_t unfinished = 0;
};
inline constexpr uint8_t kTripRunning = 1, kTripUndeparted = 2;

/// One step of the summary output.
struct SummaryRow {
  double time = 0;
  uint64_t loaded = 0, inserted = 0, running = 0, waiting = 0, ended = 0, arrived = 0;
  uint64_t collisions = 0, teleports = 0, halting = 0, stopped = 0;
  double mean_waiting_time = 0, mean_travel_time = 0, mean_speed = 0, mean_speed_relative = 0;
  double duration_ms = 0;  // wall time of the step
};

}  // namespace lpsim

namespace lpsim {

/// Column k of the counters, in the order the backends keep them (backends/stepper.hpp's LaneCounter).
std::vector<int64_t>& counter_column(LaneCounters& c, int k);

/// Counters accumulated between two snapshots of cumulative counters (now - start), for intervals.
LaneCounters counters_since(const LaneCounters& now, const LaneCounters& start);

}  // namespace lpsim

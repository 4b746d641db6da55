#pragma once
// A partitioned run's state in one part's Simulation (simulation_parts.cpp): whom it exchanges with, what a
// step hands on between its rounds, and, in part 0, the run's totals gathered from every part.
#include <cstdint>
#include <map>
#include <vector>

#include "engine/simulation.hpp"

namespace lpsim {

/// A teleported vehicle that re-enters at an edge's queue, handed to the edge's owner.
struct TeleportHandOver {
  VehicleEnd end;
  uint32_t route_pos = 0;  // where it re-enters
  uint32_t edge = 0;
  DepartRecord departure;
};

/// A vehicle inserted in a step: its place in the order one part inserts (edge << 32 | entry of the batch,
/// the batch listing edges ascending) and its insertion delay.
struct DepartDelay {
  uint64_t order;
  double delay;
};

/// A running vehicle as part 0 samples it for the outputs.
struct SampleEntry {
  uint32_t vehicle;
  int32_t lane;
  float pos, speed;
  uint32_t stop_release;
};

/// What part 0 asks the other parts for (serve_part).
enum PartRequest : uint8_t {
  kRequestStep = 1,
  kRequestSample = 2,
  kRequestCounters = 3,
  kRequestSpeedSums = 4,
  kRequestStop = 5,
  kRequestUnfinished = 6
};

struct PartState {
  PartState(const PartPlan& p, Transport& t) : plan(p), transport(t) {}

  /// One round with the transport, timed and counted in `stats` (exchange: a round of the step; else a
  /// request or a gather for the outputs).
  std::vector<Bytes> round(const std::vector<int>& to, const std::vector<Bytes>& send,
                           const std::vector<int>& from, const char* what, bool exchange);

  const PartPlan& plan;
  Transport& transport;
  std::vector<int> neighbours;  // the parts that hold a lane this one holds, ascending
  // The actuated signals this part runs that others read, and the parts that read them; the parts whose
  // signals this one reads.
  std::vector<uint32_t> signals_sent;
  std::vector<int> signal_readers, signal_owners;
  bool signal_round = false;  // some part runs an actuated signal another reads (the same in every part)
  // Some actuated signal reads a loop on a lane its part does not own: insertions go in a round of their own
  // before the next step's signals (the same in every part).
  bool insertion_round = false;
  std::vector<uint32_t> owned_shared;  // its lanes that other parts hold too, ascending

  // What this part clears from each lane map when the step next writes it, besides its own vehicles' last
  // footprints: the other parts' footprints written into it, and the last footprint of each vehicle that left
  // for another part (as value-0 writes).
  std::vector<FootprintWrite> remote_footprints[2];
  // Footprints of the last insertions on lanes others hold, by part, until they are sent.
  std::map<int, std::vector<FootprintWrite>> inserted;

  // Handed on within a step.
  std::vector<TeleportHandOver> teleports;  // this step's teleports, whoever owns their re-entry edge
  std::vector<uint32_t> adopted;            // slots taken by vehicles that drove in from other parts
  uint32_t migrated = 0;                    // running vehicles that drove into another part
  std::vector<DepartDelay> departures;      // the step's insertions

  PartStats stats;  // this part's, cumulative
  // Part 0: the run's totals, and each part's stats as of its last report.
  std::vector<PartStats> part_stats;
  Simulation::Counts counts;
  std::vector<TeleportEvent> teleport_events;
  std::vector<TripRecord> finished;
  double depart_delay_sum = 0, travel_time_sum = 0;
  bool all_idle = false;            // no part has a vehicle on the road or waiting to be inserted
  int signal = 0;                   // the first signal a part reported (SimulationOptions::pending_signal)
  std::vector<SampleEntry> sample;  // gathered by gather_sample(), ascending by vehicle
  uint64_t sample_version = ~uint64_t{0};  // the Simulation's state version it was gathered at
};

}  // namespace lpsim

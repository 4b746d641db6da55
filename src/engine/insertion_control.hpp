#pragma once
// The insertion of vehicles, as SUMO's MSInsertionControl (insertion_control.cpp): trips join their first
// edge's queue when their departure is due, the backend inserts each queue's head where there is room, the
// inserted vehicles take slots and start at the end of the step, and with a max depart delay the departures
// that waited too long are dropped. Where a trip departs elsewhere (another part, another simulator) its
// boundary link takes it.
#include <cstdint>
#include <vector>

#include "engine/boundary_link.hpp"

namespace lpsim {

/// What the insertions follow for the whole run.
struct InsertionRules {
  uint64_t seed = 0;
  int64_t step_ms = 1000;
  double max_depart_delay = -1;   // s; < 0: never drop (SimulationOptions::max_depart_delay)
  float max_emergency_decel = 9;  // the hardest any leader may brake
  float min_decel = 4.5f;         // the softest braking of any type (how a follower is assumed to react)
};

class InsertionControl {
 public:
  InsertionControl(const LinkScope& run, BoundaryLink& link, const InsertionRules& rules)
      : run_(run), link_(link), rules_(rules) {}

  /// Trips whose departure is due by `until_ms` join their first edge's queue (HostBooks::schedule).
  void enqueue_due(int64_t until_ms);
  /// The queues' heads are inserted into lane map `map` at the end of step `step` (`time_ms` that end): each
  /// inserted vehicle takes a slot (HostBooks::inits) and its departure is recorded.
  void insert(int map, int64_t time_ms, uint32_t step);
  /// The vehicles inserted in this step start in their slots and join the active list, which `kept` slots
  /// of the step's stay in (`running` of them running); the slots that left it in this step are free.
  void start(uint32_t kept, uint32_t running);

 private:
  void enqueue(uint32_t v);
  void drop_late_departures(int64_t time_ms);
  void set_stops(SlotInit& init, uint32_t next) const;

  LinkScope run_;
  BoundaryLink& link_;
  InsertionRules rules_;
};

}  // namespace lpsim

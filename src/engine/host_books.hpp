#pragma once
// The host's account of a run between the backend's passes: the slots handed out, the insertion queues,
// every trip's ledger, the counts and what one step hands on to the next. The Simulation keeps it, and its
// boundary link (boundary_link.hpp) reads and changes it where vehicles cross the boundary.
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/insertion_queues.hpp"
#include "engine/samples.hpp"
#include "engine/slot_pool.hpp"
#include "engine/trip_ledger.hpp"
#include "kernels/step_view.hpp"
#include "net/network.hpp"

namespace lpsim {

/// A run's counts (of one part in a partitioned run; part 0 reports the sums over the parts).
struct RunCounts {
  uint64_t loaded = 0, inserted = 0, running = 0, waiting = 0, arrived = 0, teleports = 0;
  uint64_t removed = 0;    // never inserted for a reason (departure before begin, route without car lanes)
  uint64_t discarded = 0;  // dropped while waiting to depart, after the max depart delay
  uint64_t cancelled = 0;  // taken out by a remove command before they departed (ended, not arrived)
  uint64_t vehicle_updates = 0;
};

/// The trips still to be queued for departure: the loaded ones from `next` on (sorted by depart), and those
/// added during the run.
struct DepartureSchedule {
  uint32_t next = 0;    // loaded trips before this one have been queued (or removed)
  uint32_t loaded = 0;  // trips loaded at the start
  // Trips added during the run whose departure has not come yet: (depart ms, trip), soonest last.
  std::vector<std::pair<int64_t, uint32_t>> added;

  bool empty() const { return next >= loaded && added.empty(); }
  template <class A>
  void visit_state(A& a) {
    a(next);
    a(loaded);
    a(added);
  }
};

struct HostBooks {
  explicit HostBooks(const Network& net) : queues(net) {}

  SlotPool slots;
  InsertionQueues queues;
  TripLedger ledger;
  RunCounts counts;
  DepartureSchedule schedule;
  uint32_t num_active = 0;  // slots the passes visit: on the road, or left it in the last step
  // Slots whose vehicle left the road in the previous step (free after this step's passes), and in this one.
  std::vector<uint32_t> retiring, retiring_next;
  // This step's insertions, each with the slot it took.
  std::vector<SlotInit> inits;
  // The teleports that started in the last step, in vehicle order.
  std::vector<TeleportEvent> teleport_events;

  /// Nothing on the road and nothing waiting to be inserted.
  bool idle() const { return num_active == 0 && queues.waiting() == 0; }
  /// Between steps (the step's hand-ons are empty then).
  template <class A>
  void visit_state(A& a) {
    a(slots);
    if constexpr (A::kReads)
      queues.load_state(a);
    else
      queues.save_state(a);
    a(ledger);
    a(counts);
    a(schedule);
    a(num_active);
    a(retiring);
    a(retiring_next);
    a(teleport_events);
  }
};

}  // namespace lpsim

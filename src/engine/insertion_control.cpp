#include "engine/insertion_control.hpp"

#include <algorithm>
#include <cmath>

#include "core/time_range.hpp"
#include "kernels/insert_vehicle.hpp"

namespace lpsim {

// In the order of their depart times, ties by index: the loaded ones (sorted by depart) and those added
// during the run.
void InsertionControl::enqueue_due(int64_t until_ms) {
  const Demand& d = run_.trips.demand();
  DepartureSchedule& due = run_.books.schedule;
  for (;;) {
    const bool loaded_due = due.next < due.loaded && seconds_to_ms(d.depart[due.next]) <= until_ms;
    const bool added_due = !due.added.empty() && due.added.back().first <= until_ms;
    if (!loaded_due && !added_due) break;
    // An added trip has a higher index than every loaded one: it goes first only when it departs earlier.
    if (added_due && (!loaded_due || due.added.back().first < seconds_to_ms(d.depart[due.next]))) {
      enqueue(due.added.back().second);
      due.added.pop_back();
    } else {
      enqueue(due.next++);
    }
  }
}

void InsertionControl::enqueue(uint32_t v) {
  const Demand& d = run_.trips.demand();
  HostBooks& books = run_.books;
  if (books.ledger.status(v) == kArrived) return;  // removed by a command before it fell due
  if (d.route_length[v] == 0 || !books.queues.has_lanes(d.route_edges[d.route_begin[v]])) {
    books.ledger.set_status(v, kArrived);
    ++books.counts.removed;
    return;
  }
  const uint32_t edge = d.route_edges[d.route_begin[v]];
  if (link_.takes_departure(v, edge)) return;
  books.queues.push_back(edge, queue_entry(v, false));
}

void InsertionControl::insert(int map, int64_t time_ms, uint32_t step) {
  HostBooks& books = run_.books;
  InsertionQueues& queues = books.queues;
  TripLedger& ledger = books.ledger;
  const double now = static_cast<double>(time_ms) / 1000.0;
  const InsertBatch& batch = queues.offer(ledger.reentry_wants());
  // The step length as a float in the one way the insertion checks have always used it.
  const InsertParams params{static_cast<float>(static_cast<double>(rules_.step_ms) / 1000.0),
                            rules_.seed,
                            step,
                            rules_.max_emergency_decel,
                            rules_.min_decel,
                            nullptr,
                            nullptr};
  if (queues.offered_entries() > 0) run_.stepper.insert(batch, queues.offered_entries(), params, map);

  // Advance the queues past the inserted heads, give each inserted vehicle a slot and record the
  // departures, in the order of the batch.
  const Demand& d = run_.trips.demand();
  books.inits.clear();
  // Each entry's edge, for a partitioned run's report of the departures in the order one part inserts.
  const bool record = link_.records_departures();
  std::vector<uint32_t> entry_edge;
  if (record) {
    entry_edge.resize(queues.offered_entries());
    for (uint32_t slot = 0; slot < batch.num_slots; ++slot)
      std::fill(entry_edge.begin() + batch.begin[slot], entry_edge.begin() + batch.begin[slot + 1],
                batch.edge[slot]);
  }
  queues.take_inserted([&](uint32_t i) {
    const uint32_t v = batch.entry[i] & ~kInsertTeleported;
    SlotInit init{0,
                  v,
                  batch.route_pos[i],
                  batch.out_lane[i],
                  batch.out_pos[i],
                  batch.out_speed[i],
                  0.0f,
                  0.0f,
                  0,
                  0,
                  0,
                  0,
                  0};
    if (batch.entry[i] & kInsertTeleported) {
      set_stops(init, ledger.reentering(init));
    } else {
      ++books.counts.inserted;
      ledger.departed(v, now, d.depart[v], init);
      if (record) link_.departed(uint64_t{entry_edge[i]} << 32 | i, now - d.depart[v]);
      set_stops(init, d.stops.first(v));
    }
    init.slot = books.slots.take();
    books.inits.push_back(init);
  });
  if (rules_.max_depart_delay >= 0) drop_late_departures(time_ms);
}

// SUMO's --max-depart-delay: a departure that could not be inserted in this step, which ends more than the
// delay after its depart time, is dropped (MSInsertionControl::tryInsert); queued vehicles behind a failed
// head were not tried and are dropped alike, as in SUMO.
void InsertionControl::drop_late_departures(int64_t time_ms) {
  const Demand& d = run_.trips.demand();
  HostBooks& books = run_.books;
  const int64_t max_delay_ms = std::llround(rules_.max_depart_delay * 1000.0);
  books.queues.drop_departures([&](uint32_t v) {
    if (time_ms - seconds_to_ms(d.depart[v]) <= max_delay_ms) return false;
    books.ledger.set_status(v, kArrived);
    ++books.counts.discarded;
    return true;
  });
}

// Vehicle v's scheduled stops still to make when it enters the road at route position `rp`: from
// `next` (where a teleport left it, else its first) on, skipping those on edges it has already left.
void InsertionControl::set_stops(SlotInit& init, uint32_t next) const {
  const StopTable& st = run_.trips.demand().stops;
  init.stops_end = st.last(init.vehicle);
  while (next < init.stops_end && st.route_pos[next] < init.route_pos) ++next;
  init.next_stop = next;
}

void InsertionControl::start(uint32_t kept, uint32_t running) {
  HostBooks& b = run_.books;
  std::vector<uint32_t> added;
  added.reserve(b.inits.size());
  for (const SlotInit& in : b.inits) added.push_back(in.slot);
  // Also the vehicles that came in across the boundary; those that left ran in the step.
  const int64_t crossed = link_.settle_crossings(added);
  std::sort(added.begin(), added.end());
  run_.stepper.start_vehicles(b.inits, added);
  b.num_active = kept + static_cast<uint32_t>(added.size());
  // Running vehicles: those of the step's active list, and every one inserted.
  b.counts.running = static_cast<uint64_t>(static_cast<int64_t>(running + b.inits.size()) + crossed);
  b.counts.waiting = b.queues.waiting();
  b.inits.clear();
  for (const uint32_t k : b.retiring) b.slots.release(k);
  b.retiring.swap(b.retiring_next);
  b.retiring_next.clear();
}

}  // namespace lpsim

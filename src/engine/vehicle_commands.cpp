#include "engine/vehicle_commands.hpp"

#include <algorithm>
#include <stdexcept>

namespace lpsim {

VehicleCommand VehicleCommand::add(NewTrip trip) {
  VehicleCommand c;
  c.kind = Kind::Add;
  c.trip = std::move(trip);
  return c;
}

VehicleCommand VehicleCommand::set_route(uint32_t vehicle, std::vector<uint32_t> edges) {
  VehicleCommand c;
  c.kind = Kind::SetRoute;
  c.vehicle = vehicle;
  c.edges = std::move(edges);
  return c;
}

VehicleCommand VehicleCommand::remove(uint32_t vehicle) {
  VehicleCommand c;
  c.kind = Kind::Remove;
  c.vehicle = vehicle;
  return c;
}

namespace {

// One part's verdict on a command: whether it has the vehicle, why the command cannot act on it (empty when
// it can), and the footprint a removal erases (a vehicle on the road), if any.
struct Verdict {
  uint8_t here = 0;
  std::vector<char> why;
  uint8_t erases = 0;
  FootprintWrite erased{};

  template <class A>
  void visit_state(A& a) {
    a(here);
    a(why);
    a(erases);
    a(erased);
  }
};

Verdict read_verdict(const Bytes& b) {
  StateIn a(b.data(), b.size(), "a part's verdict on a command");
  Verdict v;
  a(v);
  return v;
}

}  // namespace

Bytes command_bytes(const std::vector<VehicleCommand>& commands) {
  StateOut a;
  std::vector<VehicleCommand> c = commands;
  a(c);
  return std::move(a.bytes());
}

std::vector<VehicleCommand> commands_from_bytes(const Bytes& bytes) {
  StateIn a(bytes.data(), bytes.size(), "part 0's commands");
  std::vector<VehicleCommand> commands;
  a(commands);
  if (!a.done()) a.fail("bytes left after the last command");
  return commands;
}

// Where this part has a vehicle: on the road (in a slot), queued to depart or to re-enter after a teleport
// (in one of its queues), not yet due to depart (every part alike), handed to the other simulator of a
// co-simulation, or not at all (elsewhere, or its trip has ended).
struct CommandApplier::Where {
  enum Kind : uint8_t { kNowhere, kRunning, kQueued, kTeleporting, kNotDue, kOutside };
  Kind kind = kNowhere;
  int32_t slot = -1;
  uint32_t route_pos = 0;  // where it is on its route (the road), enters it (queues) or departs (not due)
  uint32_t edge = 0;       // the queue's edge
};

CommandApplier::Where CommandApplier::locate(uint32_t v) const {
  Where at;
  const Demand& d = run_.trips.demand();
  const HostBooks& books = run_.books;
  const TripLedger& ledger = books.ledger;
  if (v >= d.size()) return at;
  const int32_t k = query_.slot(v);
  const HostState& s = query_.state();
  auto in = [v](const std::vector<uint32_t>& vehicles) {
    return std::find(vehicles.begin(), vehicles.end(), v) != vehicles.end();
  };
  if (k >= 0 && s.veh.status[k] == kRunning && !in(removed_)) {
    at.kind = Where::kRunning;
    at.slot = k;
    at.route_pos = in(rerouted_) ? 0 : s.veh.route_pos[k];
    return at;
  }
  const uint32_t* route = d.route_edges.data() + d.route_begin[v];
  if (ledger.status(v) == kTeleporting) {
    at.route_pos = ledger.resume_route_pos(v);
    at.edge = route[at.route_pos];
    if (books.queues.holds(at.edge, queue_entry(v, true))) at.kind = Where::kTeleporting;
    return at;
  }
  if (ledger.status(v) == kMigrated) {
    at.kind = Where::kOutside;
    return at;
  }
  if (ledger.status(v) != kPending || ledger.departure(v).lane >= 0) return at;
  const DepartureSchedule& due = books.schedule;
  const bool not_due = v < due.loaded ? v >= due.next
                                      : std::any_of(due.added.begin(), due.added.end(),
                                                    [v](const auto& a) { return a.second == v; });
  if (not_due) {
    at.kind = Where::kNotDue;
  } else if (d.route_length[v] > 0 && books.queues.holds(route[0], queue_entry(v, false))) {
    at.kind = Where::kQueued;
    at.edge = route[0];
  }
  return at;
}

// Why `edges` cannot be vehicle v's route from where it is ("" when it can).
std::string CommandApplier::route_refusal(uint32_t v, const std::vector<uint32_t>& edges,
                                          const Where& at) const {
  const Network& net = run_.net;
  const Demand& d = run_.trips.demand();
  if (edges.empty()) return "it is empty";
  for (const uint32_t e : edges)
    if (e >= net.num_edges() || net.edge_is_internal[e]) return "no normal edge " + std::to_string(e);
  if (!TripTable::connected(net, edges, d.types.vclass_mask[d.vehicle_type[v]]))
    return "it is not connected for the vehicle's vClass";
  const uint32_t* old = d.route_edges.data() + d.route_begin[v];
  const char* where = at.kind == Where::kRunning       ? "is on edge"
                      : at.kind == Where::kTeleporting ? "re-enters after its teleport at"
                                                       : "departs from";
  if (edges.front() != old[at.route_pos])
    return std::string("it starts at edge '") + net.edge_id[edges.front()] + "', the vehicle " + where +
           " '" + net.edge_id[old[at.route_pos]] + "'";
  // On a junction's internal lane it is already bound for the next edge of its route.
  if (at.kind == Where::kRunning) {
    const auto lane = static_cast<uint32_t>(query_.state().veh.lane[at.slot]);
    if (net.edge_is_internal[net.lane_edge[lane]] && (edges.size() < 2 || edges[1] != old[at.route_pos + 1]))
      return "the vehicle is crossing a junction into edge '" + net.edge_id[old[at.route_pos + 1]] +
             "', which must come second";
  }
  return "";
}

Bytes CommandApplier::verdict(const VehicleCommand& c) const {
  const Where at = locate(c.vehicle);
  Verdict v;
  v.here = at.kind != Where::kNowhere ? 1 : 0;
  std::string why;
  if (at.kind == Where::kOutside)
    why = "the other simulator drives it";
  else if (v.here && c.kind == VehicleCommand::Kind::SetRoute)
    why = route_refusal(c.vehicle, c.edges, at);
  v.why.assign(why.begin(), why.end());
  if (at.kind == Where::kRunning && c.kind == VehicleCommand::Kind::Remove) {
    const VehicleView& veh = query_.state().veh;
    const auto k = static_cast<uint32_t>(at.slot);
    v.erased =
        FootprintWrite{current_footprint(veh, k), run_.trips.demand().types.length[veh.trip_type[k]], 0};
    v.erases = 1;
  }
  StateOut a;
  a(v);
  return std::move(a.bytes());
}

CommandOutcome CommandApplier::combine_verdicts(const VehicleCommand& c, const std::vector<Bytes>& verdicts,
                                                const Demand& demand) {
  CommandOutcome o;
  o.vehicle = c.vehicle;
  const std::string who = c.vehicle < demand.size() ? "vehicle '" + demand.vehicle_id[c.vehicle] + "'"
                                                    : "no vehicle " + std::to_string(c.vehicle);
  const std::string what =
      c.kind == VehicleCommand::Kind::SetRoute ? ": new route refused: " : ": not removed: ";
  if (c.vehicle >= demand.size()) {
    o.error = who;
    return o;
  }
  for (const Bytes& b : verdicts) {
    const Verdict v = read_verdict(b);
    if (v.here == 0) continue;
    if (!v.why.empty()) o.error = who + what + std::string(v.why.begin(), v.why.end());
    return o;
  }
  o.error = who + what + "its trip has ended";
  return o;
}

void CommandApplier::apply(const VehicleCommand& c, const std::vector<Bytes>& verdicts) {
  const Demand& d = run_.trips.demand();
  HostBooks& books = run_.books;
  TripLedger& ledger = books.ledger;
  const uint32_t v = c.vehicle;
  const Where at = locate(v);
  if (c.kind == VehicleCommand::Kind::SetRoute) {
    run_.trips.set_route(v, c.edges);
    if (at.kind == Where::kTeleporting) ledger.set_resume_route_pos(v, 0);
    if (at.kind != Where::kRunning) return;
    rerouted_.push_back(v);
    run_.sync_trips();
    run_.stepper.set_routes(
        {SlotRoute{static_cast<uint32_t>(at.slot), d.route_begin[v], d.route_length[v], 0}});
    return;
  }
  // Remove: its footprint leaves every part's lane map, wherever it was on the road.
  for (const Bytes& b : verdicts)
    if (const Verdict verdict = read_verdict(b); verdict.erases)
      run_.link.erase_removed(run_.map, verdict.erased);
  switch (at.kind) {
    case Where::kRunning: {
      // As SUMO's TraCI remove: the trip ends where the vehicle is, counted as arrived.
      const auto k = static_cast<uint32_t>(at.slot);
      const VehicleEnd e = vehicle_end(query_.state().veh, k, kEndArrived);
      ledger.ended(e, false, run_.now, d.depart[v], run_.step_length, d.speed_factor[v], true);
      ++books.counts.arrived;
      --books.counts.running;
      run_.stepper.mark_migrated({k});
      removed_.push_back(v);
      // Its slot clears its last footprint in the next step, as one that left the road in the last.
      books.retiring.push_back(k);
      return;
    }
    case Where::kTeleporting: {
      books.queues.remove(at.edge, queue_entry(v, true));
      const TripCounters carried = ledger.drop_carried(v);
      const VehicleEnd e{v,
                         0,
                         kEndArrived,
                         static_cast<int32_t>(run_.net.edge_first_lane[at.edge]),
                         0,
                         0,
                         carried.route_length,
                         carried.time_loss,
                         at.route_pos,
                         carried.waiting_steps,
                         carried.waiting_count,
                         0,
                         carried.next_stop,
                         carried.stop_steps};
      ledger.ended(e, true, run_.now, d.depart[v], run_.step_length, d.speed_factor[v], true);
      ++books.counts.arrived;
      --books.counts.waiting;
      return;
    }
    case Where::kQueued:
      books.queues.remove(at.edge, queue_entry(v, false));
      ledger.set_status(v, kArrived);
      ++books.counts.cancelled;
      --books.counts.waiting;
      return;
    case Where::kNotDue: {
      // Every part skips it when it falls due; one counts it.
      ledger.set_status(v, kArrived);
      std::vector<std::pair<int64_t, uint32_t>>& added = books.schedule.added;
      std::erase_if(added, [v](const auto& a) { return a.second == v; });
      if (run_.link.leads()) ++books.counts.cancelled;
      return;
    }
    case Where::kNowhere:
    case Where::kOutside:
      return;
  }
}

}  // namespace lpsim

// Re-cutting a saved state: what each piece of a part's state becomes in the parts that resume it
// (docs/ARCHITECTURE.md, "Checkpoints"). Every saved part's state is read into its pieces; the whole
// network's state is put together from them, each lane's cells and stands from its saved owner, each signal
// from its runner, the counters summed, every vehicle on the road with its trip's account from the part that
// held it; then each resuming part takes what it owns and holds.
#include "engine/state_recut.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include "backends/backend_state.hpp"
#include "backends/vehicle_packing.hpp"
#include "engine/engine_net.hpp"
#include "engine/host_books.hpp"
#include "engine/part_link.hpp"
#include "engine/rerouting_device.hpp"
#include "engine/state_archive.hpp"
#include "kernels/lane_map.hpp"

namespace lpsim {
namespace {

// One saved part's state, read into its pieces.
struct PartPieces {
  explicit PartPieces(const Network& net) : books(net) {}
  SavedPartState saved;
  HostBooks books;
  LaneCounters lane_counters;
  PartLinkCarry carry;    // a part of a partitioned run
  uint8_t rerouting = 0;  // the run has a rerouting device: its speeds' section and what it carries
  std::vector<uint8_t> speeds;
  ReroutingCarry rerouting_carry;
  BackendState backend;
};

template <class T>
void read_piece(const std::vector<uint8_t>& bytes, T& piece, const std::string& what) {
  StateIn in(bytes.data(), bytes.size(), what);
  in(piece);
  if (!in.done()) in.fail("bytes left after its last field");
}

template <class T>
std::vector<uint8_t> write_piece(T& piece) {
  StateOut out;
  out(piece);
  return std::move(out.bytes());
}

// A vehicle on the road, as the whole network's state holds it.
struct RoadVehicle {
  uint32_t vehicle;
  Footprint footprint;
  float length;
  size_t packed;  // where its columns begin in Whole::packed
  int from_part;  // the saved part that held it
};

// The whole network's state, as a run of one part would hold it.
struct Whole {
  std::vector<RoadVehicle> vehicles;  // ascending by vehicle
  std::vector<uint8_t> packed;
  BackendTables<HostTable> tables;  // the map in the network's layout; no active list
  std::vector<std::pair<uint32_t, std::vector<uint32_t>>> queues;  // by edge, ascending
  TripLedger ledger;
  RunCounts counts;  // the run's totals, running and waiting among them
  LaneCounters lane_counters;
  PartLinkCarry totals;      // teleport events, finished trips, sums, idle (the link's part 0 totals)
  ReroutingCarry rerouting;  // waiting: every part's, ascending
};

template <class T>
void add_into(std::vector<T>& sum, const std::vector<T>& x) {
  if (sum.empty()) sum.assign(x.size(), T{});
  if (x.size() != sum.size()) throw std::runtime_error("the saved parts' counters differ in length");
  for (size_t i = 0; i < x.size(); ++i) sum[i] += x[i];
}

void add_counters(LaneCounters& sum, LaneCounters& x) {
  for (int k = 0; k < kNumLaneCounters; ++k) add_into(counter_column(sum, k), counter_column(x, k));
}

// Cells of lane l in a map of `layout` (null: the network's own layout).
uint64_t cell_begin(const Network& net, const PartPlan* layout, uint32_t l) {
  return layout ? layout->cells.cell_begin[l] : net.lane_cell_begin[l];
}

Whole put_together(std::vector<std::unique_ptr<PartPieces>>& parts, const std::vector<PartPlan>& from,
                   const RecutScope& scope) {
  const Network& net = scope.net;
  const uint32_t nl = net.num_lanes();
  const EngineNet engine_net(net);
  Whole w;
  const PartPieces& first = *parts[0];
  const bool parted = !from.empty();
  auto plan = [&](size_t q) { return parted ? &from[q] : nullptr; };

  // Tables: each lane's from its owner, each signal's from its runner, the counters summed.
  BackendTables<HostTable>& t = w.tables;
  const BackendTables<HostTable>& t0 = first.backend.tables;
  t.map.assign(net.lane_cell_begin[nl] + kLaneMapPadding, 0);
  if (!t0.junction_stand.empty()) t.junction_stand.assign(nl, kNoJunctionStand);
  for (uint32_t l = 0; l < nl; ++l) {
    const size_t q = parted ? static_cast<size_t>(from[0].lane_owner[l]) : 0;
    const BackendTables<HostTable>& tq = parts[q]->backend.tables;
    const uint64_t at = cell_begin(net, plan(q), l), n = net.lane_cell_begin[l + 1] - net.lane_cell_begin[l];
    std::copy(tq.map.begin() + static_cast<std::ptrdiff_t>(at),
              tq.map.begin() + static_cast<std::ptrdiff_t>(at + n),
              t.map.begin() + static_cast<std::ptrdiff_t>(net.lane_cell_begin[l]));
    if (!t.junction_stand.empty()) t.junction_stand[l] = tq.junction_stand[l];
  }
  t.link_state = t0.link_state;
  t.signal_next_switch_ms = t0.signal_next_switch_ms;
  t.actuated_phase = t0.actuated_phase;
  t.actuated_start_ms = t0.actuated_start_ms;
  t.det_last_ms = t0.det_last_ms;
  for (uint32_t s = 0; s < net.num_signals() && parted; ++s) {
    const int32_t runner = from[0].signal_owner[s];
    if (runner <= 0) continue;  // part 0's, or a fixed-time program every part computes alike
    const BackendTables<HostTable>& tq = parts[static_cast<size_t>(runner)]->backend.tables;
    for (uint32_t k = engine_net.link_begin[s]; k < engine_net.link_begin[s + 1]; ++k)
      t.link_state[k] = tq.link_state[k];
    t.signal_next_switch_ms[s] = tq.signal_next_switch_ms[s];
    t.actuated_phase[s] = tq.actuated_phase[s];
    t.actuated_start_ms[s] = tq.actuated_start_ms[s];
    for (uint32_t d = engine_net.signal_det_begin[s]; d < engine_net.signal_det_begin[s + 1]; ++d)
      t.det_last_ms[d] = tq.det_last_ms[d];
  }
  for (const auto& p : parts) {
    add_into(t.lane_records, p->backend.tables.lane_records);
    add_into(t.emission_sums, p->backend.tables.emission_sums);
    add_counters(w.lane_counters, p->lane_counters);
  }

  // Vehicles on the road (a slot that left the road in the saved step only clears its footprint from the
  // other lane map in the next one, and a resumed run starts with that map cleared).
  for (size_t q = 0; q < parts.size(); ++q) {
    BackendState& b = parts[q]->backend;
    const VehicleView& veh = b.vehicles.view();
    for (const uint32_t k : b.tables.active) {
      if (veh.status[k] != kRunning) continue;
      w.vehicles.push_back(RoadVehicle{veh.vehicle[k], current_footprint(veh, k),
                                       scope.demand.types.length[veh.trip_type[k]], w.packed.size(),
                                       static_cast<int>(q)});
      pack_vehicle(veh, k, w.packed);
    }
  }
  std::sort(w.vehicles.begin(), w.vehicles.end(),
            [](const RoadVehicle& a, const RoadVehicle& b) { return a.vehicle < b.vehicle; });

  // Each edge's queue is kept by its owner only.
  for (const auto& p : parts)
    p->books.queues.for_each_queue([&](uint32_t e, const uint32_t* b, const uint32_t* end) {
      w.queues.emplace_back(e, std::vector<uint32_t>(b, end));
    });
  std::sort(w.queues.begin(), w.queues.end());

  // Every trip's account from the part that holds it: on the road, queued to re-enter after a teleport,
  // ended; else every part's is the same.
  w.ledger = first.books.ledger;
  const uint32_t trips = w.ledger.size();
  std::vector<int> holder(trips, -1);
  for (const RoadVehicle& v : w.vehicles) holder[v.vehicle] = v.from_part;
  std::vector<uint8_t> requeued(trips, 0);  // queued to re-enter after a teleport
  for (const auto& [e, entries] : w.queues)
    for (const uint32_t entry : entries)
      if (entry & kInsertTeleported) requeued[entry & ~kInsertTeleported] = 1;
  for (uint32_t v = 0; v < trips; ++v) {
    // Ended in one part: ended. Teleported: the part that queues it to re-enter.
    int h = holder[v], ended = -1, queued = -1;
    for (size_t q = 0; q < parts.size() && h < 0; ++q) {
      const uint8_t st = parts[q]->books.ledger.status(v);
      if (st == kArrived && ended < 0) ended = static_cast<int>(q);
      if (st == kTeleporting && requeued[v] && queued < 0) queued = static_cast<int>(q);
    }
    if (h < 0) h = ended >= 0 ? ended : queued;
    if (h > 0) w.ledger.copy_trip(parts[static_cast<size_t>(h)]->books.ledger, v);
  }

  // The rerouting device: its speeds and schedule are the same in every part; a vehicle was last routed on
  // the latest sample any part routed it on; the routes computed are counted in part 0.
  if (first.rerouting) {
    w.rerouting = first.rerouting_carry;
    w.rerouting.waiting.clear();
    w.rerouting.reroutes = 0;
    for (const auto& p : parts) {
      const ReroutingCarry& c = p->rerouting_carry;
      if (c.routed_at.size() != w.rerouting.routed_at.size())
        throw std::runtime_error("the saved parts' rerouting devices differ in their trips");
      for (size_t v = 0; v < c.routed_at.size(); ++v)
        w.rerouting.routed_at[v] = std::max(w.rerouting.routed_at[v], c.routed_at[v]);
      w.rerouting.router_sample = std::max(w.rerouting.router_sample, c.router_sample);
      w.rerouting.departed = w.rerouting.departed || c.departed;
      w.rerouting.reroutes += c.reroutes;
      w.rerouting.waiting.insert(w.rerouting.waiting.end(), c.waiting.begin(), c.waiting.end());
    }
    std::sort(w.rerouting.waiting.begin(), w.rerouting.waiting.end());
  }

  // The counts as part 0's report sums them; its totals as it last gathered them.
  for (const auto& p : parts) {
    const RunCounts& c = p->books.counts;
    w.counts.inserted += c.inserted;
    w.counts.running += c.running;
    w.counts.waiting += c.waiting;
    w.counts.arrived += c.arrived;
    w.counts.teleports += c.teleports;
    w.counts.discarded += c.discarded;
    w.counts.cancelled += c.cancelled;
    w.counts.vehicle_updates += c.vehicle_updates;
  }
  w.counts.loaded = first.books.counts.loaded;
  w.counts.removed = first.books.counts.removed;
  if (parted) {
    w.totals = first.carry;
  } else {
    w.totals.teleport_events = first.books.teleport_events;
    w.totals.finished = first.books.ledger.finished();
    w.totals.depart_delay_sum = first.books.ledger.depart_delay_sum();
    w.totals.travel_time_sum = first.books.ledger.travel_time_sum();
    w.totals.all_idle = first.books.idle();
  }
  w.totals.inserted.clear();
  w.totals.stats = PartStats{};
  w.totals.part_stats.clear();
  w.totals.counts = w.counts;
  return w;
}

// The rerouting device's section of a part whose books are `books`: the vehicles it waits to re-route before
// they depart are those in its queues (the others departed, or were dropped, and would leave its list).
std::vector<uint8_t> rerouting_section(const Whole& w, const PartPieces& first, const HostBooks& books,
                                       size_t part) {
  StateOut out;
  uint8_t rerouting = first.rerouting;
  out(rerouting);
  if (rerouting) {
    out.raw(first.speeds);
    ReroutingCarry carry = w.rerouting;
    std::vector<uint8_t> queued(carry.routed_at.size(), 0);
    books.queues.for_each_queue([&](uint32_t, const uint32_t* b, const uint32_t* end) {
      for (; b != end; ++b)
        if (!(*b & kInsertTeleported) && *b < queued.size()) queued[*b] = 1;
    });
    std::erase_if(carry.waiting,
                  [&](const auto& x) { return x.second >= queued.size() || !queued[x.second]; });
    if (part > 0) carry.reroutes = 0;
    out(carry);
  }
  return std::move(out.bytes());
}

// The state of part `part` of `to` (a run of one part: `to` empty) from the whole network's.
std::vector<uint8_t> cut(Whole& w, const PartPieces& first_pieces, const std::vector<PartPlan>& to,
                         size_t part, const RecutScope& scope) {
  const SavedPartState& first = first_pieces.saved;
  const Network& net = scope.net;
  const uint32_t nl = net.num_lanes();
  const bool parted = !to.empty();
  const PartPlan* plan = parted ? &to[part] : nullptr;
  auto owns_lane = [&](uint32_t l) {
    return !parted || to[part].lane_owner[l] == static_cast<int32_t>(part);
  };
  auto holds_lane = [&](int32_t l) { return l >= 0 && (!parted || to[part].held[static_cast<uint32_t>(l)]); };
  auto owner_of = [&](const RoadVehicle& v) {
    return parted ? to[0].lane_owner[static_cast<uint32_t>(v.footprint.lane)] : 0;
  };

  // Backend: the cells of the lanes it holds, its vehicles in new slots (vehicle order), the sums in part 0.
  BackendState b;
  b.map_index = first.map;
  const BackendTables<HostTable>& wt = w.tables;
  b.tables.link_state = wt.link_state;
  b.tables.signal_next_switch_ms = wt.signal_next_switch_ms;
  b.tables.actuated_phase = wt.actuated_phase;
  b.tables.actuated_start_ms = wt.actuated_start_ms;
  b.tables.det_last_ms = wt.det_last_ms;
  b.tables.lane_records = wt.lane_records;
  b.tables.emission_sums = wt.emission_sums;
  b.tables.junction_stand = wt.junction_stand;
  b.tables.map.assign((parted ? plan->cells.cells : net.lane_cell_begin[nl]) + kLaneMapPadding, 0);
  for (uint32_t l = 0; l < nl; ++l) {
    if (!holds_lane(static_cast<int32_t>(l))) continue;
    const uint64_t at = net.lane_cell_begin[l], n = net.lane_cell_begin[l + 1] - at;
    std::copy(w.tables.map.begin() + static_cast<std::ptrdiff_t>(at),
              w.tables.map.begin() + static_cast<std::ptrdiff_t>(at + n),
              b.tables.map.begin() + static_cast<std::ptrdiff_t>(cell_begin(net, plan, l)));
    if (!b.tables.junction_stand.empty() && !owns_lane(l)) b.tables.junction_stand[l] = kNoJunctionStand;
  }
  if (part > 0) {
    std::fill(b.tables.lane_records.begin(), b.tables.lane_records.end(), 0);
    std::fill(b.tables.emission_sums.begin(), b.tables.emission_sums.end(), 0);
  }
  std::vector<const RoadVehicle*> mine;
  for (const RoadVehicle& v : w.vehicles)
    if (owner_of(v) == static_cast<int32_t>(part)) mine.push_back(&v);
  b.num_slots = static_cast<uint32_t>(mine.size());
  b.vehicles.reserve(mine.size(), false);
  VehicleView& veh = b.vehicles.view();
  for (uint32_t k = 0; k < b.num_slots; ++k) {
    unpack_vehicle(w.packed.data() + mine[k]->packed, veh, k);
    // Its footprint of one step ago is cleared from the other lane map, which a resumed run has cleared, and
    // may lie on lanes this part does not hold (as when it drives in from another part: adopt_vehicles).
    veh.old_lane[k] = -1;
    b.tables.active.push_back(k);
  }

  // Books: its slots, its edges' queues, the ledger as a part holding these vehicles and queues keeps it.
  HostBooks books(net);
  for (uint32_t k = 0; k < b.num_slots; ++k) books.slots.take();
  auto owns_edge = [&](uint32_t e) {
    return !parted || to[part].edge_owner[e] == static_cast<int32_t>(part);
  };
  for (const auto& [e, entries] : w.queues)
    if (owns_edge(e))
      for (const uint32_t entry : entries) books.queues.push_back(e, entry);
  books.ledger = w.ledger;
  // A teleported trip waiting to re-enter is teleporting only in the part that queues it (a part reports its
  // teleporting trips as running, unfinished); the others hold it as departed.
  std::vector<uint8_t> queued_here(books.ledger.size(), 0);
  books.queues.for_each_queue([&](uint32_t, const uint32_t* b, const uint32_t* end) {
    for (; b != end; ++b)
      if (*b & kInsertTeleported) queued_here[*b & ~kInsertTeleported] = 1;
  });
  for (uint32_t v = 0; v < books.ledger.size() && parted; ++v) {
    if (books.ledger.status(v) != kTeleporting || queued_here[v]) continue;
    books.ledger.set_status(v, kPending);
    books.ledger.drop_carried(v);  // the part that queues it carries its counters
  }
  books.counts = part == 0 ? w.counts : RunCounts{};
  books.counts.loaded = w.counts.loaded;
  books.counts.removed = w.counts.removed;
  books.counts.running = mine.size();
  books.counts.waiting = books.queues.waiting();
  books.num_active = b.num_slots;
  books.schedule = first_pieces.books.schedule;  // every part walks the whole schedule
  if (!parted) {
    books.teleport_events = w.totals.teleport_events;
    books.ledger.set_totals(w.totals.depart_delay_sum, w.totals.travel_time_sum, w.totals.finished);
  } else {
    books.ledger.set_totals(0, 0, {});
  }

  // Link: the footprints of other parts' vehicles on the lanes it holds, which it erases in two steps as if
  // their owners had sent them; part 0 keeps the run's totals.
  SavedPartState out;
  out.time_ms = first.time_ms;
  out.step = first.step;
  out.map = first.map;
  if (parted) {
    StateOut link;
    std::vector<FootprintWrite> foreign;
    for (const RoadVehicle& v : w.vehicles) {
      const Footprint& fp = v.footprint;
      if (owner_of(v) == static_cast<int32_t>(part)) continue;
      if (holds_lane(fp.lane) || holds_lane(fp.prev) || holds_lane(fp.prev2))
        foreign.push_back(FootprintWrite{fp, v.length, 0});
    }
    link(foreign);
    PartLinkCarry carry;
    if (part == 0) carry = w.totals;
    link(carry);
    out.sections[kSectionLink] = std::move(link.bytes());
  }
  out.sections[kSectionBooks] = write_piece(books);
  out.sections[kSectionRoutes] = first.sections[kSectionRoutes];  // every part holds every trip's route
  LaneCounters counters = w.lane_counters;
  if (part > 0) counters.clear();
  out.sections[kSectionLaneCounters] = write_piece(counters);
  out.sections[kSectionRerouting] = rerouting_section(w, first_pieces, books, part);
  out.sections[kSectionBackend] = encode_backend_state(b);
  return write_piece(out);
}

}  // namespace

SavedState recut_state(const SavedState& saved, const RecutScope& scope, const std::vector<PartPlan>& to) {
  const Network& net = scope.net;
  std::vector<PartPlan> from;
  if (saved.parts.size() > 1)
    from = part_plans(net, saved.edge_part, static_cast<int32_t>(saved.parts.size()), scope.longest_vehicle);
  std::vector<std::unique_ptr<PartPieces>> parts;
  for (size_t q = 0; q < saved.parts.size(); ++q) {
    const std::string what = "the saved state of part " + std::to_string(q);
    auto p = std::make_unique<PartPieces>(net);
    read_piece(saved.parts[q], p->saved, what);
    const SavedPartState& s = p->saved;
    read_piece(s.sections[kSectionBooks], p->books, what);
    read_piece(s.sections[kSectionLaneCounters], p->lane_counters, what);
    {
      StateIn in(s.sections[kSectionRerouting].data(), s.sections[kSectionRerouting].size(), what);
      in(p->rerouting);
      if (p->rerouting) {
        in.raw(p->speeds);
        in(p->rerouting_carry);
      }
      if (!in.done()) in.fail("bytes left after the rerouting device's state");
    }
    if (!from.empty()) {
      StateIn in(s.sections[kSectionLink].data(), s.sections[kSectionLink].size(), what);
      std::vector<FootprintWrite> foreign;
      in(foreign);
      in(p->carry);
      if (!in.done()) in.fail("bytes left after the link's state");
    }
    decode_backend_state(s.sections[kSectionBackend], p->books.slots.size(), p->backend);
    parts.push_back(std::move(p));
  }
  Whole whole = put_together(parts, from, scope);
  SavedState out;
  if (!to.empty()) out.edge_part = to[0].edge_owner;
  const size_t n = to.empty() ? 1 : to.size();
  for (size_t part = 0; part < n; ++part) out.parts.push_back(cut(whole, *parts[0], to, part, scope));
  return out;
}

}  // namespace lpsim

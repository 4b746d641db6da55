// The rounds a part of a partitioned run makes with the other parts at the points of its step where their
// states meet (docs/ARCHITECTURE.md, "Partitions"), and part 0's gathering of what the outputs read. Every
// part makes the same rounds in the same order, each with the parts that share a lane with it; whatever
// crosses a cut is merged by an order-free rule (footprints others wrote are erased before the map is written
// again, the largest claim wins, vehicles and teleports are taken in vehicle order), so every part's lanes
// read as in one whole network.
#include "engine/part_link.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>

#include "backends/vehicle_packing.hpp"
#include "kernels/lane_map.hpp"
#include "kernels/vehicle_step.hpp"
#include "transport/byte_buffer.hpp"

namespace lpsim {

std::vector<Bytes> PartLink::round(const std::vector<int>& to, const std::vector<Bytes>& send,
                                   const std::vector<int>& from, const char* what, bool exchange) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Bytes> got = transport_.exchange(to, send, from, what);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (exchange) {
    for (const Bytes& b : send) carry_.stats.bytes_sent += b.size();
    ++carry_.stats.rounds;
    carry_.stats.exchange_seconds += s;
  } else {
    carry_.stats.gather_seconds += s;
  }
  return got;
}

namespace {

// Buffers for a round with each neighbour, by part.
class Outbox {
 public:
  explicit Outbox(const std::vector<int>& to) : to_(to), bytes_(to.size()) {}
  Bytes& to(int part) {
    const auto it = std::lower_bound(to_.begin(), to_.end(), part);
    if (it == to_.end() || *it != part)
      throw std::logic_error("part " + std::to_string(part) + " is not a neighbour of this part");
    return bytes_[static_cast<size_t>(it - to_.begin())];
  }
  const std::vector<Bytes>& all() const { return bytes_; }

 private:
  const std::vector<int>& to_;
  std::vector<Bytes> bytes_;
};

// Out of the hand-out's loop, so that the check costs it no inlining.
[[noreturn, gnu::cold, gnu::noinline]] void not_a_neighbour(const std::string& vehicle, int part, int other) {
  throw std::logic_error("vehicle " + vehicle + " of part " + std::to_string(part) +
                         " lies on a lane of part " + std::to_string(other) + ", which is not its neighbour");
}

// Calls each(p), ascending, for every part p other than this one that holds a lane of footprint fp (a vehicle
// `length` metres long).
template <class Each>
void for_each_other_holder(const PartPlan& plan, const NetView& net, const Footprint& fp, float length,
                           Each each) {
  constexpr int kMost = 64;
  int32_t seen[kMost];
  int n = 0;
  for_each_footprint_piece(net, fp, length, [&](int32_t lane, uint32_t, uint32_t) {
    for (uint32_t h = plan.holder_begin[lane]; h < plan.holder_begin[lane + 1]; ++h) {
      const int32_t p = plan.holders[h];
      int at = 0;
      while (at < n && seen[at] < p) ++at;
      if (p == plan.part || (at < n && seen[at] == p)) continue;
      if (n == kMost) throw std::length_error("a footprint's lanes are held by more than 64 parts");
      for (int j = n; j > at; --j) seen[j] = seen[j - 1];
      seen[at] = p;
      ++n;
    }
  });
  for (int i = 0; i < n; ++i) each(seen[i]);
}

}  // namespace

std::vector<int> part_neighbours(const PartPlan& plan) {
  std::vector<uint8_t> neighbour(static_cast<size_t>(plan.parts), 0);
  for (const uint32_t l : plan.shared_lanes)
    for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
      neighbour[static_cast<size_t>(plan.holders[h])] = 1;
  std::vector<int> out;
  for (int p = 0; p < plan.parts; ++p)
    if (neighbour[static_cast<size_t>(p)] && p != plan.part) out.push_back(p);
  return out;
}

PartLink::PartLink(const LinkScope& run, const PartPlan& plan, Transport& transport,
                   std::function<int()> pending_signal)
    : BoundaryLink(run), plan_(plan), transport_(transport), pending_signal_(std::move(pending_signal)) {
  const Network& net = run_.net;
  if (plan.parts != transport.size() || plan.part != transport.rank())
    throw std::invalid_argument("part " + std::to_string(plan.part) + " of " + std::to_string(plan.parts) +
                                " on rank " + std::to_string(transport.rank()) + " of " +
                                std::to_string(transport.size()));
  held_lanes_ = plan.held.data();
  alone_ = plan.held;
  for (const uint32_t l : plan.shared_lanes) alone_[l] = 0;
  for (const uint32_t l : plan.shared_lanes)
    if (plan.lane_owner[l] == plan.part) owned_shared_.push_back(l);
  neighbours_ = part_neighbours(plan);
  neighbour_at_.assign(static_cast<size_t>(plan.parts), -1);
  for (size_t n = 0; n < neighbours_.size(); ++n)
    neighbour_at_[static_cast<size_t>(neighbours_[n])] = static_cast<int32_t>(n);
  footprints_out_.resize(neighbours_.size());
  // An actuated signal's owner sends its state to every part holding a lane one of its links leaves.
  std::vector<std::vector<uint8_t>> reads(net.num_signals());
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    const int32_t sig = net.conn_signal[c];
    if (sig < 0 || plan.signal_owner[static_cast<uint32_t>(sig)] < 0) continue;
    std::vector<uint8_t>& r = reads[static_cast<uint32_t>(sig)];
    r.resize(static_cast<size_t>(plan.parts), 0);
    const uint32_t l = net.conn_from_lane[c];
    for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
      r[static_cast<size_t>(plan.holders[h])] = 1;
  }
  std::vector<uint8_t> readers(static_cast<size_t>(plan.parts), 0),
      owners(static_cast<size_t>(plan.parts), 0);
  for (uint32_t sig = 0; sig < net.num_signals(); ++sig) {
    const int32_t owner = plan.signal_owner[sig];
    if (owner < 0) continue;
    bool read_elsewhere = false;
    for (int p = 0; p < plan.parts; ++p) {
      if (p == owner || !reads[sig][static_cast<size_t>(p)]) continue;
      read_elsewhere = true;
      if (owner == plan.part) readers[static_cast<size_t>(p)] = 1;
      if (p == plan.part) owners[static_cast<size_t>(owner)] = 1;
    }
    if (owner == plan.part && read_elsewhere) signals_sent_.push_back(sig);
    signal_round_ = signal_round_ || read_elsewhere;
  }
  if (!net.det_lane.empty())
    for (uint32_t sig = 0; sig < net.num_signals(); ++sig)
      for (uint32_t d = net.signal_det_begin[sig]; d < net.signal_det_begin[sig + 1]; ++d)
        if (plan.signal_owner[sig] >= 0 && plan.lane_owner[net.det_lane[d]] != plan.signal_owner[sig])
          insertion_round_ = true;
  for (int p = 0; p < plan.parts; ++p) {
    if (readers[static_cast<size_t>(p)]) signal_readers_.push_back(p);
    if (owners[static_cast<size_t>(p)]) signal_owners_.push_back(p);
  }
}

std::vector<int> PartLink::others() const {
  std::vector<int> out;
  for (int p = 1; p < plan_.parts; ++p) out.push_back(p);
  return out;
}

void PartLink::begin_step() {
  if (plan_.part == 0) request(kRequestStep);
}

void PartLink::after_signals() {
  if (!signal_round_) return;  // every part knows this alike: no part sends or waits
  Bytes mine;
  ByteWriter w(mine);
  std::vector<char> chars;
  for (const uint32_t s : signals_sent_) {
    const uint32_t begin = run_.engine_net.link_begin[s], count = run_.engine_net.link_begin[s + 1] - begin;
    chars.resize(count);
    run_.stepper.read_link_states(begin, count, chars.data());
    w.put(s);
    w.put_array(chars);
  }
  const std::vector<Bytes> got = round(signal_readers_, std::vector<Bytes>(signal_readers_.size(), mine),
                                       signal_owners_, "signals", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    while (!r.done()) {
      const uint32_t s = r.get<uint32_t>();
      const std::vector<char> c = r.get_array<char>();
      run_.stepper.write_link_states(run_.engine_net.link_begin[s], static_cast<uint32_t>(c.size()),
                                     c.data());
    }
  }
}

// After approach: the first vehicles of the lanes each part owns that others hold (right of way at the
// junctions those see), and, unless they went in their own round, the footprints of the vehicles it
// inserted at the end of the last step on lanes others hold (the approach pass reads only a vehicle's own
// edge; the plan reads ghosts).
void PartLink::after_approach(uint32_t step, int read_map) {
  const PartPlan& plan = plan_;
  std::vector<LaneApproach> entries;
  run_.stepper.read_approaches(owned_shared_, entries);
  Outbox out(neighbours_);
  for (const int p : neighbours_) {
    ByteWriter w(out.to(p));
    std::vector<uint32_t> lanes;
    std::vector<LaneApproach> sent;
    for (size_t i = 0; i < owned_shared_.size(); ++i) {
      const uint32_t l = owned_shared_[i];
      if (entries[i].step != step) continue;
      for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
        if (plan.holders[h] == p) lanes.push_back(l), sent.push_back(entries[i]);
    }
    w.put_array(lanes);
    w.put_array(sent);
    if (!insertion_round_) w.put_array(carry_.inserted[p]);
  }
  carry_.inserted.clear();
  const std::vector<Bytes> got = round(neighbours_, out.all(), neighbours_, "approaches", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    const std::vector<uint32_t> lanes = r.get_array<uint32_t>();
    run_.stepper.write_approaches(lanes, r.get_array<LaneApproach>());
    if (!insertion_round_) write_foreign(read_map, r.get_array<FootprintWrite>());
  }
}

void PartLink::after_plan(uint32_t step) {
  const PartPlan& plan = plan_;
  std::vector<uint64_t> claims;
  run_.stepper.read_claims(plan.shared_lanes, claims);
  const uint64_t this_step = step & 0xFFFFFFu;
  Outbox out(neighbours_);
  std::map<int, std::pair<std::vector<uint32_t>, std::vector<uint64_t>>> sent;
  for (size_t i = 0; i < plan.shared_lanes.size(); ++i) {
    if ((claims[i] >> 40) != this_step || claims[i] == 0) continue;
    const uint32_t l = plan.shared_lanes[i];
    for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h) {
      const int p = plan.holders[h];
      if (p == plan.part) continue;
      sent[p].first.push_back(l);
      sent[p].second.push_back(claims[i]);
    }
  }
  for (const int p : neighbours_) {
    ByteWriter w(out.to(p));
    w.put_array(sent[p].first);
    w.put_array(sent[p].second);
  }
  const std::vector<Bytes> got = round(neighbours_, out.all(), neighbours_, "claims", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    const std::vector<uint32_t> lanes = r.get_array<uint32_t>();
    run_.stepper.merge_claims(lanes, r.get_array<uint64_t>());
  }
}

// After the end of step: the footprints written on lanes others hold, the vehicles whose front entered
// another part's lane (with their slot's columns and departure) and the teleported vehicles whose re-entry
// edge another part owns.
void PartLink::after_end_of_step(int map) {
  const PartPlan& plan = plan_;
  const NetView net = run_.engine_net.view(run_.net);
  TripLedger& ledger = run_.books.ledger;
  for (std::vector<FootprintWrite>& w : footprints_out_) w.clear();
  std::map<int, Bytes> migrants;
  std::map<int, std::vector<uint32_t>> migrant_ids;
  std::map<int, std::vector<DepartRecord>> migrant_departures;
  const std::vector<uint32_t> gone = hand_out(map, [&](const HostState& st, uint32_t k, const Footprint& fp,
                                                       float len) {
    // Most vehicles: a footprint no other part holds a lane of (its pieces are on these lanes only).
    if (alone_[static_cast<uint32_t>(fp.lane)] && (fp.prev < 0 || alone_[static_cast<uint32_t>(fp.prev)]) &&
        (fp.prev2 < 0 || alone_[static_cast<uint32_t>(fp.prev2)]))
      return false;
    const uint8_t value = encode_cell_speed(st.veh.speed[k]);
    for_each_other_holder(plan, net, fp, len, [&](int p) {
      // Every other holder of a lane this part holds is a neighbour (part_neighbours), and a vehicle's
      // footprint lies on lanes its part holds (its ghosts reach a vehicle length behind its lanes).
      const int32_t at = neighbour_at_[static_cast<size_t>(p)];
      if (at < 0) not_a_neighbour(run_.trips.demand().vehicle_id[st.veh.vehicle[k]], plan.part, p);
      footprints_out_[static_cast<size_t>(at)].push_back(FootprintWrite{fp, len, value});
    });
    const int32_t owner = plan.lane_owner[static_cast<uint32_t>(fp.lane)];
    if (owner == plan.part) return false;
    const uint32_t v = st.veh.vehicle[k];
    pack_vehicle(st.veh, k, migrants[owner]);
    migrant_ids[owner].push_back(v);
    migrant_departures[owner].push_back(ledger.departure(v));
    return true;
  });
  carry_.stats.migrations += gone.size();

  std::vector<TeleportHandOver> teleports;
  std::map<int, std::vector<TeleportHandOver>> teleports_out;
  for (const TeleportHandOver& t : teleports_) {
    const int owner = plan.edge_owner[t.edge];
    (owner == plan.part ? teleports : teleports_out[owner]).push_back(t);
  }
  teleports_.clear();

  Outbox out(neighbours_);
  for (size_t n = 0; n < neighbours_.size(); ++n) {
    const int p = neighbours_[n];
    const std::vector<FootprintWrite>& writes = footprints_out_[n];
    Bytes& bytes = out.to(p);
    // Sized at once: the footprints are most of it, tens of kilobytes a step on a congested cut.
    bytes.reserve(5 * sizeof(uint64_t) + writes.size() * sizeof(FootprintWrite) +
                  migrant_ids[p].size() * (sizeof(uint32_t) + sizeof(DepartRecord)) + migrants[p].size() +
                  teleports_out[p].size() * sizeof(TeleportHandOver));
    ByteWriter w(bytes);
    w.put_array(writes);
    w.put_array(migrant_ids[p]);
    w.put_array(migrant_departures[p]);
    w.put_array(migrants[p]);
    w.put_array(teleports_out[p]);
  }
  const std::vector<Bytes> got = round(neighbours_, out.all(), neighbours_, "vehicles", true);

  struct Incoming {
    uint32_t vehicle;
    DepartRecord departure;
    const uint8_t* columns;
  };
  std::vector<Incoming> incoming;
  std::vector<std::vector<uint8_t>> columns(got.size());
  for (size_t g = 0; g < got.size(); ++g) {
    ByteReader r(got[g]);
    write_foreign(map, r.get_array<FootprintWrite>());
    const std::vector<uint32_t> ids = r.get_array<uint32_t>();
    const std::vector<DepartRecord> deps = r.get_array<DepartRecord>();
    columns[g] = r.get_array<uint8_t>();
    for (size_t i = 0; i < ids.size(); ++i)
      incoming.push_back(Incoming{ids[i], deps[i], columns[g].data() + i * packed_vehicle_bytes()});
    for (const TeleportHandOver& t : r.get_array<TeleportHandOver>()) teleports.push_back(t);
  }
  // Slots handed out in vehicle order, so that a part's slots do not depend on the order of its neighbours.
  std::sort(incoming.begin(), incoming.end(),
            [](const Incoming& a, const Incoming& b) { return a.vehicle < b.vehicle; });
  adopted_.clear();
  std::vector<uint8_t> packed;
  for (const Incoming& in : incoming) {
    const uint32_t k = run_.books.slots.take();
    adopted_.push_back(k);
    ledger.set_departure(in.vehicle, in.departure);
    packed.insert(packed.end(), in.columns, in.columns + packed_vehicle_bytes());
  }
  run_.stepper.adopt_vehicles(adopted_, packed);

  // As one part queues them (Simulation::handle_vehicle_ends): each at the head of its edge's queue, in
  // vehicle order.
  std::sort(teleports.begin(), teleports.end(), [](const TeleportHandOver& a, const TeleportHandOver& b) {
    return a.end.vehicle < b.end.vehicle;
  });
  for (const TeleportHandOver& t : teleports) {
    ledger.set_departure(t.end.vehicle, t.departure);
    ledger.teleporting(t.end, t.route_pos);
    run_.books.queues.push_front(t.edge, queue_entry(t.end.vehicle, true));
  }
}

// After insertion into lane map `map`: the footprints of the vehicles this part inserted on lanes others
// hold, sent with the next step's approaches, or at once in a round of their own where an actuated signal
// reads a loop on another part's lane (the signals are updated before the approaches go).
void PartLink::after_insertion(int map) {
  const NetView net = run_.engine_net.view(run_.net);
  const Demand& d = run_.trips.demand();
  for (const SlotInit& in : run_.books.inits) {
    const Footprint fp{in.lane, -1, -1, in.pos};
    const float len = d.types.length[d.vehicle_type[in.vehicle]];
    const FootprintWrite fw{fp, len, encode_cell_speed(in.speed)};
    for_each_other_holder(plan_, net, fp, len, [&](int p) { carry_.inserted[p].push_back(fw); });
  }
  if (!insertion_round_) return;
  Outbox out(neighbours_);
  for (const int p : neighbours_) ByteWriter(out.to(p)).put_array(carry_.inserted[p]);
  carry_.inserted.clear();
  const std::vector<Bytes> got = round(neighbours_, out.all(), neighbours_, "insertions", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    write_foreign(map, r.get_array<FootprintWrite>());
  }
}

// The vehicles that drove in from other parts join the active list; those that drove out ran in the step.
int64_t PartLink::settle_crossings(std::vector<uint32_t>& added) {
  const int64_t net = static_cast<int64_t>(adopted_.size()) - static_cast<int64_t>(left_);
  added.insert(added.end(), adopted_.begin(), adopted_.end());
  adopted_.clear();
  left_ = 0;
  return net;
}

void PartLink::count_step(double seconds) {
  ++carry_.stats.steps;
  carry_.stats.vehicle_updates = run_.books.counts.vehicle_updates;
  carry_.stats.step_seconds += seconds;
}

// The edge's owner queues the departure; the others never see it.
bool PartLink::takes_departure(uint32_t /*v*/, uint32_t edge) { return !owns_edge(edge); }

// Every part queues the teleports it is handed in one order (after_end_of_step), its own among them.
bool PartLink::takes_reentry(const VehicleEnd& end, uint32_t rp, uint32_t edge) {
  teleports_.push_back(TeleportHandOver{end, rp, edge, run_.books.ledger.departure(end.vehicle)});
  return true;
}

// Every part's counts, ended trips, teleports and departures of the step, to part 0, which sums them in the
// order one part would (trips and teleports by vehicle, departures by edge and queue position).
void PartLink::report() {
  HostBooks& books = run_.books;
  Bytes mine;
  ByteWriter w(mine);
  w.put(books.counts);
  w.put<uint8_t>(books.idle() ? 1 : 0);
  w.put_array(books.ledger.take_finished());
  w.put_array(books.teleport_events);
  w.put_array(departures_);
  departures_.clear();
  w.put(carry_.stats);
  w.put<int32_t>(pending_signal_ ? pending_signal_() : 0);
  const std::vector<Bytes> all = gather(mine, "report");
  if (all.empty()) return;
  RunCounts sum;
  bool idle = true;
  std::vector<TripRecord> ended;
  std::vector<TeleportEvent> events;
  std::vector<DepartDelay> departures;
  carry_.part_stats.clear();
  for (const Bytes& b : all) {
    ByteReader r(b);
    const RunCounts c = r.get<RunCounts>();
    sum.inserted += c.inserted;
    sum.running += c.running;
    sum.waiting += c.waiting;
    sum.arrived += c.arrived;
    sum.teleports += c.teleports;
    sum.discarded += c.discarded;
    sum.cancelled += c.cancelled;
    sum.vehicle_updates += c.vehicle_updates;
    const bool part_idle = r.get<uint8_t>() != 0;
    idle = idle && part_idle;
    for (const TripRecord& t : r.get_array<TripRecord>()) ended.push_back(t);
    for (const TeleportEvent& t : r.get_array<TeleportEvent>()) events.push_back(t);
    for (const DepartDelay& dep : r.get_array<DepartDelay>()) departures.push_back(dep);
    carry_.part_stats.push_back(r.get<PartStats>());
    const int32_t signal = r.get<int32_t>();
    if (signal_ == 0) signal_ = signal;
  }
  // Loaded and removed trips are counted where every part counts them alike: part 0's own.
  sum.loaded = books.counts.loaded;
  sum.removed = books.counts.removed;
  carry_.counts = sum;
  carry_.all_idle = idle;
  // By arrival, then vehicle: a step's trips all end at its time, those a command removed before it earlier.
  std::sort(ended.begin(), ended.end(), [](const TripRecord& a, const TripRecord& b) {
    return a.arrival != b.arrival ? a.arrival < b.arrival : a.vehicle < b.vehicle;
  });
  for (const TripRecord& t : ended) {
    carry_.travel_time_sum += t.arrival - t.depart;
    carry_.finished.push_back(t);
  }
  std::sort(events.begin(), events.end(),
            [](const TeleportEvent& a, const TeleportEvent& b) { return a.vehicle < b.vehicle; });
  carry_.teleport_events = std::move(events);
  std::sort(departures.begin(), departures.end(),
            [](const DepartDelay& a, const DepartDelay& b) { return a.order < b.order; });
  for (const DepartDelay& dep : departures) carry_.depart_delay_sum += dep.delay;
}

std::vector<TripRecord> PartLink::take_finished() {
  std::vector<TripRecord> out;
  out.swap(carry_.finished);
  return out;
}

// The running vehicles of every part, at part 0, ascending by vehicle.
const std::vector<SampleEntry>& PartLink::running_vehicles(uint64_t version) {
  if (plan_.part == 0) {
    if (sample_version_ == version) return sample_;  // gathered for this state already
    sample_version_ = version;
    request(kRequestSample);
  }
  Bytes b;
  ByteWriter(b).put_array(own_running());
  const std::vector<Bytes> all = gather(b, "sample");
  if (all.empty()) return sample_;
  sample_.clear();
  for (const Bytes& x : all) {
    ByteReader r(x);
    for (const SampleEntry& e : r.get_array<SampleEntry>()) sample_.push_back(e);
  }
  std::sort(sample_.begin(), sample_.end(),
            [](const SampleEntry& a, const SampleEntry& b) { return a.vehicle < b.vehicle; });
  return sample_;
}

// Part 0 asks every other part to do `what` (Simulation::serve_part).
void PartLink::request(PartRequest what) {
  if (plan_.part != 0) return;
  const std::vector<int> to = others();
  round(to, std::vector<Bytes>(to.size(), Bytes{static_cast<uint8_t>(what)}), {}, "request", false);
}

PartRequest PartLink::next_request() {
  if (plan_.part == 0) return BoundaryLink::next_request();
  const std::vector<Bytes> got = round({}, {}, {0}, "request", false);
  const uint8_t what = got.at(0).empty() ? 0 : got[0][0];
  if (what < kRequestStep || what > kRequestCommands)
    throw std::logic_error("part " + std::to_string(plan_.part) + ": unknown request " +
                           std::to_string(what));
  return static_cast<PartRequest>(what);
}

std::vector<Bytes> PartLink::gather(const Bytes& mine, const char* what) {
  if (plan_.part == 0) {
    std::vector<Bytes> got = round({}, {}, others(), what, false);
    got.insert(got.begin(), mine);
    return got;
  }
  round({0}, {mine}, {}, what, false);
  return {};
}

Bytes PartLink::scatter(const std::vector<Bytes>& each, const char* what) {
  if (plan_.part == 0) {
    if (each.size() != static_cast<size_t>(plan_.parts))
      throw std::logic_error(std::string(what) + ": " + std::to_string(each.size()) + " pieces for " +
                             std::to_string(plan_.parts) + " parts");
    round(others(), std::vector<Bytes>(each.begin() + 1, each.end()), {}, what, false);
    return each[0];
  }
  return round({}, {}, {0}, what, false).at(0);
}

// A vehicle inserted in the last step and removed before its neighbours saw it: they never will.
void PartLink::erase_removed(int map, const FootprintWrite& fp) {
  BoundaryLink::erase_removed(map, fp);
  for (auto& [p, writes] : carry_.inserted)
    std::erase_if(writes, [&](const FootprintWrite& w) {
      return w.fp.lane == fp.fp.lane && w.fp.pos == fp.fp.pos && w.length == fp.length;
    });
}

// Between steps the link carries the footprints it has to erase and what PartLinkCarry lists; what a step
// hands on between its rounds is empty then.
template <class A>
void PartLink::visit_state(A& a, int map) {
  if (!teleports_.empty() || !adopted_.empty() || !departures_.empty())
    a.fail("a part's step has not handed on everything");
  visit_foreign(a, map);
  a(carry_);
}

std::vector<Bytes> PartLink::allgather(const Bytes& mine, const char* what) {
  return transport_.allgather(mine, what);
}

Bytes PartLink::broadcast(const Bytes& root, const char* what) {
  if (plan_.part == 0) {
    const std::vector<int> to = others();
    round(to, std::vector<Bytes>(to.size(), root), {}, what, false);
    return root;
  }
  return round({}, {}, {0}, what, false).at(0);
}

}  // namespace lpsim

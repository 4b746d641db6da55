// The rounds a part of a partitioned run makes with the other parts at the points of its step where their
// states meet (docs/ARCHITECTURE.md, "Partitions"), and part 0's gathering of what the outputs read. Every
// part makes the same rounds in the same order, each with the parts that share a lane with it; whatever
// crosses a cut is merged by an order-free rule (footprints others wrote are erased before the map is written
// again, the largest claim wins, vehicles and teleports are taken in vehicle order), so every part's lanes
// read as in one whole network.
#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>

#include "backends/vehicle_packing.hpp"
#include "engine/part_state.hpp"
#include "engine/simulation.hpp"
#include "kernels/lane_map.hpp"
#include "kernels/vehicle_step.hpp"
#include "transport/byte_buffer.hpp"

namespace lpsim {

std::vector<Bytes> PartState::round(const std::vector<int>& to, const std::vector<Bytes>& send,
                                    const std::vector<int>& from, const char* what, bool exchange) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Bytes> got = transport.exchange(to, send, from, what);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (exchange) {
    for (const Bytes& b : send) stats.bytes_sent += b.size();
    ++stats.rounds;
    stats.exchange_seconds += s;
  } else {
    stats.gather_seconds += s;
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

void Simulation::init_parts() {
  parts_ = std::make_unique<PartState>(*opt_.part, *opt_.transport);
  PartState& ps = *parts_;
  const PartPlan& plan = ps.plan;
  if (plan.parts != ps.transport.size() || plan.part != ps.transport.rank())
    throw std::invalid_argument("part " + std::to_string(plan.part) + " of " + std::to_string(plan.parts) +
                                " on rank " + std::to_string(ps.transport.rank()) + " of " +
                                std::to_string(ps.transport.size()));
  std::vector<uint8_t> neighbour(static_cast<size_t>(plan.parts), 0);
  for (const uint32_t l : plan.shared_lanes) {
    for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
      neighbour[static_cast<size_t>(plan.holders[h])] = 1;
    if (plan.lane_owner[l] == plan.part) ps.owned_shared.push_back(l);
  }
  for (int p = 0; p < plan.parts; ++p)
    if (neighbour[static_cast<size_t>(p)] && p != plan.part) ps.neighbours.push_back(p);
  // An actuated signal's owner sends its state to every part holding a lane one of its links leaves.
  std::vector<std::vector<uint8_t>> reads(net_.num_signals());
  for (uint32_t c = 0; c < net_.num_connections(); ++c) {
    const int32_t sig = net_.conn_signal[c];
    if (sig < 0 || plan.signal_owner[static_cast<uint32_t>(sig)] < 0) continue;
    std::vector<uint8_t>& r = reads[static_cast<uint32_t>(sig)];
    r.resize(static_cast<size_t>(plan.parts), 0);
    const uint32_t l = net_.conn_from_lane[c];
    for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
      r[static_cast<size_t>(plan.holders[h])] = 1;
  }
  std::vector<uint8_t> readers(static_cast<size_t>(plan.parts), 0),
      owners(static_cast<size_t>(plan.parts), 0);
  for (uint32_t sig = 0; sig < net_.num_signals(); ++sig) {
    const int32_t owner = plan.signal_owner[sig];
    if (owner < 0) continue;
    bool read_elsewhere = false;
    for (int p = 0; p < plan.parts; ++p) {
      if (p == owner || !reads[sig][static_cast<size_t>(p)]) continue;
      read_elsewhere = true;
      if (owner == plan.part) readers[static_cast<size_t>(p)] = 1;
      if (p == plan.part) owners[static_cast<size_t>(owner)] = 1;
    }
    if (owner == plan.part && read_elsewhere) ps.signals_sent.push_back(sig);
    ps.signal_round = ps.signal_round || read_elsewhere;
  }
  if (!net_.det_lane.empty())
    for (uint32_t sig = 0; sig < net_.num_signals(); ++sig)
      for (uint32_t d = net_.signal_det_begin[sig]; d < net_.signal_det_begin[sig + 1]; ++d)
        if (plan.signal_owner[sig] >= 0 && plan.lane_owner[net_.det_lane[d]] != plan.signal_owner[sig])
          ps.insertion_round = true;
  for (int p = 0; p < plan.parts; ++p) {
    if (readers[static_cast<size_t>(p)]) ps.signal_readers.push_back(p);
    if (owners[static_cast<size_t>(p)]) ps.signal_owners.push_back(p);
  }
}

void Simulation::share_signals() {
  PartState& ps = *parts_;
  if (!ps.signal_round) return;  // every part knows this alike: no part sends or waits
  Bytes mine;
  ByteWriter w(mine);
  std::vector<char> chars;
  for (const uint32_t s : ps.signals_sent) {
    const uint32_t begin = engine_net_.link_begin[s], count = engine_net_.link_begin[s + 1] - begin;
    chars.resize(count);
    stepper_->read_link_states(begin, count, chars.data());
    w.put(s);
    w.put_array(chars);
  }
  const std::vector<Bytes> got =
      ps.round(ps.signal_readers, std::vector<Bytes>(ps.signal_readers.size(), mine), ps.signal_owners,
               "signals", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    while (!r.done()) {
      const uint32_t s = r.get<uint32_t>();
      const std::vector<char> c = r.get_array<char>();
      stepper_->write_link_states(engine_net_.link_begin[s], static_cast<uint32_t>(c.size()), c.data());
    }
  }
}

// Writes footprints other parts sent into lane map `map` and keeps them: the step that writes that map again
// clears them (forget_remote_footprints), as the parts of their vehicles clear them in theirs, so that no
// part needs to be told what another cleared.
void Simulation::apply_remote_footprints(int map, const std::vector<FootprintWrite>& writes) {
  if (writes.empty()) return;
  stepper_->write_footprints(map, writes, parts_->plan.held.data());
  std::vector<FootprintWrite>& kept = parts_->remote_footprints[map];
  for (const FootprintWrite& w : writes) kept.push_back(FootprintWrite{w.fp, w.length, 0});
}

// Before the step writes lane map `map`: the footprints kept for it (apply_remote_footprints, and those of
// the vehicles that left for another part) are gone, as each part's clear pass erases its own vehicles'.
void Simulation::forget_remote_footprints(int map) {
  std::vector<FootprintWrite>& kept = parts_->remote_footprints[map];
  if (!kept.empty()) stepper_->write_footprints(map, kept, parts_->plan.held.data());
  kept.clear();
}

// After approach: the first vehicles of the lanes each part owns that others hold (right of way at the
// junctions those see), and, unless they went in their own round, the footprints of the vehicles it
// inserted at the end of the last step on lanes others hold (the approach pass reads only a vehicle's own
// edge; the plan reads ghosts).
void Simulation::share_approaches() {
  PartState& ps = *parts_;
  const PartPlan& plan = ps.plan;
  std::vector<LaneApproach> entries;
  stepper_->read_approaches(ps.owned_shared, entries);
  Outbox out(ps.neighbours);
  for (const int p : ps.neighbours) {
    ByteWriter w(out.to(p));
    std::vector<uint32_t> lanes;
    std::vector<LaneApproach> sent;
    for (size_t i = 0; i < ps.owned_shared.size(); ++i) {
      const uint32_t l = ps.owned_shared[i];
      if (entries[i].step != step_) continue;
      for (uint32_t h = plan.holder_begin[l]; h < plan.holder_begin[l + 1]; ++h)
        if (plan.holders[h] == p) lanes.push_back(l), sent.push_back(entries[i]);
    }
    w.put_array(lanes);
    w.put_array(sent);
    if (!ps.insertion_round) w.put_array(ps.inserted[p]);
  }
  ps.inserted.clear();
  const std::vector<Bytes> got = ps.round(ps.neighbours, out.all(), ps.neighbours, "approaches", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    const std::vector<uint32_t> lanes = r.get_array<uint32_t>();
    stepper_->write_approaches(lanes, r.get_array<LaneApproach>());
    if (!ps.insertion_round) apply_remote_footprints(cur_, r.get_array<FootprintWrite>());
  }
}

void Simulation::share_claims() {
  PartState& ps = *parts_;
  const PartPlan& plan = ps.plan;
  std::vector<uint64_t> claims;
  stepper_->read_claims(plan.shared_lanes, claims);
  const uint64_t this_step = step_ & 0xFFFFFFu;
  Outbox out(ps.neighbours);
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
  for (const int p : ps.neighbours) {
    ByteWriter w(out.to(p));
    w.put_array(sent[p].first);
    w.put_array(sent[p].second);
  }
  const std::vector<Bytes> got = ps.round(ps.neighbours, out.all(), ps.neighbours, "claims", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    const std::vector<uint32_t> lanes = r.get_array<uint32_t>();
    stepper_->merge_claims(lanes, r.get_array<uint64_t>());
  }
}

// After the end of step: the footprints written on lanes others hold, the vehicles whose front entered
// another part's lane (with their slot's columns and departure) and the teleported vehicles whose re-entry
// edge another part owns.
void Simulation::exchange_vehicles() {
  PartState& ps = *parts_;
  const PartPlan& plan = ps.plan;
  const NetView net = engine_net_.view(net_);
  const float* length = trips_.demand().types.length.data();
  const HostState& st = stepper_->fetch(StateParts::Columns, slots_.size());
  std::map<int, std::vector<FootprintWrite>> writes;
  std::map<int, Bytes> migrants;
  std::map<int, std::vector<uint32_t>> migrant_ids;
  std::map<int, std::vector<DepartRecord>> migrant_departures;
  std::vector<uint32_t> gone;
  for (uint32_t i = 0; i < st.num_active; ++i) {
    const uint32_t k = st.active[i];
    if (st.veh.status[k] != kRunning) continue;
    const Footprint fp{st.veh.lane[k], st.veh.prev[k], st.veh.prev2[k], st.veh.pos[k]};
    const float len = length[st.veh.trip_type[k]];
    const uint8_t value = encode_cell_speed(st.veh.speed[k]);
    for_each_other_holder(plan, net, fp, len, [&](int p) {
      writes[p].push_back(FootprintWrite{fp, len, value});
    });
    const int32_t owner = plan.lane_owner[static_cast<uint32_t>(fp.lane)];
    if (owner == plan.part) continue;
    const uint32_t v = st.veh.vehicle[k];
    // Its footprint now is this part's to clear when this map is next written (its slot here stops after
    // clearing the one before; its new part clears this one in its own map).
    ps.remote_footprints[1 - cur_].push_back(FootprintWrite{fp, len, 0});
    pack_vehicle(st.veh, k, migrants[owner]);
    migrant_ids[owner].push_back(v);
    migrant_departures[owner].push_back(ledger_.departure(v));
    gone.push_back(k);
  }
  if (!gone.empty()) stepper_->mark_migrated(gone);
  ps.stats.migrations += gone.size();
  for (const uint32_t k : gone) retiring_next_.push_back(k);
  ps.migrated = static_cast<uint32_t>(gone.size());

  std::vector<TeleportHandOver> teleports;
  std::map<int, std::vector<TeleportHandOver>> teleports_out;
  for (const TeleportHandOver& t : ps.teleports) {
    const int owner = plan.edge_owner[t.edge];
    (owner == plan.part ? teleports : teleports_out[owner]).push_back(t);
  }
  ps.teleports.clear();

  Outbox out(ps.neighbours);
  for (const int p : ps.neighbours) {
    ByteWriter w(out.to(p));
    w.put_array(writes[p]);
    w.put_array(migrant_ids[p]);
    w.put_array(migrant_departures[p]);
    w.put_array(migrants[p]);
    w.put_array(teleports_out[p]);
  }
  const std::vector<Bytes> got = ps.round(ps.neighbours, out.all(), ps.neighbours, "vehicles", true);

  struct Incoming {
    uint32_t vehicle;
    DepartRecord departure;
    const uint8_t* columns;
  };
  std::vector<Incoming> incoming;
  std::vector<std::vector<uint8_t>> columns(got.size());
  for (size_t g = 0; g < got.size(); ++g) {
    ByteReader r(got[g]);
    apply_remote_footprints(1 - cur_, r.get_array<FootprintWrite>());
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
  ps.adopted.clear();
  std::vector<uint8_t> packed;
  for (const Incoming& in : incoming) {
    const uint32_t k = slots_.take();
    ps.adopted.push_back(k);
    ledger_.set_departure(in.vehicle, in.departure);
    packed.insert(packed.end(), in.columns, in.columns + packed_vehicle_bytes());
  }
  stepper_->adopt_vehicles(ps.adopted, packed);

  // As one part queues them (handle_vehicle_ends): each at the head of its edge's queue, in vehicle order.
  std::sort(teleports.begin(), teleports.end(), [](const TeleportHandOver& a, const TeleportHandOver& b) {
    return a.end.vehicle < b.end.vehicle;
  });
  for (const TeleportHandOver& t : teleports) {
    ledger_.set_departure(t.end.vehicle, t.departure);
    ledger_.teleporting(t.end, t.route_pos);
    queues_.push_front(t.edge, queue_entry(t.end.vehicle, true));
  }
}

}  // namespace lpsim

namespace lpsim {

// After insertion into lane map `map`: the footprints of the vehicles this part inserted on lanes others
// hold, sent with the next step's approaches, or at once in a round of their own where an actuated signal
// reads a loop on another part's lane (the signals are updated before the approaches go).
void Simulation::share_insertions(int map) {
  PartState& ps = *parts_;
  const PartPlan& plan = ps.plan;
  const NetView net = engine_net_.view(net_);
  const Demand& d = trips_.demand();
  for (const SlotInit& in : inits_) {
    const Footprint fp{in.lane, -1, -1, in.pos};
    const float len = d.types.length[d.vehicle_type[in.vehicle]];
    const FootprintWrite fw{fp, len, encode_cell_speed(in.speed)};
    for_each_other_holder(plan, net, fp, len, [&](int p) { ps.inserted[p].push_back(fw); });
  }
  if (!ps.insertion_round) return;
  Outbox out(ps.neighbours);
  for (const int p : ps.neighbours) ByteWriter(out.to(p)).put_array(ps.inserted[p]);
  ps.inserted.clear();
  const std::vector<Bytes> got = ps.round(ps.neighbours, out.all(), ps.neighbours, "insertions", true);
  for (const Bytes& b : got) {
    ByteReader r(b);
    apply_remote_footprints(map, r.get_array<FootprintWrite>());
  }
}

// Every part's counts, ended trips, teleports and departures of the step, to part 0, which sums them in the
// order one part would (trips and teleports by vehicle, departures by edge and queue position).
void Simulation::report_to_root() {
  PartState& ps = *parts_;
  Bytes mine;
  ByteWriter w(mine);
  w.put(counts_);
  w.put<uint8_t>(num_active_ == 0 && queues_.waiting() == 0 ? 1 : 0);
  w.put_array(ledger_.take_finished());
  w.put_array(teleport_events_);
  w.put_array(ps.departures);
  ps.departures.clear();
  w.put(ps.stats);
  w.put<int32_t>(opt_.pending_signal ? opt_.pending_signal() : 0);
  const std::vector<Bytes> all = gather_at_root(mine, "report");
  if (all.empty()) return;
  Counts sum;
  bool idle = true;
  std::vector<TripRecord> ended;
  std::vector<TeleportEvent> events;
  std::vector<DepartDelay> departures;
  ps.part_stats.clear();
  for (const Bytes& b : all) {
    ByteReader r(b);
    const Counts c = r.get<Counts>();
    sum.inserted += c.inserted;
    sum.running += c.running;
    sum.waiting += c.waiting;
    sum.arrived += c.arrived;
    sum.teleports += c.teleports;
    sum.discarded += c.discarded;
    sum.vehicle_updates += c.vehicle_updates;
    const bool part_idle = r.get<uint8_t>() != 0;
    idle = idle && part_idle;
    for (const TripRecord& t : r.get_array<TripRecord>()) ended.push_back(t);
    for (const TeleportEvent& t : r.get_array<TeleportEvent>()) events.push_back(t);
    for (const DepartDelay& dep : r.get_array<DepartDelay>()) departures.push_back(dep);
    ps.part_stats.push_back(r.get<PartStats>());
    const int32_t signal = r.get<int32_t>();
    if (ps.signal == 0) ps.signal = signal;
  }
  // Loaded and removed trips are counted where every part counts them alike: part 0's own.
  sum.loaded = counts_.loaded;
  sum.removed = counts_.removed;
  ps.counts = sum;
  ps.all_idle = idle;
  std::sort(ended.begin(), ended.end(),
            [](const TripRecord& a, const TripRecord& b) { return a.vehicle < b.vehicle; });
  for (const TripRecord& t : ended) {
    ps.travel_time_sum += t.arrival - t.depart;
    ps.finished.push_back(t);
  }
  std::sort(events.begin(), events.end(),
            [](const TeleportEvent& a, const TeleportEvent& b) { return a.vehicle < b.vehicle; });
  ps.teleport_events = std::move(events);
  std::sort(departures.begin(), departures.end(),
            [](const DepartDelay& a, const DepartDelay& b) { return a.order < b.order; });
  for (const DepartDelay& dep : departures) ps.depart_delay_sum += dep.delay;
}

std::vector<Bytes> Simulation::gather_at_root(const Bytes& mine, const char* what) const {
  PartState& ps = *parts_;
  std::vector<int> others;
  if (ps.plan.part == 0) {
    for (int p = 1; p < ps.plan.parts; ++p) others.push_back(p);
    std::vector<Bytes> got = ps.round({}, {}, others, what, false);
    got.insert(got.begin(), mine);
    return got;
  }
  ps.round({0}, {mine}, {}, what, false);
  return {};
}

// Part 0 asks every other part to do `what` (serve_part).
void Simulation::request(uint8_t what) const {
  PartState& ps = *parts_;
  std::vector<int> others;
  for (int p = 1; p < ps.plan.parts; ++p) others.push_back(p);
  ps.round(others, std::vector<Bytes>(others.size(), Bytes{what}), {}, "request", false);
}

void Simulation::serve_part() {
  if (!parts_ || parts_->plan.part == 0) throw std::logic_error("serve_part: not a part other than part 0");
  PartState& ps = *parts_;
  for (;;) {
    const std::vector<Bytes> got = ps.round({}, {}, {0}, "request", false);
    const uint8_t what = got.at(0).empty() ? 0 : got[0][0];
    if (what == kRequestStep) {
      step();
    } else if (what == kRequestSample) {
      gather_sample();
    } else if (what == kRequestCounters) {
      collect_lane_counters();
    } else if (what == kRequestSpeedSums) {
      gather_speed_sums();
    } else if (what == kRequestUnfinished) {
      unfinished_trips(0, false);  // the arguments come with the gather
    } else if (what == kRequestStop) {
      return;
    } else {
      throw std::logic_error("part " + std::to_string(ps.plan.part) + ": unknown request " +
                             std::to_string(what));
    }
  }
}

// Part 0 sends `end` and `undeparted` with the gather's request; every part answers with its own records.
std::vector<TripRecord> Simulation::unfinished_trips(double end, bool undeparted) const {
  if (!parts_) return own_unfinished_trips(end, undeparted);
  PartState& ps = *parts_;
  std::vector<int> others;
  for (int p = 1; p < ps.plan.parts; ++p) others.push_back(p);
  if (ps.plan.part == 0) {
    request(kRequestUnfinished);
    Bytes args;
    ByteWriter w(args);
    w.put(end);
    w.put(static_cast<uint8_t>(undeparted ? 1 : 0));
    ps.round(others, std::vector<Bytes>(others.size(), args), {}, "unfinished arguments", false);
  } else {
    const std::vector<Bytes> got = ps.round({}, {}, {0}, "unfinished arguments", false);
    ByteReader r(got.at(0));
    end = r.get<double>();
    undeparted = r.get<uint8_t>() != 0;
  }
  Bytes b;
  ByteWriter(b).put_array(own_unfinished_trips(end, undeparted));
  std::vector<TripRecord> all;
  for (const Bytes& x : gather_at_root(b, "unfinished"))
    for (const TripRecord& t : ByteReader(x).get_array<TripRecord>()) all.push_back(t);
  std::sort(all.begin(), all.end(),
            [](const TripRecord& a, const TripRecord& b) { return a.vehicle < b.vehicle; });
  return all;
}

// The summary's sums of every part, added at part 0 (integers: exact in any order).
SpeedSums Simulation::gather_speed_sums() const {
  if (parts_->plan.part == 0) request(kRequestSpeedSums);
  Bytes b;
  ByteWriter(b).put(speed_sums());
  SpeedSums total;
  for (const Bytes& x : gather_at_root(b, "speed sums")) {
    const SpeedSums s = ByteReader(x).get<SpeedSums>();
    total.running += s.running;
    total.halting += s.halting;
    total.stopped += s.stopped;
    total.speed += s.speed;
    total.relative += s.relative;
  }
  return total;
}

// The running vehicles of every part, at part 0, ascending by vehicle.
void Simulation::gather_sample() const {
  PartState& ps = *parts_;
  if (ps.plan.part == 0) {
    if (ps.sample_version == version_) return;  // gathered for this state already
    ps.sample_version = version_;
    request(kRequestSample);
  }
  std::vector<SampleEntry> mine;
  const HostState& s = state(StateParts::Sample);
  for (uint32_t i = 0; i < s.num_active; ++i) {
    const uint32_t k = s.active[i];
    if (s.veh.status[k] != kRunning) continue;
    mine.push_back(
        SampleEntry{s.veh.vehicle[k], s.veh.lane[k], s.veh.pos[k], s.veh.speed[k], s.veh.stop_release[k]});
  }
  Bytes b;
  ByteWriter(b).put_array(mine);
  const std::vector<Bytes> all = gather_at_root(b, "sample");
  if (all.empty()) return;
  ps.sample.clear();
  for (const Bytes& x : all) {
    ByteReader r(x);
    for (const SampleEntry& e : r.get_array<SampleEntry>()) ps.sample.push_back(e);
  }
  std::sort(ps.sample.begin(), ps.sample.end(),
            [](const SampleEntry& a, const SampleEntry& b) { return a.vehicle < b.vehicle; });
}

// The lane counters counted since the last request, from every part to part 0, which adds them to its own.
// Only the columns every part keeps travel (kept_counters: the parts run with the same options).
void Simulation::gather_counters() {
  PartState& ps = *parts_;
  std::vector<uint32_t> lanes;
  std::vector<int64_t> values;
  const std::vector<int> kept = kept_counters();
  if (ps.plan.part != 0 && !kept.empty()) {
    const uint32_t nl = net_.num_lanes();
    std::vector<int64_t> all(static_cast<size_t>(kNumLaneCounters) * nl, 0);
    int64_t* columns[kNumLaneCounters];
    for (int k = 0; k < kNumLaneCounters; ++k) columns[k] = all.data() + static_cast<size_t>(k) * nl;
    stepper_->drain_counters(columns);
    for (uint32_t l = 0; l < nl; ++l) {
      bool any = false;
      for (const int k : kept) any = any || columns[k][l] != 0;
      if (!any) continue;
      lanes.push_back(l);
      for (const int k : kept) values.push_back(columns[k][l]);
    }
  }
  Bytes b;
  ByteWriter w(b);
  w.put_array(lanes);
  w.put_array(values);
  const std::vector<Bytes> all = gather_at_root(b, "counters");
  for (size_t i = 1; i < all.size(); ++i) {
    ByteReader r(all[i]);
    const std::vector<uint32_t> l = r.get_array<uint32_t>();
    const std::vector<int64_t> v = r.get_array<int64_t>();
    for (size_t j = 0; j < l.size(); ++j)
      for (size_t c = 0; c < kept.size(); ++c)
        counter_column(lane_counters_, kept[c])[l[j]] += v[j * kept.size() + c];
  }
}

int Simulation::part_signal() const { return parts_ ? parts_->signal : 0; }

std::vector<PartStats> Simulation::part_stats() const {
  return parts_ ? parts_->part_stats : std::vector<PartStats>{};
}

const Simulation::Counts& Simulation::counts() const { return parts_ ? parts_->counts : counts_; }

std::vector<TripRecord> Simulation::take_finished_trips() {
  if (!parts_) return ledger_.take_finished();
  std::vector<TripRecord> out;
  out.swap(parts_->finished);
  return out;
}

const std::vector<TeleportEvent>& Simulation::teleport_events() const {
  return parts_ ? parts_->teleport_events : teleport_events_;
}

}  // namespace lpsim

// SUMO's rerouting device in a Simulation (engine/rerouting.hpp): at a step's start the vehicles due re-route
// on the averaged edge speeds, at its end the speeds take a sample. SUMO's timing (MSDevice_Routing,
// MSRoutingEngine), with SUMO's step T being the step that ends at T here:
//  - a vehicle with the device re-routes from its first edge to its last in the step it is due to depart
//    (the insertion events run before the insertions), and again every pre-period while it waits;
//  - an equipped vehicle re-routes from where it is every period after its departure (the begin-of-step
//    events run before the moves);
//  - the speeds take a sample after the steps ending at begin + k * adaptation interval, from the first
//    departure on;
//  - a vehicle re-routes only on speeds newer than those it was last routed on.
// In a partitioned run each part routes the vehicles it holds (queued or on its lanes); the parts then swap
// the new routes, which every part's trip table takes in vehicle order, and the speed samples' lane sums.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/time_range.hpp"
#include "demand/trip_routes.hpp"
#include "engine/rerouting.hpp"
#include "engine/simulation.hpp"
#include "transport/byte_buffer.hpp"

namespace lpsim {
namespace {}  // namespace

void Simulation::init_rerouting() {
  const Demand& d = trips_.demand();
  if (d.rerouting.empty()) return;
  reroute_ = std::make_unique<RerouteState>(net_, opt_.rerouting, opt_.seed);
  reroute_->routed_at.assign(d.size(), 0);
  if (opt_.rerouting.contraction_hierarchy) reroute_->hierarchy = std::make_unique<CchRouter>(net_);
  // Vehicles that depart before the begin time are not simulated: not routed either.
  reroute_->next_due = books_.schedule.next;
}

void Simulation::reroute_vehicles(int64_t end_ms) {
  RerouteState& r = *reroute_;
  const Demand& d = trips_.demand();
  const uint64_t sample = r.speeds.samples();

  std::vector<RouteRequest> requests;
  std::vector<uint32_t> who, kept;  // per request: the vehicle, and the edge kept before the path (or ~0)
  auto ask = [&](uint32_t v, uint32_t from_pos, uint32_t keep_edge, bool all_via) {
    const uint32_t* route = d.route_edges.data() + d.route_begin[v];
    const uint32_t length = d.route_length[v];
    RouteRequest q;
    q.origins = {route[from_pos]};
    q.destinations = {route[length - 1]};
    q.vclass = d.types.vclass_mask[d.vehicle_type[v]];
    if (r.options.random_factor > 1) q.random_stream = draw_stream(d.vehicle_id[v]) | 1;
    if (!d.via_begin.empty() && d.via_begin[v] != d.via_begin[v + 1]) {
      // Via edges still ahead: those the current route passes from here on, in order (the ones already
      // driven past are not sought again).
      uint32_t at = from_pos;
      for (uint32_t i = d.via_begin[v]; i < d.via_begin[v + 1]; ++i) {
        const uint32_t via = d.via_edges[i];
        if (all_via) {
          q.via.push_back(via);
          continue;
        }
        for (uint32_t k = at; k < length; ++k)
          if (route[k] == via) {
            q.via.push_back(via);
            at = k;
            break;
          }
      }
    }
    // Then its stops' edges (a vehicle with stops re-routes only before it departs: all are ahead).
    for (uint32_t k = d.stops.first(v); k < d.stops.last(v); ++k)
      q.via.push_back(net_.lane_edge[d.stops.lane[k]]);
    requests.push_back(std::move(q));
    who.push_back(v);
    kept.push_back(keep_edge);
    r.routed_at[v] = sample;
  };
  auto holds_queue_of = [&](uint32_t edge) {
    return link_->queues_at(edge) && books_.queues.has_lanes(edge);
  };

  // Due to depart in this step: routed when due (a trip's loaded route is the one free-flow times give,
  // so before the first sample only equipped vehicles re-route).
  while (r.next_due < books_.schedule.loaded && seconds_to_ms(d.depart[r.next_due]) <= end_ms) {
    const uint32_t v = r.next_due++;
    if (d.rerouting[v] == 0 || d.route_length[v] == 0) continue;
    if (!holds_queue_of(d.route_edges[d.route_begin[v]])) continue;
    if (sample > 0 || (d.rerouting[v] & kRerouteEquipped)) ask(v, 0, ~0u, true);
    if (r.options.pre_period_ms > 0) r.waiting.emplace_back(end_ms + r.options.pre_period_ms, v);
  }
  // Waiting to be inserted since a pre-period or more.
  size_t kept_waiting = 0;
  for (auto& [when, v] : r.waiting) {
    if (books_.ledger.status(v) != kPending || books_.ledger.departure(v).lane >= 0)
      continue;  // departed, or dropped
    if (when <= end_ms) {
      if (r.routed_at[v] < sample) ask(v, 0, ~0u, true);
      when += r.options.pre_period_ms;
    }
    r.waiting[kept_waiting++] = {when, v};
  }
  r.waiting.resize(kept_waiting);
  // Equipped vehicles on the road, every period from their departure.
  if (r.options.period_ms > 0) {
    const HostState& s = state(StateParts::Columns);
    for (uint32_t i = 0; i < s.num_active; ++i) {
      const uint32_t k = s.active[i];
      if (s.veh.status[k] != kRunning) continue;
      const uint32_t v = s.veh.vehicle[k];
      if (v >= d.rerouting.size() || !(d.rerouting[v] & kRerouteWhileDriving) || r.routed_at[v] >= sample)
        continue;
      const int64_t departed = std::llround(books_.ledger.departure(v).time / step_length()) * opt_.step_ms;
      const int64_t since = end_ms - (r.options.synchronize ? 0 : departed);
      if (end_ms <= departed || since % r.options.period_ms != 0) continue;
      const uint32_t rp = s.veh.route_pos[k];
      const bool crossing = net_.edge_is_internal[net_.lane_edge[static_cast<uint32_t>(s.veh.lane[k])]] != 0;
      const uint32_t from = crossing ? rp + 1 : rp;
      if (from + 1 >= d.route_length[v]) continue;  // on (or bound for) its last edge
      ask(v, from, crossing ? d.route_edges[d.route_begin[v] + rp] : ~0u, false);
    }
  }

  std::vector<NewRoute> mine;
  if (!requests.empty()) {
    if (r.router_sample != sample || r.router_stale) {
      r.router.set_speeds(r.speeds.speeds());
      r.router_sample = sample;
      r.router_stale = false;
    }
    const std::vector<std::vector<uint32_t>> paths =
        r.hierarchy ? r.hierarchy->route_all(r.router, requests, opt_.threads)
                    : r.router.route_all(requests, opt_.threads);
    r.reroutes += requests.size();
    std::optional<VehicleQuery> on_road;  // read once a vehicle with a new path is looked up
    for (size_t i = 0; i < requests.size(); ++i) {
      const uint32_t v = who[i];
      NewRoute n{v, {}};
      if (!paths[i].empty()) {  // no path: it keeps its route, as in SUMO
        if (kept[i] != ~0u) n.edges.push_back(kept[i]);
        n.edges.insert(n.edges.end(), paths[i].begin(), paths[i].end());
        // Unchanged when it equals what is left of the route.
        const uint32_t* route = d.route_edges.data() + d.route_begin[v];
        if (!on_road) on_road.emplace(query());
        const uint32_t rp = on_road->route_pos(v);
        if (n.edges.size() == d.route_length[v] - rp &&
            std::equal(n.edges.begin(), n.edges.end(), route + rp))
          n.edges.clear();
      }
      mine.push_back(std::move(n));
    }
  }
  if (link_->parts() > 1) share_new_routes(mine);
  apply_new_routes(mine);
}

// Every part's new routes, in vehicle order, on every part (each part holds every trip's route).
void Simulation::share_new_routes(std::vector<NewRoute>& routes) {
  Bytes out;
  {
    ByteWriter w(out);
    std::vector<uint32_t> vehicles, lengths, edges;
    for (const NewRoute& n : routes) {
      vehicles.push_back(n.vehicle);
      lengths.push_back(static_cast<uint32_t>(n.edges.size()));
      edges.insert(edges.end(), n.edges.begin(), n.edges.end());
    }
    w.put_array(vehicles);
    w.put_array(lengths);
    w.put_array(edges);
  }
  const std::vector<Bytes> all = link_->allgather(out, "new routes");
  routes.clear();
  const uint64_t sample = reroute_->speeds.samples();
  for (const Bytes& b : all) {
    ByteReader rd(b);
    const auto vehicles = rd.get_array<uint32_t>();
    const auto lengths = rd.get_array<uint32_t>();
    const auto edges = rd.get_array<uint32_t>();
    size_t at = 0;
    for (size_t i = 0; i < vehicles.size(); ++i) {
      routes.push_back(
          {vehicles[i], std::vector<uint32_t>(edges.begin() + static_cast<std::ptrdiff_t>(at),
                                              edges.begin() + static_cast<std::ptrdiff_t>(at + lengths[i]))});
      at += lengths[i];
      reroute_->routed_at[vehicles[i]] = sample;
    }
  }
  std::sort(routes.begin(), routes.end(),
            [](const NewRoute& a, const NewRoute& b) { return a.vehicle < b.vehicle; });
}

void Simulation::apply_new_routes(const std::vector<NewRoute>& routes) {
  const Demand& d = trips_.demand();
  std::vector<std::pair<uint32_t, uint32_t>> running;  // (slot, vehicle)
  std::optional<VehicleQuery> on_road;                 // read once a route changes
  for (const NewRoute& n : routes) {
    if (n.edges.empty()) continue;
    if (d.stops.first(n.vehicle) != d.stops.last(n.vehicle)) {
      // Routed through its stops' edges, so each is on it; placed along it before it departs.
      const std::vector<uint32_t> at = stop_positions(d, net_, n.vehicle, n.edges);
      if (at.empty()) continue;
      trips_.set_stop_positions(n.vehicle, at);
    }
    trips_.set_route(n.vehicle, n.edges);
    if (!on_road) on_road.emplace(query());
    if (const int32_t k = on_road->slot(n.vehicle); k >= 0)
      running.emplace_back(static_cast<uint32_t>(k), n.vehicle);
  }
  if (running.empty()) return;
  sync_trips();
  std::vector<SlotRoute> slots;
  for (const auto& [k, v] : running) slots.push_back(SlotRoute{k, d.route_begin[v], d.route_length[v], 0});
  stepper_->set_routes(slots);
  ++version_;
}

void Simulation::sample_routing_speeds() {
  RerouteState& r = *reroute_;
  const ReroutingOptions& o = r.options;
  if (o.adaptation_interval_ms <= 0 || o.adaptation_weight >= 1) return;
  const int64_t begin_ms = std::llround(opt_.begin * 1000.0);
  if ((time_ms_ - begin_ms) % o.adaptation_interval_ms != 0) return;
  r.lanes.clear();
  const HostState& s = state(StateParts::Columns);
  for (uint32_t i = 0; i < s.num_active; ++i) {
    const uint32_t k = s.active[i];
    if (s.veh.status[k] == kRunning) r.lanes.add(static_cast<uint32_t>(s.veh.lane[k]), s.veh.speed[k]);
  }
  bool departed = books_.counts.inserted > 0;
  if (link_->parts() > 1) {
    Bytes out;
    {
      ByteWriter w(out);
      std::vector<uint32_t> lanes, counts;
      std::vector<int64_t> speeds;
      for (const uint32_t l : r.lanes.lanes) {
        lanes.push_back(l);
        counts.push_back(r.lanes.count[l]);
        speeds.push_back(r.lanes.speed[l]);
      }
      r.lanes.clear();
      w.put<uint8_t>(departed ? 1 : 0);
      w.put_array(lanes);
      w.put_array(counts);
      w.put_array(speeds);
    }
    departed = false;
    for (const Bytes& b : link_->allgather(out, "routing speeds")) {
      ByteReader rd(b);
      departed = rd.get<uint8_t>() != 0 || departed;
      const auto lanes = rd.get_array<uint32_t>();
      const auto counts = rd.get_array<uint32_t>();
      const auto speeds = rd.get_array<int64_t>();
      for (size_t i = 0; i < lanes.size(); ++i) r.lanes.add(lanes[i], counts[i], speeds[i]);
    }
  }
  r.departed = r.departed || departed;
  if (r.departed) r.speeds.add_sample(r.lanes);
}

}  // namespace lpsim

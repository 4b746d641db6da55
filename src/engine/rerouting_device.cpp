// SUMO's rerouting device (engine/rerouting_device.hpp): at a step's start the vehicles due re-route
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
#include "engine/rerouting_device.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/time_range.hpp"
#include "transport/byte_buffer.hpp"

namespace lpsim {

ReroutingDevice::ReroutingDevice(const Network& net, const ReroutingOptions& o, uint64_t seed, int threads,
                                 int64_t begin_ms, int64_t step_ms, uint32_t trips, uint32_t first_due)
    : options_(o),
      threads_(threads),
      begin_ms_(begin_ms),
      step_ms_(step_ms),
      router_(net, o.minor_penalty, RandomWeights{o.random_factor, seed ^ kSeedRandomWeights}),
      speeds_(net, o.adaptation_steps, o.adaptation_weight),
      lanes_(net.num_lanes()) {
  carry_.next_due = first_due;
  carry_.routed_at.assign(trips, 0);
  if (o.contraction_hierarchy) hierarchy_ = std::make_unique<CchRouter>(net);
}

std::vector<NewRoute> ReroutingDevice::reroute(int64_t end_ms, const RerouteScope& scope,
                                               const std::function<VehicleQuery()>& query) {
  const Demand& d = scope.demand;
  const Network& net = scope.net;
  const HostBooks& books = scope.books;
  const uint64_t sample = speeds_.samples();
  std::optional<VehicleQuery> on_road;  // read once a vehicle on the road is looked at
  auto road = [&]() -> const VehicleQuery& {
    if (!on_road) on_road.emplace(query());
    return *on_road;
  };

  std::vector<RouteRequest> requests;
  std::vector<uint32_t> who, kept;  // per request: the vehicle, and the edge kept before the path (or ~0)
  auto ask = [&](uint32_t v, uint32_t from_pos, uint32_t keep_edge, bool all_via) {
    const uint32_t* route = d.route_edges.data() + d.route_begin[v];
    const uint32_t length = d.route_length[v];
    RouteRequest q;
    q.origins = {route[from_pos]};
    q.destinations = {route[length - 1]};
    q.vclass = d.types.vclass_mask[d.vehicle_type[v]];
    if (options_.random_factor > 1) q.random_stream = draw_stream(d.vehicle_id[v]) | 1;
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
      q.via.push_back(net.lane_edge[d.stops.lane[k]]);
    requests.push_back(std::move(q));
    who.push_back(v);
    kept.push_back(keep_edge);
    carry_.routed_at[v] = sample;
  };
  auto holds_queue_of = [&](uint32_t edge) {
    return scope.link.queues_at(edge) && books.queues.has_lanes(edge);
  };

  // Due to depart in this step: routed when due (a trip's loaded route is the one free-flow times give,
  // so before the first sample only equipped vehicles re-route).
  while (carry_.next_due < books.schedule.loaded && seconds_to_ms(d.depart[carry_.next_due]) <= end_ms) {
    const uint32_t v = carry_.next_due++;
    if (d.rerouting[v] == 0 || d.route_length[v] == 0) continue;
    if (!holds_queue_of(d.route_edges[d.route_begin[v]])) continue;
    if (sample > 0 || (d.rerouting[v] & kRerouteEquipped)) ask(v, 0, ~0u, true);
    if (options_.pre_period_ms > 0) carry_.waiting.emplace_back(end_ms + options_.pre_period_ms, v);
  }
  // Waiting to be inserted since a pre-period or more.
  size_t kept_waiting = 0;
  for (auto& [when, v] : carry_.waiting) {
    if (books.ledger.status(v) != kPending || books.ledger.departure(v).lane >= 0)
      continue;  // departed, or dropped
    if (when <= end_ms) {
      if (carry_.routed_at[v] < sample) ask(v, 0, ~0u, true);
      when += options_.pre_period_ms;
    }
    carry_.waiting[kept_waiting++] = {when, v};
  }
  carry_.waiting.resize(kept_waiting);
  // Equipped vehicles on the road, every period from their departure.
  if (options_.period_ms > 0) {
    const HostState& s = road().state();
    for (uint32_t i = 0; i < s.num_active; ++i) {
      const uint32_t k = s.active[i];
      if (s.veh.status[k] != kRunning) continue;
      const uint32_t v = s.veh.vehicle[k];
      if (v >= d.rerouting.size() || !(d.rerouting[v] & kRerouteWhileDriving) ||
          carry_.routed_at[v] >= sample)
        continue;
      const int64_t departed =
          std::llround(books.ledger.departure(v).time / (static_cast<double>(step_ms_) / 1000.0)) * step_ms_;
      const int64_t since = end_ms - (options_.synchronize ? 0 : departed);
      if (end_ms <= departed || since % options_.period_ms != 0) continue;
      const uint32_t rp = s.veh.route_pos[k];
      const bool crossing = net.edge_is_internal[net.lane_edge[static_cast<uint32_t>(s.veh.lane[k])]] != 0;
      const uint32_t from = crossing ? rp + 1 : rp;
      if (from + 1 >= d.route_length[v]) continue;  // on (or bound for) its last edge
      ask(v, from, crossing ? d.route_edges[d.route_begin[v] + rp] : ~0u, false);
    }
  }

  std::vector<NewRoute> mine;
  if (!requests.empty()) {
    if (carry_.router_sample != sample || router_stale_) {
      router_.set_speeds(speeds_.speeds());
      carry_.router_sample = sample;
      router_stale_ = false;
    }
    const std::vector<std::vector<uint32_t>> paths = hierarchy_
                                                         ? hierarchy_->route_all(router_, requests, threads_)
                                                         : router_.route_all(requests, threads_);
    carry_.reroutes += requests.size();
    for (size_t i = 0; i < requests.size(); ++i) {
      const uint32_t v = who[i];
      NewRoute n{v, {}};
      if (!paths[i].empty()) {  // no path: it keeps its route, as in SUMO
        if (kept[i] != ~0u) n.edges.push_back(kept[i]);
        n.edges.insert(n.edges.end(), paths[i].begin(), paths[i].end());
        // Unchanged when it equals what is left of the route.
        const uint32_t* route = d.route_edges.data() + d.route_begin[v];
        const uint32_t rp = road().route_pos(v);
        if (n.edges.size() == d.route_length[v] - rp &&
            std::equal(n.edges.begin(), n.edges.end(), route + rp))
          n.edges.clear();
      }
      mine.push_back(std::move(n));
    }
  }
  if (scope.link.parts() > 1) share(mine, scope.link);
  return mine;
}

// Every part's new routes, in vehicle order, on every part (each part holds every trip's route).
void ReroutingDevice::share(std::vector<NewRoute>& routes, BoundaryLink& link) {
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
  const std::vector<Bytes> all = link.allgather(out, "new routes");
  routes.clear();
  const uint64_t sample = speeds_.samples();
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
      carry_.routed_at[vehicles[i]] = sample;
    }
  }
  std::sort(routes.begin(), routes.end(),
            [](const NewRoute& a, const NewRoute& b) { return a.vehicle < b.vehicle; });
}

bool ReroutingDevice::sample_due(int64_t time_ms) const {
  const ReroutingOptions& o = options_;
  return o.adaptation_interval_ms > 0 && o.adaptation_weight < 1 &&
         (time_ms - begin_ms_) % o.adaptation_interval_ms == 0;
}

void ReroutingDevice::sample_speeds(const RerouteScope& scope, const HostState& s) {
  lanes_.clear();
  for (uint32_t i = 0; i < s.num_active; ++i) {
    const uint32_t k = s.active[i];
    if (s.veh.status[k] == kRunning) lanes_.add(static_cast<uint32_t>(s.veh.lane[k]), s.veh.speed[k]);
  }
  bool departed = scope.books.counts.inserted > 0;
  if (scope.link.parts() > 1) {
    Bytes out;
    {
      ByteWriter w(out);
      std::vector<uint32_t> lanes, counts;
      std::vector<int64_t> speeds;
      for (const uint32_t l : lanes_.lanes) {
        lanes.push_back(l);
        counts.push_back(lanes_.count[l]);
        speeds.push_back(lanes_.speed[l]);
      }
      lanes_.clear();
      w.put<uint8_t>(departed ? 1 : 0);
      w.put_array(lanes);
      w.put_array(counts);
      w.put_array(speeds);
    }
    departed = false;
    for (const Bytes& b : scope.link.allgather(out, "routing speeds")) {
      ByteReader rd(b);
      departed = rd.get<uint8_t>() != 0 || departed;
      const auto lanes = rd.get_array<uint32_t>();
      const auto counts = rd.get_array<uint32_t>();
      const auto speeds = rd.get_array<int64_t>();
      for (size_t i = 0; i < lanes.size(); ++i) lanes_.add(lanes[i], counts[i], speeds[i]);
    }
  }
  carry_.departed = carry_.departed || departed;
  if (carry_.departed) speeds_.add_sample(lanes_);
}

}  // namespace lpsim

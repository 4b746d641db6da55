#include "demand/demand_builder.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string_view>
#include <utility>

#include "demand/demand_draws.hpp"
#include "demand/depart_speed.hpp"
#include "demand/departure.hpp"
#include "demand/flat_index.hpp"
#include "demand/flow_expansion.hpp"
#include "demand/rerouting_equipment.hpp"
#include "demand/route_table.hpp"
#include "demand/stop_resolution.hpp"
#include "demand/trip_batch.hpp"
#include "demand/vtype_table.hpp"

namespace lpsim {
namespace {

// A vehicle between resolution and the final sorted layout. `origin` indexes spec.vehicles, or spec.flows
// when from_flow is set (its depart attributes and location live there).
struct PendingVehicle {
  double depart;
  uint32_t type;
  uint32_t slot;
  float speed_factor;
  uint32_t origin;
  bool from_flow;
  bool routed;  // a trip or flow routed here (from/to): SUMO gives it the rerouting device
};

const char* kind_name(DemandSource s) {
  switch (s) {
    case DemandSource::Trip:
      return "trip";
    case DemandSource::OdCsv:
      return "OD trip";
    default:
      return "vehicle";
  }
}

class Builder {
 public:
  Builder(const DemandSpec& spec, const Network& net, const DemandOptions& options, Demand& demand)
      : spec_(spec),
        net_(net),
        opt_(options),
        demand_(demand),
        types_(spec, options.default_car_follow_model),
        routes_(spec, net, options.ignore_route_errors, demand.route_edges),
        trips_(net, routes_),
        stops_(spec, net) {}

  void run() {
    std::vector<std::vector<double>> flow_times(spec_.flows.size());
    size_t total = spec_.vehicles.size();
    for (size_t f = 0; f < spec_.flows.size(); ++f) {
      flow_times[f] = flow_departures(spec_.flows[f], opt_.seed, opt_.step_length);
      total += flow_times[f].size();
    }
    if (total > std::numeric_limits<uint32_t>::max())
      throw InputError("the demand has " + std::to_string(total) + " vehicles, more than 2^32 - 1");
    pending_.reserve(total);
    ids_.reserve(total);

    for (uint32_t i = 0; i < spec_.vehicles.size(); ++i) add_vehicle(i);
    for (uint32_t f = 0; f < spec_.flows.size(); ++f) add_flow(f, flow_times[f]);
    flow_times.clear();
    demand_.routing.seconds = trips_.route_all(
        opt_.threads, opt_.minor_penalty, RandomWeights{opt_.random_factor, opt_.seed ^ kSeedRandomWeights},
        opt_.contraction_hierarchy);
    demand_.routing.requests = trips_.num_requests();
    check_unique_ids();
    assemble();
  }

 private:
  void add_vehicle(uint32_t i) {
    const VehicleSpec& v = spec_.vehicles[i];
    const uint64_t stream = draw_stream(v.id);
    const uint32_t type = types_.resolve(v.type, v.id, opt_.seed, stream, v.loc);
    uint32_t slot;
    if (!v.route.empty()) {
      slot = routes_.named(v.route, v.id, opt_.seed, stream, v.loc);
    } else if (!v.edges.empty()) {
      slot = routes_.inline_route(v.edges, "vehicle '" + v.id + "'", v.loc);
    } else if (v.edge_ref_count > 0) {
      slot = routes_.interned_route(v.edge_ref_begin, v.edge_ref_count, "vehicle", v.id, v.loc);
    } else {
      const bool no_from = v.from.empty() && v.from_junction.empty(),
                 no_to = v.to.empty() && v.to_junction.empty();
      // SUMO: a trip without 'from' ('to') starts (ends) on the edge of its first (last) stop.
      const std::string from = no_from ? stop_edge(v.stops, true) : v.from;
      const std::string to = no_to ? stop_edge(v.stops, false) : v.to;
      slot = trips_.add({from, to, v.from_junction, v.to_junction, via_and_stops(v.via, v.stops)},
                        types_.types().vclass_mask[type], kind_name(v.source), v.id, v.loc,
                        random_stream(stream));
    }
    const bool routed = v.route.empty() && v.edges.empty() && v.edge_ref_count == 0;
    pending_.push_back(
        {v.depart, type, slot, types_.speed_factor(type, opt_.seed, stream), i, false, routed});
    ids_.push_back(v.id);
  }

  void add_flow(uint32_t f, const std::vector<double>& times) {
    if (times.empty()) return;
    const FlowSpec& flow = spec_.flows[f];
    // One route for the whole flow unless it names a route (a distribution draws per vehicle) or its
    // vehicles are routed each with random weights.
    const bool routed_each = flow.route.empty() && flow.edges.empty() && opt_.random_factor > 1;
    uint32_t shared_slot = 0;
    if (flow.route.empty() && !routed_each) {
      // The flow's one route is routed for the class of its first vehicle's type (a vTypeDistribution of
      // mixed classes gets that class's route for all; class_problem then skips or refuses the others).
      const std::string first_id = flow.id + ".0";
      const uint32_t first_type =
          types_.resolve(flow.type, first_id, opt_.seed, draw_stream(first_id), flow.loc);
      shared_slot = flow.edges.empty()
                        ? trips_.add({flow.from, flow.to, flow.from_junction, flow.to_junction,
                                      via_and_stops(flow.via, flow.stops)},
                                     types_.types().vclass_mask[first_type], "flow", flow.id, flow.loc)
                        : routes_.inline_route(flow.edges, "flow '" + flow.id + "'", flow.loc);
    }
    std::string id;
    for (size_t n = 0; n < times.size(); ++n) {
      id.assign(flow.id).append(".").append(std::to_string(n));
      const uint64_t stream = draw_stream(id);
      const uint32_t type = types_.resolve(flow.type, id, opt_.seed, stream, flow.loc);
      const uint32_t slot = routed_each          ? trips_.add({flow.from, flow.to, flow.from_junction,
                                                               flow.to_junction, via_and_stops(flow.via, flow.stops)},
                                                              types_.types().vclass_mask[type], "flow", id, flow.loc,
                                                              random_stream(stream))
                            : flow.route.empty() ? shared_slot
                                                 : routes_.named(flow.route, id, opt_.seed, stream, flow.loc);
      pending_.push_back({times[n], type, slot, types_.speed_factor(type, opt_.seed, stream), f, true,
                          flow.route.empty() && flow.edges.empty()});
      ids_.push_back(id);
    }
  }

  // The stream a trip's random edge-cost factors are drawn from (0: no random weights). Never 0 when
  // they are on, whatever the id hashes to.
  uint64_t random_stream(uint64_t vehicle_stream) const {
    return opt_.random_factor > 1 ? (vehicle_stream | 1) : 0;
  }

  // The edge of the first (or last) stop that is not dropped, or "" (the trip then has no such end).
  std::string stop_edge(const std::vector<StopSpec>& stops, bool first) const {
    for (size_t k = 0; k < stops.size(); ++k)
      if (const auto e = stops_.edge_of(stops[first ? k : stops.size() - 1 - k])) return net_.edge_id[*e];
    return "";
  }

  // A trip's via edges, then the edges of its stops: the router leads it through both, as duarouter does.
  const std::vector<std::string>& via_and_stops(const std::vector<std::string>& via,
                                                const std::vector<StopSpec>& stops) {
    if (stops.empty()) return via;
    via_buffer_ = via;
    for (const StopSpec& st : stops)
      if (const auto e = stops_.edge_of(st)) via_buffer_.push_back(net_.edge_id[*e]);
    return via_buffer_;
  }

  // Resolves pending vehicle k's stops (its named route's, then its own) into staged_; "" or why they
  // cannot be made.
  std::string stage_stops(uint32_t k) {
    const PendingVehicle& p = pending_[k];
    const RouteSlot& slot = routes_.slot(p.slot);
    const std::vector<StopSpec>& own =
        p.from_flow ? spec_.flows[p.origin].stops : spec_.vehicles[p.origin].stops;
    const std::vector<StopSpec>& on_route = routes_.route_stops(p.slot);
    if (own.empty() && on_route.empty()) return "";
    std::vector<const StopSpec*> specs;
    for (const StopSpec& s : on_route) specs.push_back(&s);
    for (const StopSpec& s : own) specs.push_back(&s);
    const double shift = p.from_flow ? p.depart - spec_.flows[p.origin].begin : 0.0;
    std::string why = stops_.append(specs, demand_.route_edges.data() + slot.begin, slot.length,
                                    types_.types().vclass_mask[p.type], shift, staged_);
    if (!why.empty()) {
      why = "vehicle '" + ids_[k] + "': " + why;
      staged_.truncate(staged_begin_[k]);
    }
    return why;
  }

  const SourceLoc& loc_of(const PendingVehicle& p) const {
    return p.from_flow ? spec_.flows[p.origin].loc : spec_.vehicles[p.origin].loc;
  }
  const DepartSpec& depart_of(const PendingVehicle& p) const {
    return p.from_flow ? spec_.flows[p.origin].depart_spec : spec_.vehicles[p.origin].depart_spec;
  }

  void check_unique_ids() const {
    FlatIndex seen(ids_.size());
    for (uint32_t k = 0; k < ids_.size(); ++k)
      if (seen.find_or_insert(draw_stream(ids_[k]), k,
                              [&](uint32_t other) { return ids_[other] == ids_[k]; }) != k)
        throw InputError(loc_of(pending_[k]), "duplicate vehicle id '" + ids_[k] + "'");
  }

  // Why vehicle k's class (its type's vClass mask) cannot drive its resolved route, in SUMO's words, or ""
  // when it can: an edge none of whose lanes admits the class, two consecutive edges joined only by moves
  // the class may not make (a connection between bus lanes, for a car), or a given departLane that the
  // class may not use.
  std::string class_problem(uint32_t k) const {
    const PendingVehicle& p = pending_[k];
    const RouteSlot& slot = routes_.slot(p.slot);
    const uint32_t mask = types_.types().vclass_mask[p.type];
    const uint32_t* edges = demand_.route_edges.data() + slot.begin;
    auto who = [&]() { return "vehicle '" + ids_[k] + "' (vClass " + types_.types().vclass[p.type] + ")"; };
    for (uint32_t i = 0; i < slot.length; ++i) {
      if ((net_.edge_permissions[edges[i]] & mask) == 0)
        return i == 0
                   ? who() + " is not allowed to depart on any lane of edge '" + net_.edge_id[edges[0]] + "'"
                   : who() + " is not allowed on edge '" + net_.edge_id[edges[i]] + "' of its route";
      if (i > 0 && !net_.connected(edges[i - 1], edges[i], mask) && !repairs(k))
        return who() + " has no valid route: no connection between edge '" + net_.edge_id[edges[i - 1]] +
               "' and edge '" + net_.edge_id[edges[i]] + "' that its class may use";
    }
    const DepartSpec& ds = depart_of(p);
    if (ds.lane == DepartLane::Given) {
      const int position = car_lane_position(net_, edges[0], ds.lane_index);
      if (position >= 0 &&
          (net_.lane_permissions[net_.edge_first_lane[edges[0]] + static_cast<uint32_t>(position)] & mask) ==
              0)
        return "invalid departLane " + std::to_string(ds.lane_index) + " for " + who() + ": lane '" +
               net_.lane_id[net_.edge_first_lane[edges[0]] + static_cast<uint32_t>(position)] +
               "' does not allow its class";
    }
    return "";
  }

  // Who SUMO equips with the rerouting device, by pending vehicle (load order: SUMO's quota counts vehicles
  // as it loads them).
  void equip() {
    const ReroutingEquipment equipment(opt_.rerouting, spec_, types_.types(), opt_.seed);
    equipped_.assign(pending_.size(), 0);
    for (uint32_t k = 0; k < pending_.size(); ++k) {
      const PendingVehicle& p = pending_[k];
      const int8_t param =
          p.from_flow ? spec_.flows[p.origin].rerouting_param : spec_.vehicles[p.origin].rerouting_param;
      equipped_[k] = equipment.equipped(ids_[k], draw_stream(ids_[k]), k, p.type, param) ? 1 : 0;
    }
  }

  // Whether pending vehicle k's route, if not connected, is repaired when it is due (SUMO: with
  // --ignore-route-errors, by the rerouting device's routing at insertion).
  bool repairs(uint32_t k) const { return equipped_[k] && routes_.ignore_route_errors(); }

  void assemble() {
    equip();
    // Drop vehicles on broken routes (only possible with ignore_route_errors), in file order. Sorting
    // (depart, position) pairs is a stable sort by depart that touches only the pairs.
    std::vector<std::pair<double, uint32_t>> by_depart;
    by_depart.reserve(pending_.size());
    staged_begin_.assign(pending_.size() + 1, 0);
    for (uint32_t k = 0; k < pending_.size(); ++k) {
      const RouteSlot& slot = routes_.slot(pending_[k].slot);
      std::string reason;
      staged_begin_[k] = staged_.size();
      // A route that is not connected is an error; with ignore_route_errors SUMO keeps it, and routing a
      // vehicle with the rerouting device when due repairs it (any other vehicle is skipped here).
      const bool repaired = slot.problem >= 0 && routes_.problem_repairable(slot.problem) && repairs(k);
      if (slot.problem >= 0 && routes_.problem_repairable(slot.problem) && !routes_.ignore_route_errors())
        throw InputError(loc_of(pending_[k]), routes_.problem(slot.problem));
      if (slot.problem >= 0 && !repaired) {
        reason = routes_.problem(slot.problem);
        if (routes_.problem_outside_car_map(slot.problem)) {
          // The route uses an edge without road lanes (a footpath, a railway). A road vehicle cannot drive
          // it in SUMO either: an error. Trains, trams on their own tracks and ships are outside the road
          // traffic LPSim simulates: skipped with the reason.
          const uint32_t type = pending_[k].type;
          if (road_vclass(types_.types().vclass_mask[type]) && !routes_.ignore_route_errors())
            throw InputError(loc_of(pending_[k]), reason + " (vehicle '" + ids_[k] + "')");
          reason = "vClass " + types_.types().vclass[type] + ": " + reason;
        }
      } else {
        reason = class_problem(k);
        // As SUMO: stops that are not along the route, or on a lane the class may not use, are errors.
        if (reason.empty()) reason = stage_stops(k);
        // As SUMO: a vehicle whose class cannot drive its route is an error, or skipped with the reason
        // when route errors are ignored.
        if (!reason.empty() && !routes_.ignore_route_errors()) throw InputError(loc_of(pending_[k]), reason);
      }
      if (!reason.empty()) {
        // Shared named routes keep a vehicle-free reason; name the vehicle here.
        if (reason.find("'" + ids_[k] + "'") == std::string::npos) reason += " of vehicle '" + ids_[k] + "'";
        demand_.unroutable.push_back({ids_[k], reason, loc_of(pending_[k])});
      } else {
        by_depart.emplace_back(pending_[k].depart, k);
      }
    }
    staged_begin_[pending_.size()] = staged_.size();
    if (!std::is_sorted(by_depart.begin(), by_depart.end())) std::sort(by_depart.begin(), by_depart.end());
    std::vector<uint32_t> order(by_depart.size());
    for (size_t v = 0; v < order.size(); ++v) order[v] = by_depart[v].second;
    by_depart = {};

    const size_t n = order.size();
    Demand& d = demand_;
    d.vehicle_id.resize(n);
    d.vehicle_type.resize(n);
    d.depart.resize(n);
    d.route_begin.resize(n);
    d.route_length.resize(n);
    d.speed_factor.resize(n);
    d.source.resize(n);
    d.depart_lane_kind.resize(n);
    d.depart_lane.resize(n);
    d.depart_pos_kind.resize(n);
    d.depart_pos.resize(n);
    d.depart_speed_kind.resize(n);
    d.depart_speed.resize(n);
    d.arrival_pos_kind.resize(n);
    d.arrival_pos.resize(n);
    if (staged_.size() > 0) {
      d.stops.vehicle_begin.resize(n + 1);
      for (size_t v = 0; v < n; ++v) {
        d.stops.vehicle_begin[v] = d.stops.size();
        d.stops.append(staged_, staged_begin_[order[v]], staged_begin_[order[v] + 1]);
      }
      d.stops.vehicle_begin[n] = d.stops.size();
      staged_ = StopTable{};
    }
    for (size_t v = 0; v < n; ++v) {
      const PendingVehicle& p = pending_[order[v]];
      const RouteSlot& slot = routes_.slot(p.slot);
      const DepartSpec& ds = depart_of(p);
      const uint32_t first_edge = d.route_edges[slot.begin];
      const uint32_t last_edge = d.route_edges[slot.begin + slot.length - 1];
      d.vehicle_id[v] = std::move(ids_[order[v]]);
      d.vehicle_type[v] = p.type;
      d.depart[v] = p.depart;
      d.route_begin[v] = slot.begin;
      d.route_length[v] = slot.length;
      d.speed_factor[v] = p.speed_factor;
      d.source[v] = p.from_flow ? DemandSource::Flow : spec_.vehicles[p.origin].source;

      if (!set_departure(d, v, ds, net_, first_edge, last_edge))
        throw InputError(loc_of(p), "departLane " + std::to_string(ds.lane_index) + " of vehicle '" +
                                        d.vehicle_id[v] + "' is not a lane of its first edge '" +
                                        net_.edge_id[first_edge] + "' (" +
                                        std::to_string(net_.edge_num_lanes[first_edge]) + " vehicle lanes)");
      // As SUMO, which checks a departSpeed when it inserts: vehicles outside [begin, end] never depart.
      const bool departs = p.depart >= opt_.begin && (opt_.end < 0 || p.depart <= opt_.end);
      if (departs) {
        d.speed_factor[v] = depart_speed_factor(types_.types(), p.type, p.speed_factor, ds, net_, first_edge,
                                                d.vehicle_id[v], loc_of(p));
        if (d.speed_factor[v] != p.speed_factor && d.raised_speed_factors++ == 0)
          d.first_raised_speed_factor = d.vehicle_id[v];
      }
    }
    assign_rerouting(order);
    d.types = types_.take();
    d.unsupported = spec_.skipped;
    // Stopping places on rail, tram or pedestrian lanes: skipped, with the vehicles using them (trains).
    if (const uint64_t n = stops_.left_out_places(); n > 0)
      d.unsupported["stopping place on a lane no road vehicle may use"] += static_cast<int64_t>(n);
    // As SUMO 1.15, which reports each and runs on without it.
    if (const uint64_t n = stops_.dropped_stops(); n > 0)
      d.unsupported["stop (position off its lane, dropped as SUMO drops it)"] += static_cast<int64_t>(n);
    for (auto src : d.source) d.routing.vehicles += src != DemandSource::Vehicle ? 1 : 0;
  }

  // Demand::rerouting and the via edges of the trips that re-route, by the vehicles' final order.
  void assign_rerouting(const std::vector<uint32_t>& order) {
    Demand& d = demand_;
    std::vector<uint8_t> flags(order.size(), 0);
    bool any = false;
    std::vector<uint32_t> via_begin(order.size() + 1, 0), via_edges;
    std::string reason;
    for (size_t v = 0; v < order.size(); ++v) {
      via_begin[v] = static_cast<uint32_t>(via_edges.size());
      const uint32_t k = order[v];
      const PendingVehicle& p = pending_[k];
      const bool is_trip =
          p.routed && (p.from_flow || spec_.vehicles[p.origin].source != DemandSource::OdCsv);
      uint8_t f = is_trip ? kRerouteAtInsertion : 0;
      if (equipped_[k]) {
        f |= kRerouteAtInsertion | kRerouteWhileDriving | kRerouteEquipped;
        const RouteSlot& slot = routes_.slot(p.slot);
        const uint32_t* edges = d.route_edges.data() + slot.begin;
        for (uint32_t i = 1; i < slot.length; ++i)
          if (!net_.connected(edges[i - 1], edges[i], types_.types().vclass_mask[p.type]))
            f |= kRerouteRepair;
      }
      // A vehicle with stops re-routes only before it departs (through its stops' edges).
      if (d.stops.first(static_cast<uint32_t>(v)) != d.stops.last(static_cast<uint32_t>(v)))
        f &= static_cast<uint8_t>(~kRerouteWhileDriving);
      flags[v] = f;
      any = any || f != 0;
      if (f == 0 || !p.routed) continue;
      for (const std::string& name : p.from_flow ? spec_.flows[p.origin].via : spec_.vehicles[p.origin].via)
        if (const auto e = routes_.edges().drivable(name, reason)) via_edges.push_back(*e);
    }
    via_begin[order.size()] = static_cast<uint32_t>(via_edges.size());
    if (!any) return;
    d.rerouting = std::move(flags);
    if (!via_edges.empty()) {
      d.via_begin = std::move(via_begin);
      d.via_edges = std::move(via_edges);
    }
  }

  const DemandSpec& spec_;
  const Network& net_;
  const DemandOptions& opt_;
  Demand& demand_;
  VTypeTable types_;
  RouteTable routes_;
  TripBatch trips_;
  StopResolver stops_;
  std::vector<std::string> via_buffer_;
  StopTable staged_;                    // stops in pending order, while vehicles may still be dropped
  std::vector<uint32_t> staged_begin_;  // [pending + 1]: each pending vehicle's first staged stop
  std::vector<uint8_t> equipped_;       // [pending]: SUMO gives it the rerouting device (equip())
  std::vector<PendingVehicle> pending_;
  std::vector<std::string> ids_;
};

}  // namespace

Demand build_demand(const DemandSpec& spec, const Network& net, const DemandOptions& options) {
  Demand demand;
  Builder(spec, net, options, demand).run();
  return demand;
}

}  // namespace lpsim

#include "demand/route_table.hpp"

#include <cmath>

#include "demand/demand_draws.hpp"

namespace lpsim {

EdgeLookup::EdgeLookup(const Network& net) : net_(net), index_(net.num_edges()) {
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    const std::string& id = net.edge_id[e];
    index_.find_or_insert(rng_hash(id.data(), id.size()), e,
                          [&](uint32_t other) { return net.edge_id[other] == id; });
  }
}

namespace {
constexpr const char* kNoCarLane = "has no lane a road vehicle may use";
constexpr uint32_t kNotDrivable = 0xFFFFFFFFu;
}  // namespace

bool EdgeLookup::outside_car_map(const std::string& reason) {
  return reason.find(kNoCarLane) != std::string::npos;
}

std::optional<uint32_t> EdgeLookup::drivable(const std::string& id, std::string& reason) const {
  const uint32_t e =
      index_.find(rng_hash(id.data(), id.size()), [&](uint32_t other) { return net_.edge_id[other] == id; });
  if (e == FlatIndex::kEmpty) {
    reason = "unknown edge '" + id + "'";
    return std::nullopt;
  }
  if (net_.edge_is_internal[e]) {
    reason = "edge '" + id + "' is an internal junction edge";
    return std::nullopt;
  }
  if (net_.edge_num_lanes[e] == 0) {
    reason = "edge '" + id + "' " + kNoCarLane;
    return std::nullopt;
  }
  return e;
}

RouteTable::RouteTable(const DemandSpec& spec, const Network& net, bool ignore_route_errors,
                       std::vector<uint32_t>& route_edges)
    : spec_(spec), net_(net), edges_(net), ignore_(ignore_route_errors), route_edges_(route_edges) {
  // Interned routes list few distinct edges many times: look each up once. A name that is not drivable is
  // looked up again for its reason only if a route using it is checked.
  name_edge_.resize(spec.edge_names.size());
  std::string reason;
  for (size_t n = 0; n < spec.edge_names.size(); ++n)
    name_edge_[n] = edges_.drivable(spec.edge_names[n], reason).value_or(kNotDrivable);
  route_edges_.reserve(route_edges_.size() + spec.edge_refs.size());
  route_index_.reserve(spec.routes.size());
  for (uint32_t r = 0; r < spec.routes.size(); ++r) {
    const RouteSpec& route = spec.routes[r];
    if (!route_index_.emplace(route.id, r).second)
      throw InputError(route.loc, "duplicate route id '" + route.id + "'");
  }
  route_slot_.assign(spec.routes.size(), -1);
  for (const auto& d : spec.route_dists) {
    if (route_index_.count(d.id) || dist_index_.count(d.id))
      throw InputError(d.loc,
                       "routeDistribution id '" + d.id + "' is already used by a route or distribution");
    if (d.members.empty()) throw InputError(d.loc, "routeDistribution '" + d.id + "' has no members");
    Distribution dist;
    double total = 0;
    for (const auto& m : d.members) {
      auto it = route_index_.find(m.id);
      if (it == route_index_.end())
        throw InputError(d.loc, "unknown route '" + m.id + "' in routeDistribution '" + d.id + "'");
      if (!(m.probability >= 0) || !std::isfinite(m.probability))
        throw InputError(d.loc,
                         "invalid probability of route '" + m.id + "' in routeDistribution '" + d.id + "'");
      total += m.probability;
      dist.routes.push_back(it->second);
      dist.cumulative.push_back(total);
    }
    if (!(total > 0)) throw InputError(d.loc, "routeDistribution '" + d.id + "' has only zero probabilities");
    dist_index_.emplace(d.id, static_cast<uint32_t>(dists_.size()));
    dists_.push_back(std::move(dist));
  }
}

uint32_t RouteTable::named(const std::string& ref, std::string_view vehicle_id, uint64_t seed,
                           uint64_t stream, const SourceLoc& loc) {
  if (auto it = route_index_.find(ref); it != route_index_.end()) return route_slot(it->second, vehicle_id);
  if (auto it = dist_index_.find(ref); it != dist_index_.end()) {
    const Distribution& d = dists_[it->second];
    return route_slot(d.routes[draw_weighted(d.cumulative, seed, stream, kDrawRouteMember)], vehicle_id);
  }
  throw InputError(loc, "unknown route '" + ref + "' for vehicle '" + std::string(vehicle_id) + "'");
}

uint32_t RouteTable::route_slot(uint32_t route, std::string_view vehicle_id) {
  if (route_slot_[route] < 0) {
    const RouteSpec& r = spec_.routes[route];
    route_slot_[route] =
        resolve(r.edges, "route '" + r.id + "'", r.loc, " of vehicle '" + std::string(vehicle_id) + "'");
    if (!r.stops.empty()) slot_route_.emplace(static_cast<uint32_t>(route_slot_[route]), route);
  }
  return static_cast<uint32_t>(route_slot_[route]);
}

uint32_t RouteTable::inline_route(const std::vector<std::string>& edges, const std::string& owner,
                                  const SourceLoc& loc) {
  return resolve(edges, "the route of " + owner, loc);
}

template <class EdgeAt, class IdAt, class What>
uint32_t RouteTable::append_checked(size_t n, EdgeAt&& edge_at, IdAt&& id_at, What&& what,
                                    const SourceLoc& loc, const std::string& user) {
  if (n == 0) return add_broken(loc, "no edges in " + what(), false, user);
  const auto begin = route_edges_.size();
  std::string reason, disconnected;
  for (size_t i = 0; i < n; ++i) {
    std::optional<uint32_t> e = edge_at(i, reason);
    if (!e) {
      route_edges_.resize(begin);
      return add_broken(loc, reason + " in " + what(), EdgeLookup::outside_car_map(reason), user);
    }
    if (i > 0 && !connected(route_edges_.back(), *e) && disconnected.empty())
      disconnected = "no connection from edge '" + id_at(i - 1) + "' to edge '" + id_at(i) + "' in " + what();
    route_edges_.push_back(*e);
  }
  int32_t problem = -1;
  if (!disconnected.empty()) {
    // Kept with its edges: a vehicle with the rerouting device is routed when due, which repairs it; for any
    // other the builder refuses it (or skips it with ignore_route_errors).
    problems_.push_back(disconnected + user);
    outside_car_map_.push_back(0);
    repairable_.resize(problems_.size(), 0);
    repairable_.back() = 1;
    problem = static_cast<int32_t>(problems_.size() - 1);
  }
  slots_.push_back({static_cast<uint32_t>(begin), static_cast<uint32_t>(n), problem});
  return static_cast<uint32_t>(slots_.size() - 1);
}

uint32_t RouteTable::interned_route(uint64_t begin, uint32_t count, std::string_view kind,
                                    std::string_view id, const SourceLoc& loc) {
  auto what = [&] { return "the route of " + std::string(kind) + " '" + std::string(id) + "'"; };
  if (begin > spec_.edge_refs.size() || count > spec_.edge_refs.size() - begin)
    throw InputError(loc, "interned route of " + std::string(kind) + " '" + std::string(id) +
                              "' lies outside the edge list");
  const uint32_t* refs = spec_.edge_refs.data() + begin;
  return append_checked(
      count,
      [&](size_t i, std::string& reason) -> std::optional<uint32_t> {
        if (refs[i] >= name_edge_.size())
          throw InputError(
              loc, "interned route of " + std::string(kind) + " '" + std::string(id) + "' names no edge");
        const uint32_t e = name_edge_[refs[i]];
        if (e != kNotDrivable) return e;
        return edges_.drivable(spec_.edge_names[refs[i]], reason);
      },
      [&](size_t i) -> const std::string& { return spec_.edge_names[refs[i]]; }, what, loc, "");
}

uint32_t RouteTable::resolve(const std::vector<std::string>& edges, const std::string& what,
                             const SourceLoc& loc, const std::string& user) {
  return append_checked(
      edges.size(), [&](size_t i, std::string& reason) { return edges_.drivable(edges[i], reason); },
      [&](size_t i) -> const std::string& { return edges[i]; }, [&] { return what; }, loc, user);
}

uint32_t RouteTable::add_resolved(const std::vector<uint32_t>& edges) {
  const uint32_t slot = add_pending();
  set_resolved(slot, edges);
  return slot;
}

uint32_t RouteTable::add_pending() {
  slots_.push_back({});
  return static_cast<uint32_t>(slots_.size() - 1);
}

void RouteTable::set_resolved(uint32_t slot, const std::vector<uint32_t>& edges) {
  slots_[slot] = {static_cast<uint32_t>(route_edges_.size()), static_cast<uint32_t>(edges.size()), -1};
  route_edges_.insert(route_edges_.end(), edges.begin(), edges.end());
}

void RouteTable::set_broken(uint32_t slot, const SourceLoc& loc, const std::string& reason) {
  if (!ignore_) throw InputError(loc, reason);
  problems_.push_back(reason);
  outside_car_map_.push_back(0);
  slots_[slot] = {0, 0, static_cast<int32_t>(problems_.size() - 1)};
}

uint32_t RouteTable::add_broken(const SourceLoc& loc, const std::string& reason, bool outside_car_map,
                                const std::string& user) {
  if (!ignore_ && !outside_car_map) throw InputError(loc, reason + user);
  problems_.push_back(reason);
  outside_car_map_.push_back(outside_car_map ? 1 : 0);
  slots_.push_back({0, 0, static_cast<int32_t>(problems_.size() - 1)});
  return static_cast<uint32_t>(slots_.size() - 1);
}

}  // namespace lpsim

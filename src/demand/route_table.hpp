#pragma once
// Routes of a demand as edge-index runs in Demand::route_edges. A vehicle refers to a route "slot"; a named
// route (and each flow's route) has one slot shared by every vehicle using it, so its edges are stored
// once. Named routes are resolved and checked when first used (an unused broken route is harmless).
//
// Route problems (unknown, internal or car-less edge, two consecutive edges without a connection, a trip
// without a path) throw InputError, or with ignore_route_errors mark the slot broken: vehicles on a broken
// slot are skipped and recorded in Demand::unroutable with the reason.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/demand_spec.hpp"
#include "demand/flat_index.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Index of edge `id` if a vehicle can drive on it (exists, is not internal, has a car lane); otherwise
/// nullopt and `reason` says why, naming the edge.
/// Edge ids to indices for millions of route lookups: open addressing on the id's hash, no node chasing.
class EdgeLookup {
 public:
  explicit EdgeLookup(const Network& net);
  /// Index of a normal edge with car lanes, or nullopt with the reason (unknown, internal, no car lane).
  std::optional<uint32_t> drivable(const std::string& id, std::string& reason) const;
  /// Whether a reason from drivable() is "the edge exists but has no car lane" (outside the car lane map).
  static bool outside_car_map(const std::string& reason);

 private:
  const Network& net_;
  FlatIndex index_;
};

struct RouteSlot {
  uint32_t begin = 0, length = 0;  // in route_edges
  int32_t problem = -1;            // index into RouteTable::problem(); -1: usable
};

class RouteTable {
 public:
  const EdgeLookup& edges() const { return edges_; }
  RouteTable(const DemandSpec& spec, const Network& net, bool ignore_route_errors,
             std::vector<uint32_t>& route_edges);

  /// Slot for a route attribute: a named route, or a routeDistribution from which a member is drawn with
  /// the vehicle's `stream`. InputError at `loc` naming the route and the vehicle when the id is unknown.
  uint32_t named(const std::string& ref, std::string_view vehicle_id, uint64_t seed, uint64_t stream,
                 const SourceLoc& loc);

  /// New slot for an inline list of edge ids, checked like a named route; errors at `loc` name `owner`
  /// (e.g. "vehicle 'v1'" or "flow 'f'").
  uint32_t inline_route(const std::vector<std::string>& edges, const std::string& owner,
                        const SourceLoc& loc);
  /// As inline_route for a route interned by the reader: `count` entries of spec.edge_refs from `begin`.
  /// Each distinct edge id was resolved once when the table was built; errors name `kind` 'id'.
  uint32_t interned_route(uint64_t begin, uint32_t count, std::string_view kind, std::string_view id,
                          const SourceLoc& loc);

  /// New slot holding already-resolved edges (a routed trip); connectivity is the router's business.
  uint32_t add_resolved(const std::vector<uint32_t>& edges);
  /// New broken slot, or InputError(loc, reason) unless route errors are ignored.
  /// `outside_car_map`: the route uses an edge without car lanes. That is not raised here: only vehicles of a
  /// car class make it an error (others, e.g. buses on bus lanes, are skipped with a reason).
  uint32_t add_broken(const SourceLoc& loc, const std::string& reason, bool outside_car_map = false,
                      const std::string& user = "");
  /// New empty slot to be filled later by set_resolved / set_broken (trips waiting for the router).
  uint32_t add_pending();
  void set_resolved(uint32_t slot, const std::vector<uint32_t>& edges);
  void set_broken(uint32_t slot, const SourceLoc& loc, const std::string& reason);

  const RouteSlot& slot(uint32_t s) const { return slots_[s]; }
  /// The stops of the named route whose slot `s` is (made by every vehicle on it), or none.
  const std::vector<StopSpec>& route_stops(uint32_t s) const {
    auto it = slot_route_.find(s);
    return it == slot_route_.end() ? no_stops_ : spec_.routes[it->second].stops;
  }
  const std::string& problem(int32_t p) const { return problems_[static_cast<size_t>(p)]; }
  bool problem_outside_car_map(int32_t p) const { return outside_car_map_[static_cast<size_t>(p)] != 0; }
  /// Whether problem p is a route whose edges are not all connected, kept with its edges (the slot's begin
  /// and length are valid): routing the vehicle repairs it.
  bool problem_repairable(int32_t p) const {
    return static_cast<size_t>(p) < repairable_.size() && repairable_[static_cast<size_t>(p)] != 0;
  }
  bool ignore_route_errors() const { return ignore_; }

 private:
  struct Distribution {
    std::vector<uint32_t> routes;  // indices into spec.routes
    std::vector<double> cumulative;
  };
  uint32_t route_slot(uint32_t route, std::string_view vehicle_id);
  // Appends the checked edges of a route as a slot; `what` names the route for messages.
  // `user` (" of vehicle 'x'") is named in a raised error but not stored: a named route is shared.
  uint32_t resolve(const std::vector<std::string>& edges, const std::string& what, const SourceLoc& loc,
                   const std::string& user = "");
  // Network::connected, inlined: millions of route steps are checked while loading.
  bool connected(uint32_t from, uint32_t to) const {
    for (uint32_t k = net_.edge_succ_begin[from], end = net_.edge_succ_begin[from + 1]; k < end; ++k)
      if (net_.edge_succ[k] == to) return true;
    return false;
  }
  // The checks of resolve() over `n` edges: edge_at(i, reason) gives the i-th edge's index or nullopt with
  // the reason, id_at(i) its id, what() names the route (built only for a message).
  template <class EdgeAt, class IdAt, class What>
  uint32_t append_checked(size_t n, EdgeAt&& edge_at, IdAt&& id_at, What&& what, const SourceLoc& loc,
                          const std::string& user);

  const DemandSpec& spec_;
  const Network& net_;
  EdgeLookup edges_;
  std::vector<uint32_t> name_edge_;  // per spec.edge_names: its edge index, or kNotDrivable
  bool ignore_;
  std::vector<uint32_t>& route_edges_;
  std::unordered_map<std::string, uint32_t> route_index_, dist_index_;
  std::vector<Distribution> dists_;
  std::vector<int64_t> route_slot_;                    // per named route: its slot, -1 until first used
  std::unordered_map<uint32_t, uint32_t> slot_route_;  // slot of a named route with stops -> the route
  const std::vector<StopSpec> no_stops_;
  std::vector<RouteSlot> slots_;
  std::vector<std::string> problems_;
  std::vector<uint8_t> outside_car_map_;
  std::vector<uint8_t> repairable_;  // per problem (shorter: the rest are not)
};

}  // namespace lpsim

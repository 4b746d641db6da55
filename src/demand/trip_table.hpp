#pragma once
// The trips a run simulates: the loaded demand, then trips added while it runs (a vehicle handed over from
// another simulator) and routes replaced (rerouting). Append-only: a trip keeps its index for the whole run,
// and a replaced route's edges are appended and the trip pointed at them, so that every index a backend
// holds stays valid and a backend's copy is brought up to date by copying what was appended (changes()).
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

/// A trip added during a run.
struct NewTrip {
  std::string id;
  uint32_t type = 0;            // index into the demand's vehicle types
  double depart = 0;            // s: due for insertion then (or at once, if that has passed)
  std::vector<uint32_t> route;  // edge indices, each reachable from the one before
  float speed_factor = 1.0f;
  DepartSpec
      departure;  // SUMO's departLane / departPos / departSpeed / arrivalPos (src/core/demand_spec.hpp)
};

class TripTable {
 public:
  explicit TripTable(Demand demand);

  const Demand& demand() const { return d_; }
  uint32_t size() const { return d_.size(); }
  /// The index of the trip with id `id`, or -1 (the ids are indexed at the first lookup or addition).
  int64_t find(const std::string& id) const;

  /// Appends a trip and returns its index; std::invalid_argument naming the trip when it is not valid here
  /// (an id in use, an unknown type, an empty or unconnected route, an edge without car lanes).
  uint32_t add(const NewTrip& trip, const Network& net);
  /// Trip v drives `edges` from now on (appended; its old route stays where it was, unreferenced by v).
  /// The caller checks that they are connected and lead on from where the vehicle is.
  void set_route(uint32_t v, const std::vector<uint32_t>& edges);
  /// Vehicle v's stops lie at these positions of its route from now on (one per stop, in order).
  void set_stop_positions(uint32_t v, const std::vector<uint32_t>& route_pos);
  /// Whether each edge of `edges` is reachable from the one before (normal edges, in the net's edge graph).
  /// Whether a vehicle of class mask `vclass` can drive `edges` (each allows it, each move too).
  static bool connected(const Network& net, const std::vector<uint32_t>& edges,
                        uint32_t vclass = kAllVClasses);

  /// What was appended or rerouted since the last call.
  struct Changes {
    uint32_t first_new_vehicle = 0;
    uint64_t first_new_route_edge = 0;
    std::vector<uint32_t> new_routes;  // earlier trips whose route changed
    bool stops_moved = false;          // some stop's route position changed
  };
  bool changed() const;
  Changes take_changes();

  /// The trips added and the routes and stops' positions as they are now (rerouting replaces them), for a
  /// checkpoint (an archive of engine/state_archive.hpp): the added trips' columns, the appended route edges
  /// and the trips whose route changed, each with its loaded route. Read back into a table made from the same
  /// demand (whose own additions and changed routes are undone first), every trip added and every route that
  /// differs counts as changed.
  template <class A>
  void visit_routes(A& a);

 private:
  Demand d_;
  uint32_t loaded_trips_ = 0;        // the demand's trips
  uint64_t loaded_route_edges_ = 0;  // and route edges
  // Vehicle ids, built at the first lookup or addition: a run that never asks keeps no string per trip twice.
  mutable std::unordered_map<std::string, uint32_t> index_;
  const std::unordered_map<std::string, uint32_t>& index() const;
  Changes changes_;
  // The loaded route (begin, length) of each loaded trip whose route was replaced: a checkpoint saves only
  // these trips' routes.
  struct LoadedRoute {
    uint32_t begin = 0, length = 0;
  };
  std::unordered_map<uint32_t, LoadedRoute> replaced_;

  // The columns TripTable::add appends to, but the ids (f(column) for each).
  template <class F>
  void visit_added_columns(F&& f);
  // The added trips (from loaded_trips_ on), for visit_routes; read back, the table is cut to the loaded
  // trips first.
  template <class A>
  void visit_added(A& a);
};

template <class F>
void TripTable::visit_added_columns(F&& f) {
  f(d_.vehicle_type);
  f(d_.depart);
  f(d_.route_begin);
  f(d_.route_length);
  f(d_.speed_factor);
  f(d_.source);
  f(d_.depart_lane_kind);
  f(d_.depart_lane);
  f(d_.depart_pos_kind);
  f(d_.depart_pos);
  f(d_.depart_speed_kind);
  f(d_.depart_speed);
  f(d_.arrival_pos_kind);
  f(d_.arrival_pos);
}

template <class A>
void TripTable::visit_added(A& a) {
  const uint32_t loaded = loaded_trips_;
  std::vector<uint32_t> id_length;
  std::vector<char> id_chars;
  for (uint32_t v = loaded; v < d_.size(); ++v) {
    id_length.push_back(static_cast<uint32_t>(d_.vehicle_id[v].size()));
    id_chars.insert(id_chars.end(), d_.vehicle_id[v].begin(), d_.vehicle_id[v].end());
  }
  a(id_length);
  a(id_chars);
  visit_added_columns([&](auto& column) {
    using Column = std::remove_reference_t<decltype(column)>;
    Column added(column.begin() + std::min<size_t>(loaded, column.size()), column.end());
    a(added);
    if constexpr (A::kReads) {
      if (added.size() != id_length.size()) a.fail("the added trips' columns differ in length");
      column.resize(loaded);
      column.insert(column.end(), added.begin(), added.end());
    }
  });
  if constexpr (A::kReads) {
    d_.vehicle_id.resize(loaded);
    size_t at = 0;
    for (const uint32_t n : id_length) {
      if (at + n > id_chars.size()) a.fail("the added trips' ids past their characters");
      d_.vehicle_id.emplace_back(id_chars.begin() + static_cast<std::ptrdiff_t>(at),
                                 id_chars.begin() + static_cast<std::ptrdiff_t>(at + n));
      at += n;
    }
    // An added trip makes no scheduled stops.
    if (!d_.stops.vehicle_begin.empty())
      d_.stops.vehicle_begin.resize(size_t{d_.size()} + 1, d_.stops.size());
    index_.clear();
    changes_.first_new_vehicle = std::min(changes_.first_new_vehicle, loaded);
  }
}

template <class A>
void TripTable::visit_routes(A& a) {
  uint64_t trips = loaded_trips_;
  a(trips);
  if (trips != loaded_trips_)
    a.fail("the state has " + std::to_string(trips) + " loaded trips, this run " +
           std::to_string(loaded_trips_));
  visit_added(a);
  std::vector<uint32_t> tail, replaced, loaded_begin, loaded_length, begin, length;
  std::vector<uint32_t> stops = d_.stops.route_pos;
  if constexpr (!A::kReads) {
    tail.assign(d_.route_edges.begin() + static_cast<std::ptrdiff_t>(loaded_route_edges_),
                d_.route_edges.end());
    for (const auto& [v, r] : replaced_) replaced.push_back(v);
    std::sort(replaced.begin(), replaced.end());
    for (const uint32_t v : replaced) {
      loaded_begin.push_back(replaced_.at(v).begin);
      loaded_length.push_back(replaced_.at(v).length);
      begin.push_back(d_.route_begin[v]);
      length.push_back(d_.route_length[v]);
    }
  }
  a(tail);
  a(replaced);
  a(loaded_begin);
  a(loaded_length);
  a(begin);
  a(length);
  a(stops);
  if constexpr (A::kReads) {
    const size_t n = replaced.size();
    if (loaded_begin.size() != n || loaded_length.size() != n || begin.size() != n || length.size() != n ||
        stops.size() != d_.stops.route_pos.size())
      a.fail("the trip table's routes do not match this run's trips");
    // This table's own replaced routes (a vehicle that re-routed at the begin time) back to the loaded ones.
    for (const auto& [v, r] : replaced_) {
      d_.route_begin[v] = r.begin;
      d_.route_length[v] = r.length;
      changes_.new_routes.push_back(v);
    }
    replaced_.clear();
    d_.route_edges.resize(loaded_route_edges_);
    d_.route_edges.insert(d_.route_edges.end(), tail.begin(), tail.end());
    changes_.first_new_route_edge = std::min(changes_.first_new_route_edge, loaded_route_edges_);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t v = replaced[i];
      if (v >= d_.size() || uint64_t{begin[i]} + length[i] > d_.route_edges.size() ||
          uint64_t{loaded_begin[i]} + loaded_length[i] > loaded_route_edges_)
        a.fail("a replaced route past the route edges");
      replaced_[v] = LoadedRoute{loaded_begin[i], loaded_length[i]};
      d_.route_begin[v] = begin[i];
      d_.route_length[v] = length[i];
      changes_.new_routes.push_back(v);
    }
    if (stops != d_.stops.route_pos) {
      d_.stops.route_pos = stops;
      changes_.stops_moved = true;
    }
    for (uint32_t v = loaded_trips_; v < d_.size(); ++v)
      if (uint64_t{d_.route_begin[v]} + d_.route_length[v] > d_.route_edges.size() ||
          d_.vehicle_type[v] >= d_.types.size())
        a.fail("an added trip's route or type out of range");
  }
}

}  // namespace lpsim

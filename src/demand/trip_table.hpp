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

  /// The routes and the stops' positions as they are now (rerouting replaces them), for a checkpoint (an
  /// archive of engine/state_archive.hpp). Read back into a table made from the same demand, every route
  /// that differs counts as changed. A table that grew while it ran (trips added) is not saved.
  template <class A>
  void visit_routes(A& a);

 private:
  Demand d_;
  uint32_t loaded_trips_ = 0;                        // the demand's trips
  uint64_t loaded_route_edges_ = 0;                  // and route edges
  std::unordered_map<std::string, uint32_t> index_;  // vehicle ids, built at the first add
  Changes changes_;
};

template <class A>
void TripTable::visit_routes(A& a) {
  if (d_.size() != loaded_trips_)
    throw std::runtime_error("a run whose trips grew while it ran (a co-simulation) has no saved state yet");
  uint64_t trips = d_.size();
  a(trips);
  if (trips != d_.size())
    a.fail("the state has " + std::to_string(trips) + " trips, this run " + std::to_string(d_.size()));
  std::vector<uint32_t> tail, begin = d_.route_begin, length = d_.route_length, stops = d_.stops.route_pos;
  if constexpr (!A::kReads)
    tail.assign(d_.route_edges.begin() + static_cast<std::ptrdiff_t>(loaded_route_edges_),
                d_.route_edges.end());
  a(tail);
  a(begin);
  a(length);
  a(stops);
  if constexpr (A::kReads) {
    if (begin.size() != d_.size() || length.size() != d_.size() || stops.size() != d_.stops.route_pos.size())
      a.fail("the trip table's routes do not match this run's trips");
    d_.route_edges.resize(loaded_route_edges_);
    d_.route_edges.insert(d_.route_edges.end(), tail.begin(), tail.end());
    changes_.first_new_route_edge = std::min(changes_.first_new_route_edge, loaded_route_edges_);
    for (uint32_t v = 0; v < d_.size(); ++v) {
      if (uint64_t{begin[v]} + length[v] > d_.route_edges.size()) a.fail("a route past the route edges");
      if (begin[v] == d_.route_begin[v] && length[v] == d_.route_length[v]) continue;
      d_.route_begin[v] = begin[v];
      d_.route_length[v] = length[v];
      if (v < changes_.first_new_vehicle) changes_.new_routes.push_back(v);
    }
    if (stops != d_.stops.route_pos) {
      d_.stops.route_pos = stops;
      changes_.stops_moved = true;
    }
  }
}

}  // namespace lpsim

#pragma once
// The trips a run simulates: the loaded demand, then trips added while it runs (a vehicle handed over from
// another simulator) and routes replaced (rerouting). Append-only: a trip keeps its index for the whole run,
// and a replaced route's edges are appended and the trip pointed at them, so that every index a backend
// holds stays valid and a backend's copy is brought up to date by copying what was appended (changes()).
#include <cstdint>
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

 private:
  Demand d_;
  std::unordered_map<std::string, uint32_t> index_;  // vehicle ids, built at the first add
  Changes changes_;
};

}  // namespace lpsim

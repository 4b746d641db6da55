#pragma once
// Scheduled stops (<stop>) resolved against the network and a vehicle's route, as SUMO 1.15 places them:
//  - at a stopping place (busStop, trainStop, containerStop, chargingStation): its lane and stretch
//    [startPos, endPos] (endPos defaults to the lane's end; negative positions count from the end);
//  - on a lane: endPos (default the lane's end), startPos (default endPos - 0.2 m);
//  - on an edge: its first lane the vehicle's class may use, as on a lane;
//  - each stop on the first occurrence of its edge in the route after the stop before it (a stop further
//    along the same edge stays on it); a stop that is not downstream is an error, as in SUMO;
//  - a flow's `until` is later for each vehicle by its depart - the flow's begin (SUMO shifts it so);
//  - positions checked, and with friendlyPos moved onto the lane, as SUMO's checkStopPos does
//    (stop_position_valid): a stopping place off its lane is an input error, a stop on a lane off it is
//    dropped and counted (SUMO 1.15 reports it and runs on without it);
//  - a stopping place or stop on a lane LPSim leaves out (rail, tram, sidewalk) is no error by itself: only
//    a vehicle LPSim keeps that would stop there is (trains using it are skipped with their routes).
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/demand_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

/// SUMO's check of a stop's or stopping place's stretch [start, end] on a lane of `length` m: negative
/// positions count from the lane's end; without `friendly` the stretch must lie on the lane and be at least
/// `min_length` long (0.1 m for stopping places, 0 for stops), with `friendly` it is moved there instead.
/// False when invalid; start and end are updated in place.
bool stop_position_valid(double& start, double& end, double length, double min_length, bool friendly);

class StopResolver {
 public:
  /// Stopping places are checked here (unknown or dropped lane, positions outside it): InputError at
  /// their location.
  StopResolver(const DemandSpec& spec, const Network& net);

  /// The edge a stop is made on, for routing a trip through it (possibly one without road lanes, when the
  /// stop lies on a lane LPSim leaves out). InputError at the stop's location for an unknown stopping
  /// place, lane or edge.
  /// nullopt for a stop dropped for its position.
  std::optional<uint32_t> edge_of(const StopSpec& stop) const;

  /// Appends the stops `specs` of a vehicle of class mask `vclass` on `route` (route_len edges) to `out`.
  /// Returns "" or why they cannot be made (naming the stop's lane), for the caller to raise or record.
  /// `until_shift` (s) is added to each `until`.
  std::string append(const std::vector<const StopSpec*>& specs, const uint32_t* route, uint32_t route_len,
                     uint32_t vclass, double until_shift, StopTable& out);

  /// Stopping places skipped because their lane is one LPSim leaves out.
  uint64_t left_out_places() const { return left_out_places_; }
  /// Stops left out of the vehicles appended so far because their position lies off their lane.
  uint64_t dropped_stops() const { return dropped_stops_; }

 private:
  static constexpr uint32_t kLeftOut = 0xFFFFFFFFu;  // Place::lane of a place on a lane left out
  static constexpr uint32_t kDropped = 0xFFFFFFFEu;  // Place::lane of a stop dropped for its position
  struct Place {
    uint32_t lane;  // kLeftOut: on a lane LPSim leaves out
    uint32_t edge;
    float start, end;
  };
  // Where stop `s` is made for a vehicle of class `vclass`: lane and stretch; InputError for ids or
  // positions that do not exist.
  Place place_of(const StopSpec& s, uint32_t vclass) const;
  uint32_t lane_of(const std::string& id, const SourceLoc& loc, const char* what) const;

  const Network& net_;
  std::unordered_map<std::string, Place> places_;
  uint64_t left_out_places_ = 0;
  uint64_t dropped_stops_ = 0;
};

}  // namespace lpsim

#pragma once
// Plain description of traffic demand as read from SUMO route files, add-files or an LPSim OD CSV.
// Readers fill it; src/demand/demand_builder resolves ids, expands flows and routes trips.
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace lpsim {

struct VTypeSpec {
  std::string id;
  // SUMO 1.15 defaults for a passenger car.
  double length = 5.0, min_gap = 2.5, accel = 2.6, decel = 4.5, emergency_decel = 9.0;
  double max_speed = 55.56, speed_factor = 1.0, speed_dev = 0.1, tau = 1.0, sigma = 0.5;
  // SUMO's desiredMaxSpeed: the speed the driver wishes at most, before its speed factor (a bicycle's 20 km/h
  // by default, while its maxSpeed is 50 km/h); infinity: none.
  double desired_max_speed = std::numeric_limits<double>::infinity();
  bool speed_dev_given = false;
  std::string vclass = "passenger";
  std::string car_follow_model = "Krauss";
  // Given in the file (attribute or <carFollowing-X>), not SUMO's default: only a model asked for by name
  // earns the warning that LPSim follows IDM instead.
  bool car_follow_model_given = false;
  std::string lane_change_model;              // as given; empty: SUMO's default (LC2013)
  std::optional<std::string> emission_class;  // as given; not given: the vClass's default
  std::optional<double> width, height;        // m; not given: the vClass's (read by the emission model)
  std::map<std::string, std::string> params;  // other attributes and car-following parameters (delta, ...)
  SourceLoc loc;
};

struct WeightedId {
  std::string id;
  double probability = 1.0;
};

struct VTypeDistSpec {
  std::string id;
  std::vector<WeightedId> members;
  SourceLoc loc;
};

/// A scheduled stop (<stop> in a vehicle, trip, flow or route): at a stopping place, or on a lane up to
/// end_pos. It lasts `duration` and at least until `until` (SUMO's rule: the later of the two).
struct StopSpec {
  std::string stopping_place;  // busStop, trainStop, containerStop or chargingStation id; or empty
  std::string lane;            // with no stopping place
  std::string edge;            // with neither: the edge's first lane the vehicle's class may use
  std::optional<double> start_pos, end_pos;  // not given: SUMO's defaults apply
  bool friendly_pos = false;                 // positions outside the lane are moved onto it, not refused
  double duration = -1, until = -1;          // s; -1: not given
  SourceLoc loc;
};

/// A stopping place (<busStop>, <trainStop>, <containerStop>, <chargingStation>): a stretch of a lane
/// where stops that name it are made.
struct StoppingPlaceSpec {
  std::string id, lane;
  double start_pos = 0;
  std::optional<double> end_pos;  // not given: the lane's end
  bool friendly_pos = false;      // positions outside the lane are moved onto it instead of refused
  SourceLoc loc;
};

struct RouteSpec {
  std::string id;
  std::vector<std::string> edges;
  std::vector<StopSpec> stops;  // made by every vehicle on the route, before the vehicle's own
  SourceLoc loc;
};

struct RouteDistSpec {
  std::string id;
  std::vector<WeightedId> members;  // route ids (inline routes are registered under generated ids)
  SourceLoc loc;
};

// departLane / departPos / departSpeed / arrivalPos as SUMO writes them: a keyword or a number.
enum class DepartLane : uint8_t { Given, First, Random, Free, Allowed, Best };
enum class DepartPos : uint8_t { Given, Base, Random, Free, RandomFree, Last, Stop };
enum class DepartSpeed : uint8_t { Given, Zero, Random, Max, Desired, SpeedLimit, Last, Avg };
enum class ArrivalPos : uint8_t { Given, Max, Random };

struct DepartSpec {
  DepartLane lane = DepartLane::First;
  int lane_index = 0;
  DepartPos pos = DepartPos::Base;
  double pos_value = 0;
  DepartSpeed speed = DepartSpeed::Zero;
  double speed_value = 0;
  ArrivalPos arrival = ArrivalPos::Max;
  double arrival_value = 0;
};

enum class DemandSource : uint8_t { Vehicle, Trip, Flow, OdCsv, Added };  // Added: during a run (TripTable)

/// A vehicle, a trip or an OD row: one traveller. Exactly one of route / edges / (from,to) names the path.
struct VehicleSpec {
  std::string id, type;  // type empty: DEFAULT_VEHTYPE
  double depart = 0;     // s
  DemandSource source = DemandSource::Vehicle;
  std::string route;               // route or routeDistribution id
  std::vector<std::string> edges;  // inline route
  // Inline route interned by the route reader: edge_ref_count entries of DemandSpec::edge_refs from
  // edge_ref_begin (used when `edges` is empty). A million routes then hold no string per edge.
  uint64_t edge_ref_begin = 0;
  uint32_t edge_ref_count = 0;
  std::string from, to;                    // trip endpoints (edge ids)
  std::string from_junction, to_junction;  // trip endpoints as junctions (fromJunction / OD CSV nodes)
  std::vector<std::string> via;
  DepartSpec depart_spec;
  std::vector<StopSpec> stops;
  int8_t rerouting_param = -1;  // <param key="has.rerouting.device">: -1 none, 0 false, 1 true
  SourceLoc loc;
};

/// A flow: a generator of vehicles. Exactly one of period / vehs_per_hour / probability; end or number.
struct FlowSpec {
  std::string id, type;
  double begin = 0, end = -1;  // end -1: not given
  double period = -1, vehs_per_hour = -1, probability = -1;
  int64_t number = -1;
  std::string route;
  std::vector<std::string> edges;
  std::string from, to, from_junction, to_junction;
  std::vector<std::string> via;
  DepartSpec depart_spec;
  std::vector<StopSpec> stops;  // `until` counts from begin: each vehicle's is later by its depart - begin
  int8_t rerouting_param = -1;  // <param key="has.rerouting.device">: -1 none, 0 false, 1 true
  SourceLoc loc;
};

struct DemandSpec {
  std::vector<VTypeSpec> vtypes;
  std::vector<VTypeDistSpec> vtype_dists;
  std::vector<RouteSpec> routes;
  std::vector<RouteDistSpec> route_dists;
  std::vector<VehicleSpec> vehicles;  // vehicles, trips and OD rows in file order
  std::vector<FlowSpec> flows;
  std::vector<StoppingPlaceSpec> stopping_places;
  std::vector<std::string> edge_names;     // each edge id of the interned inline routes, once
  std::vector<uint32_t> edge_refs;         // interned inline routes: indices into edge_names
  std::map<std::string, int64_t> skipped;  // element name -> count of unsupported elements (persons, ...)
  // Vehicles, trips and flows a route file lists after a later departure, which SUMO ignores (its route
  // files are read ahead by departure time); the first one's id and place, for the warning.
  int64_t unsorted_ignored = 0;
  std::string first_unsorted_ignored;
  SourceLoc first_unsorted_loc;
};

}  // namespace lpsim

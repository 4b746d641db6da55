#pragma once
// Demand as the engine sees it: vehicle types and vehicles in structure-of-arrays form, routes as arrays of
// edge indices, sorted by depart time (ties keep file order). Built by demand_builder from a DemandSpec.
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/demand_spec.hpp"

namespace lpsim {

struct VehicleTypes {
  std::vector<std::string> id;
  std::vector<float> length, min_gap, accel, decel, emergency_decel, max_speed;
  // SUMO's desiredMaxSpeed (m/s, before the speed factor); FLT_MAX where the type has none.
  std::vector<float> desired_max_speed;
  std::vector<float> speed_factor, speed_dev, tau, sigma, delta;  // delta: IDM acceleration exponent
  std::vector<std::string> vclass, car_follow_model;  // car_follow_model: the vType's, or the default's
  std::vector<uint8_t> model;         // CarFollowModel simulated (kernels/idm.hpp): IDM or Krauss
  std::vector<uint32_t> vclass_mask;  // the lanes a type may use: core/vehicle_vclass_mask of its vclass
  // Emissions (demand/emission_class.hpp, kernels/emissions.hpp): the class as SUMO names it, its model and
  // coefficients (kCoefficientsPerClass per type, zero for Zero and other models), its coasting cut-off,
  // its fuel's density (mg/ml) and the stop length beyond which the engine is off (s).
  std::vector<std::string> emission_class;
  std::vector<uint8_t> emission_model;
  std::vector<double> emission_coeff;
  std::vector<double> coast_incl, coast_mass_term, fuel_density, shut_off_stop;
  std::vector<SourceLoc> loc;  // where each was defined (none for a DEFAULT_VEHTYPE LPSim added)
  std::unordered_map<std::string, uint32_t> index;

  uint32_t size() const { return static_cast<uint32_t>(id.size()); }
};

/// Scheduled stops (<stop>) of all vehicles, in one table: vehicle v's are [vehicle_begin[v],
/// vehicle_begin[v+1]), in the order they are made along its route.
struct StopTable {
  std::vector<uint32_t> vehicle_begin;    // [vehicles + 1]; empty while no vehicle has a stop
  std::vector<uint32_t> route_pos;        // position in the vehicle's route of the stop's edge
  std::vector<uint32_t> lane;             // network lane index
  std::vector<float> start_pos, end_pos;  // m along the lane: the stretch the vehicle stops within
  std::vector<double> duration;           // s
  std::vector<double> until;              // s; -1: none

  uint32_t size() const { return static_cast<uint32_t>(route_pos.size()); }
  /// Vehicle v's stops: [first, last).
  uint32_t first(uint32_t v) const { return vehicle_begin.empty() ? 0 : vehicle_begin[v]; }
  uint32_t last(uint32_t v) const { return vehicle_begin.empty() ? 0 : vehicle_begin[v + 1]; }
  /// Keeps the first n stops (vehicle_begin untouched).
  void truncate(uint32_t n);
  /// Appends stops [first, last) of `from` (vehicle_begin untouched).
  void append(const StopTable& from, uint32_t first, uint32_t last);
};

/// How a vehicle re-routes (SUMO's rerouting device): kRerouteAtInsertion, when it is inserted (and every
/// pre-period while it waits to be), from its first edge to its last through its stops' edges;
/// kRerouteWhileDriving, also every period while it drives, from where it is (vehicles without stops);
/// kRerouteEquipped, it has the device by SUMO's options or params (not only as a trip): routed when due
/// whatever the speeds (SUMO's first routing always happens; a trip's loaded route is that routing's result
/// until speeds are sampled); kRerouteRepair, its loaded route is not connected (SUMO repairs an equipped
/// vehicle's route so).
enum RerouteFlags : uint8_t {
  kRerouteAtInsertion = 1,
  kRerouteWhileDriving = 2,
  kRerouteEquipped = 4,
  kRerouteRepair = 8
};

struct Demand {
  VehicleTypes types;

  // --- vehicles, sorted by depart ---
  std::vector<std::string> vehicle_id;
  std::vector<uint32_t> vehicle_type;
  std::vector<double> depart;         // s
  std::vector<uint32_t> route_begin;  // [route_begin[v], route_begin[v] + route_length[v]) in route_edges
  std::vector<uint32_t> route_length;
  std::vector<float> speed_factor;  // drawn per vehicle from its type (deterministic in seed and id)
  std::vector<DemandSource> source;
  std::vector<uint8_t> depart_lane_kind;  // DepartLane
  std::vector<int8_t> depart_lane;        // for DepartLane::Given
  std::vector<uint8_t> depart_pos_kind;   // DepartPos
  std::vector<float> depart_pos;
  std::vector<uint8_t> depart_speed_kind;  // DepartSpeed
  std::vector<float> depart_speed;
  std::vector<uint8_t> arrival_pos_kind;  // ArrivalPos
  std::vector<float> arrival_pos;

  std::vector<uint32_t> route_edges;  // edge indices; routes shared by id are stored once
  StopTable stops;

  // SUMO's rerouting device (engine/rerouting_device.hpp), per vehicle: RerouteFlags. Empty: no vehicle has
  // it.
  std::vector<uint8_t> rerouting;
  // The via edges of trips that re-route (in order), [via_begin[v], via_begin[v + 1]) of via_edges; empty
  // while no such trip has any.
  std::vector<uint32_t> via_begin, via_edges;

  // --- what was not turned into vehicles ---
  struct Skipped {
    std::string id, reason;
    SourceLoc loc;
  };
  std::vector<Skipped> unroutable;             // trips without a path (kept only with ignore_route_errors)
  std::map<std::string, int64_t> unsupported;  // from DemandSpec::skipped
  // Vehicles whose departSpeed needed a higher speed factor than drawn (demand/depart_speed.hpp), for a
  // warning; not kept in snapshots.
  uint64_t raised_speed_factors = 0;
  std::string first_raised_speed_factor;

  /// Trip routing done while building: vehicles routed, distinct requests after deduplication, wall time.
  struct RoutingStats {
    uint64_t vehicles = 0, requests = 0;
    double seconds = 0;
  } routing;

  uint32_t size() const { return static_cast<uint32_t>(vehicle_id.size()); }
  uint64_t count(DemandSource s) const;
};

}  // namespace lpsim

#pragma once
#include <string>

#include "core/config_spec.hpp"
#include "core/demand_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"
#include "net/router.hpp"

namespace lpsim {

struct DemandOptions {
  uint64_t seed = 23423;
  bool ignore_route_errors = false;  // as SUMO's --ignore-route-errors: skip unroutable/broken, report them
  int threads = 0;                   // routing threads; 0: all hardware threads
  double step_length = 1.0;          // s; the grid on which probability flows draw
  double minor_penalty = kMinorLinkPenalty;  // s; routing cost of crossing on a link without priority
  // SUMO's --routing-algorithm CH/CHWrapper: trips routed with the contraction hierarchy (same costs).
  bool contraction_hierarchy = false;
  // SUMO's --weights.random-factor: above 1, every trip (each flow vehicle too) is routed on its own with
  // its edge costs multiplied by factors drawn in [1, F) from the seed and its id (RandomWeights).
  double random_factor = 1;
  // Kept for the engine: every vehicle is built whatever its depart; the engine decides what runs.
  double begin = 0, end = -1;
  // SUMO's --default.carfollowmodel: the model of every vType that names none.
  std::string default_car_follow_model = "Krauss";
  // SUMO's device.rerouting.probability / .explicit / .deterministic: which vehicles get the rerouting device
  // (Demand::rerouting) besides the trips and flows routed here, which always do.
  ReroutingSpec rerouting;
};

/// Resolves types, distributions and routes, expands flows, routes trips (fastest free-flow path over lane
/// connections) and checks every route is connected. Raises InputError naming the vehicle and the bad id.
///
/// Conventions of the result (beyond demand.hpp):
///  - vehicles are sorted by depart, stable: vehicles/trips/OD rows in file order first, then each flow's
///    vehicles in flow order; flows therefore interleave with everything else by time only;
///  - flow vehicles are named "<flow id>.<n>" (see flow_expansion.hpp for the expansion rules);
///  - depart_lane (DepartLane::Given) is the position of the lane among the first edge's car lanes, i.e. the
///    lane is edge_first_lane[e] + depart_lane; the SUMO index given in the file is mapped to it;
///  - depart_pos / arrival_pos (Given) are from the start of the first / last edge: SUMO's negative values
///    (measured back from the lane end) are converted by adding that edge's length;
///  - every random draw is keyed by (seed, hash of the vehicle id) (flows' per-step draws: flow id, step),
///    never by load order;
///  - with ignore_route_errors, vehicles on broken routes and trips without a path are left out and listed
///    in Demand::unroutable (every flow vehicle individually).
Demand build_demand(const DemandSpec& spec, const Network& net, const DemandOptions& options);

}  // namespace lpsim

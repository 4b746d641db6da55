#pragma once
// SUMO's rerouting device in a Simulation (simulation_rerouting.cpp): the averaged edge speeds, the router on
// them, and which vehicles re-route when. Host work between steps; what it decides is a function of the
// state at the step's start, so every backend, thread count and part count decides alike.
#include <cstdint>
#include <memory>
#include <vector>

#include "demand/demand_draws.hpp"
#include "engine/routing_speeds.hpp"
#include "net/cch_router.hpp"
#include "net/router.hpp"

namespace lpsim {

/// SUMO's --device.rerouting.* timing options, in the engine's milliseconds.
struct ReroutingOptions {
  int64_t adaptation_interval_ms = 1000;  // between speed samples; <= 0: never (free-flow times throughout)
  int adaptation_steps = 180;             // samples in the moving average; 0: exponential with the weight
  double adaptation_weight = 0;           // >= 1: the speeds never change
  int64_t period_ms = 0;                  // en-route re-routing of equipped vehicles; 0: never
  int64_t pre_period_ms = 60000;          // re-routing while waiting to be inserted; 0: once, when due
  bool synchronize = false;               // periods count from time 0, not from each departure
  double minor_penalty = kMinorLinkPenalty;
  // SUMO's --weights.random-factor, which the device's router applies too: each vehicle's edge costs times
  // factors drawn per (vehicle, edge) as when its trip was routed while loading (RandomWeights).
  double random_factor = 1;
  // SUMO's --routing-algorithm CH/CHWrapper, which the device's router follows too: the routes are the
  // contraction hierarchy's (net/cch_router.hpp), customized on the speeds of each routing.
  bool contraction_hierarchy = false;
};

/// A re-routing's outcome: the vehicle, and its new route from where it is (empty: it keeps its route).
struct NewRoute {
  uint32_t vehicle;
  std::vector<uint32_t> edges;
};

struct RerouteState {
  RerouteState(const Network& net, const ReroutingOptions& o, uint64_t seed)
      : options(o),
        router(net, o.minor_penalty, RandomWeights{o.random_factor, seed ^ kSeedRandomWeights}),
        speeds(net, o.adaptation_steps, o.adaptation_weight),
        lanes(net.num_lanes()) {}

  ReroutingOptions options;
  Router router;                         // on `speeds` once a sample was taken, on free-flow times before
  std::unique_ptr<CchRouter> hierarchy;  // with contraction_hierarchy: ordered and contracted once
  RoutingSpeeds speeds;
  LaneSpeedSums lanes;    // the sample's scratch
  uint32_t next_due = 0;  // loaded vehicles (by depart) before this one were routed when due
  // Equipped vehicles this part queued to depart, with the time of their next re-routing while they wait.
  std::vector<std::pair<int64_t, uint32_t>> waiting;
  // Per vehicle: the speeds' sample count it was last routed on (SUMO re-routes only on new speeds).
  std::vector<uint64_t> routed_at;
  uint64_t router_sample = 0;  // the sample the router's costs were set from (0: free-flow times)
  bool departed = false;       // some vehicle has departed (SUMO samples only from then on)
  uint64_t reroutes = 0;       // routes computed
  // The router's costs are not part of a saved state: one loaded with router_sample > 0 takes the speeds of
  // that sample anew before it next routes.
  bool router_stale = false;

  template <class A>
  void visit_state(A& a) {
    a(speeds);
    a(next_due);
    a(waiting);
    a(routed_at);
    a(router_sample);
    a(departed);
    a(reroutes);
    if constexpr (A::kReads) router_stale = router_sample != 0;
  }
};

}  // namespace lpsim

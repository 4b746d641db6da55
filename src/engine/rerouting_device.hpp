#pragma once
// SUMO's rerouting device (MSDevice_Routing, MSRoutingEngine) beside a Simulation: the averaged edge speeds,
// the router on them, and which vehicles re-route when. Host work between steps; what it decides is a
// function of the state at the step's start, so every backend, thread count and part count decides alike.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "demand/demand.hpp"
#include "demand/demand_draws.hpp"
#include "engine/boundary_link.hpp"
#include "engine/host_books.hpp"
#include "engine/routing_speeds.hpp"
#include "engine/state_archive.hpp"
#include "engine/vehicle_query.hpp"
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

/// What the device reads of its run between steps, and the link that swaps its work with the other parts.
struct RerouteScope {
  const Network& net;
  const Demand& demand;
  const HostBooks& books;
  BoundaryLink& link;
};

/// What the rerouting device carries from one step to the next besides its speeds: a piece of its state.
struct ReroutingCarry {
  uint32_t next_due = 0;  // loaded vehicles (by depart) before this one were routed when due
  // Equipped vehicles this part queued to depart, with the time of their next re-routing while they wait.
  std::vector<std::pair<int64_t, uint32_t>> waiting;
  // Per vehicle: the speeds' sample count it was last routed on (SUMO re-routes only on new speeds).
  std::vector<uint64_t> routed_at;
  uint64_t router_sample = 0;  // the sample the router's costs were set from (0: free-flow times)
  bool departed = false;       // some vehicle has departed (SUMO samples only from then on)
  uint64_t reroutes = 0;       // routes computed

  template <class A>
  void visit_state(A& a) {
    a(next_due);
    a(waiting);
    a(routed_at);
    a(router_sample);
    a(departed);
    a(reroutes);
  }
};

class ReroutingDevice {
 public:
  /// For a run of `trips` trips that starts at begin_ms with steps of step_ms, the trips before `first_due`
  /// (by depart) departing before it: not simulated, not routed either.
  ReroutingDevice(const Network& net, const ReroutingOptions& o, uint64_t seed, int threads, int64_t begin_ms,
                  int64_t step_ms, uint32_t trips, uint32_t first_due);

  /// At the start of the step that ends at end_ms: the new routes of the vehicles due to re-route, every
  /// part's, in vehicle order (each part holds every trip's route). `query` reads the vehicles on the road;
  /// it is called only when some vehicle could re-route.
  std::vector<NewRoute> reroute(int64_t end_ms, const RerouteScope& scope,
                                const std::function<VehicleQuery()>& query);
  /// Whether the speeds take a sample at the end of the step that ended at time_ms.
  bool sample_due(int64_t time_ms) const;
  /// The sample from `s`, the slot columns (every part's lanes' sums in a partitioned run, a collective
  /// call).
  void sample_speeds(const RerouteScope& scope, const HostState& s);

  template <class A>
  void visit_state(A& a) {
    // The speeds are the same in every part of a partitioned run: a section of their own, which a state
    // re-cut for other parts takes whole.
    std::vector<uint8_t> speeds;
    if constexpr (!A::kReads) {
      StateOut s;
      s(speeds_);
      speeds = std::move(s.bytes());
    }
    a.raw(speeds);
    if constexpr (A::kReads) {
      StateIn s(speeds.data(), speeds.size(), a.what());
      s(speeds_);
      if (!s.done()) s.fail("bytes left after the rerouting device's speeds");
    }
    a(carry_);
    if constexpr (A::kReads) router_stale_ = carry_.router_sample != 0;
  }

 private:
  void share(std::vector<NewRoute>& routes, BoundaryLink& link);

  ReroutingOptions options_;
  int threads_;
  int64_t begin_ms_, step_ms_;
  Router router_;                         // on `speeds_` once a sample was taken, on free-flow times before
  std::unique_ptr<CchRouter> hierarchy_;  // with contraction_hierarchy: ordered and contracted once
  RoutingSpeeds speeds_;
  LaneSpeedSums lanes_;  // the sample's scratch
  ReroutingCarry carry_;
  // The router's costs are not part of a saved state: one loaded with router_sample_ > 0 takes the speeds
  // of that sample anew before it next routes.
  bool router_stale_ = false;
};

}  // namespace lpsim

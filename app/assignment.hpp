#pragma once
// Dynamic user assignment as SUMO's duaIterate.py runs it, in one process: iterations of routing every
// vehicle on the travel times the last simulation measured and simulating the routes chosen. Differences to
// duaIterate, which shells out to duarouter and sumo: the network, the demand and the router stay loaded;
// the travel times go from the simulation's counters to the router without an edgeData file; routing and
// route choice use every thread.
//
// One iteration: each vehicle's fastest route at its depart time on the previous iteration's interval
// travel times (free flow at first; Router::route_timed, duarouter's Dijkstra on --weight-files with
// --weights.expand) joins its alternatives, of which it chooses one by Gawron's model
// (demand/route_choice.hpp; the draw keyed by seed, vehicle and iteration); the chosen routes are simulated;
// the simulation's edge counters give every normal edge's travel time per aggregation interval as SUMO's
// edgeData traveltime (length * sampled seconds / distance, where at least one vehicle-second and some
// distance were sampled; else free flow, as duaIterate's dump with excludeEmpty and minSamples 1). Then
// every vehicle is routed again on those times: the routes are the next iteration's best responses, and
// their costs give the iteration's relative gap
//   (sum of each vehicle's route cost - sum of its best route's cost) / sum of the best routes' costs,
// both costed on the iteration's measured times at the planned depart (the route cost: the time-dependent
// travel time along the route driven, Router::timed_cost); `relative_gap` computes the same for routes and
// travel times from files (duaIterate's iterations).
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/config_spec.hpp"
#include "demand/demand.hpp"
#include "demand/route_choice.hpp"
#include "engine/simulation.hpp"
#include "net/cch_router.hpp"
#include "net/network.hpp"
#include "net/router.hpp"

namespace lpsim {

class PartLauncher;

/// Sums of the relative gap over the vehicles both costs are finite for.
struct GapSums {
  double route_cost_sum = 0, best_cost_sum = 0;  // s
  uint64_t vehicles = 0;
  double relative_gap() const {
    return best_cost_sum > 0 ? (route_cost_sum - best_cost_sum) / best_cost_sum : 0.0;
  }
};

/// The gap of `d`'s routes on `times` against the best routes' costs `best_cost` (per vehicle).
GapSums gap_sums(const Router& router, const Demand& d, const IntervalTravelTimes& times,
                 const std::vector<double>& best_cost);
/// The relative gap of `d`'s routes on `times`, each vehicle's best route found by `router` (as an
/// assignment iteration computes it; `threads` route).
GapSums relative_gap(const Network& net, const Router& router, const Demand& d,
                     const IntervalTravelTimes& times, int threads);

struct IterationResult {
  int iteration = 0;
  GapSums gap;
  uint64_t vehicles = 0, finished = 0, teleports = 0;
  double mean_trip_time = 0;  // s: mean duration of the finished trips
  double routing_cpu_seconds = 0, simulation_cpu_seconds = 0;
  // The iteration's wall time, and of that its simulation's: with the simulation on a GPU the CPU seconds
  // do not say how long an iteration takes.
  double wall_seconds = 0, simulation_wall_seconds = 0;
};

class Assignment {
 public:
  /// `demand`: the scenario's vehicles, each assigned from its route's first edge to its last (through its
  /// via and stop edges); vehicles no route reaches keep their loaded route. `options` are the iterations'
  /// simulation options (lane counters are switched on). `begin`/`end`: the simulated span (end < 0: until
  /// every vehicle has arrived); `threads` route and choose (0: all cores).
  /// With `hierarchy` the best routes come from a contraction hierarchy customized per aggregation interval,
  /// each vehicle routed on its depart interval's times (duarouter's CH with --weight-period); they are
  /// then costed time-dependently like any route. Vehicles departing after `end` are not routed.
  Assignment(const Network& net, Demand demand, SimulationOptions options, const AssignSpec& spec,
             double begin, double end, int threads, bool hierarchy = false);
  /// Simulates each iteration in the parts `launcher` starts (null, the default: one part in this process).
  /// Its parts give the same results as one part. Under mpirun rank 0 measures the travel times and the
  /// trips and passes them on, so that every rank routes and chooses as rank 0 does (the same choices: each
  /// draw is keyed by vehicle and iteration) and iterate() returns the same results on every rank but for
  /// their CPU seconds. The launcher outlives the iterations.
  void simulate_in(PartLauncher* launcher) { launcher_ = launcher; }

  /// Goes on from iteration `first` of an assignment that left each vehicle (by id) with `alternatives` and
  /// its route chosen among them (an .rou.alt.xml): the next iterate() first simulates the chosen routes
  /// again to measure their times, then runs iteration `first` as the uninterrupted assignment would have.
  /// Vehicles without alternatives there start afresh.
  void resume(int first, const std::unordered_map<std::string, RouteAlternatives>& alternatives);

  /// Runs the next iteration and returns its results.
  IterationResult iterate();
  int iterations_done() const { return done_; }

  /// The demand with the last iteration's chosen routes, and each vehicle's alternatives (empty for those
  /// kept on their loaded route).
  const Demand& assigned() const { return assigned_; }
  const std::vector<RouteAlternatives>& alternatives() const { return alternatives_; }

 private:
  // Routes every vehicle on `times_` at its depart time: best_ and best_cost_.
  void route_all();
  void choose_routes();
  // What an iteration's simulation gives besides the travel times.
  struct Simulated {
    uint64_t finished = 0, teleports = 0;
    double mean_trip_time = 0;
  };
  // Simulates assigned_ and measures times_.
  Simulated simulate();
  Simulated simulate_part0(const SimulationOptions& options);
  // Under mpirun: rank 0's times_ and `s` on every rank.
  void share_with_ranks(Simulated* s);

  const Network& net_;
  const Demand base_;
  Demand assigned_;
  SimulationOptions options_;
  AssignSpec spec_;
  RouteChoiceOptions choice_;
  double begin_, end_;
  int threads_;
  Router router_;
  std::unique_ptr<CchRouter> hierarchy_;
  Router interval_router_;  // the hierarchy's metric of one interval
  std::vector<RouteRequest> requests_;
  IntervalTravelTimes times_;
  std::vector<std::vector<uint32_t>> best_;
  std::vector<double> best_cost_;
  std::vector<RouteAlternatives> alternatives_;
  int done_ = 0;
  bool resumed_ = false;
  PartLauncher* launcher_ = nullptr;  // null: one part
};

}  // namespace lpsim

#pragma once
// A run whose trip table changes while it runs (src/demand/trip_table.hpp): trips added mid-run (due at once,
// due in the past, due later) and routes replaced (a running vehicle's remaining route, a waiting vehicle's
// whole route), checked by the invariant checker after every step and recorded in comparable form, for the
// CPU suite (behaviour) and the GPU suites (the same run, bit for bit, on the CUDA backend).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "net/router.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {

struct TripChangesRun {
  RunResult result;
  std::vector<TripRecord> trips;  // every trip record, in the order written
  std::vector<double> fcd;        // per step and running vehicle: time, vehicle, lane, pos, speed
  uint32_t loaded = 0;            // trips loaded with the scenario
  std::vector<uint32_t> added;    // the trips added
  uint32_t rerouted = 0;          // the running vehicle given a new route
  std::vector<uint32_t> new_route;
  std::vector<uint32_t> visited;  // normal edges the rerouted vehicle was on from the reroute on
  uint32_t rerouted_waiting = 0;  // a vehicle not yet departed given a new route
  std::vector<uint32_t> waiting_route;
  std::vector<uint32_t> waiting_visited;
};

/// The normal edges of the fastest path from edge `from` through `via` to `to` (empty: none).
inline std::vector<uint32_t> path_through(const Network& net, uint32_t from, uint32_t via, uint32_t to) {
  const Router router(net);
  const std::vector<std::vector<uint32_t>> paths = router.route_all({RouteRequest{{via}, {to}, {}}}, 1);
  if (paths[0].empty()) return {};
  std::vector<uint32_t> route{from};
  route.insert(route.end(), paths[0].begin(), paths[0].end());
  return route;
}

/// The running vehicle to reroute at a normal lane, and its new route: from its edge into another successor
/// than the one its route takes, then the fastest way to its old destination. None: rerouted stays -1.
inline int64_t pick_reroute(const Simulation& sim, const Network& net, std::vector<uint32_t>& route) {
  const Demand& d = sim.demand();
  for (const uint32_t v : sim.active()) {
    if (sim.query().status(v) != kRunning) continue;
    const int32_t lane = sim.query().lane(v);
    const uint32_t edge = net.lane_edge[static_cast<uint32_t>(lane)];
    if (net.edge_is_internal[edge]) continue;
    const uint32_t* old = d.route_edges.data() + d.route_begin[v];
    const uint32_t rp = sim.query().route_pos(v), len = d.route_length[v];
    if (old[rp] != edge || rp + 3 >= len) continue;
    for (uint32_t i = net.edge_succ_begin[edge]; i < net.edge_succ_begin[edge + 1]; ++i) {
      const uint32_t next = net.edge_succ[i];
      if (next == old[rp + 1]) continue;
      route = path_through(net, edge, next, old[len - 1]);
      if (route.size() >= 3) return v;
    }
  }
  return -1;
}

/// Adds trips at t = 60 (copies of the first loaded trips' routes: due now, due 50 s ago, due in 30 s),
/// reroutes a running vehicle at t = 90 and a not yet departed one at once, and runs to the end with every
/// invariant checked after every step.
inline TripChangesRun run_with_trip_changes(const Scenario& sc, SimulationOptions options) {
  TripChangesRun out;
  options.time_to_teleport = 0;  // no teleport skips an edge of the routes followed below
  Simulation sim(sc.network, sc.demand, options);
  InvariantChecker checker(sc, sim, 1);
  const Network& net = sc.network;
  out.loaded = sim.demand().size();
  FcdFrame frame;
  auto edge_of = [&](uint32_t v) { return net.lane_edge[static_cast<uint32_t>(sim.query().lane(v))]; };
  auto follow = [&](uint32_t v, std::vector<uint32_t>& visited) {
    if (sim.query().status(v) != kRunning) return;
    const uint32_t e = edge_of(v);
    if (!net.edge_is_internal[e] && (visited.empty() || visited.back() != e)) visited.push_back(e);
  };
  bool added = false, rerouted = false;
  int64_t waiting = -1;
  while (!sim.finished() && sim.time() < 7200) {
    if (!added && sim.time() >= 60) {
      added = true;
      const Demand& d = sim.demand();
      CommandQueue queue;
      for (uint32_t k = 0; k < 12; ++k) {
        NewTrip t;
        t.id = "added_" + std::to_string(k);
        t.type = d.vehicle_type[k];
        t.depart = sim.time() + (k % 3 == 0 ? 0.0 : k % 3 == 1 ? -50.0 : 30.0);
        t.route.assign(d.route_edges.begin() + d.route_begin[k],
                       d.route_edges.begin() + d.route_begin[k] + d.route_length[k]);
        t.speed_factor = 0.9f + 0.02f * static_cast<float>(k);
        queue.push(VehicleCommand::add(t));
      }
      // The last loaded trip has not departed yet: it gets a route through another first successor.
      const uint32_t last = out.loaded - 1;
      const uint32_t first = d.route_edges[d.route_begin[last]];
      const uint32_t dest = d.route_edges[d.route_begin[last] + d.route_length[last] - 1];
      EXPECT_EQ(sim.query().status(last), kPending);
      for (uint32_t i = net.edge_succ_begin[first]; i < net.edge_succ_begin[first + 1] && waiting < 0; ++i) {
        if (net.edge_succ[i] == d.route_edges[d.route_begin[last] + 1]) continue;
        out.waiting_route = path_through(net, first, net.edge_succ[i], dest);
        if (out.waiting_route.size() >= 3) waiting = last;
      }
      EXPECT_GE(waiting, 0) << "no other route for the last trip";
      if (waiting >= 0) {
        queue.push(VehicleCommand::set_route(static_cast<uint32_t>(waiting), out.waiting_route));
        out.rerouted_waiting = static_cast<uint32_t>(waiting);
      }
      for (const CommandOutcome& o : sim.apply_commands(queue.take())) {
        EXPECT_TRUE(o.done()) << o.error;
        if (out.added.size() < 12) out.added.push_back(o.vehicle);
      }
    }
    if (!rerouted && sim.time() >= 90) {
      rerouted = true;
      const int64_t v = pick_reroute(sim, net, out.new_route);
      EXPECT_GE(v, 0) << "no running vehicle to reroute at t=" << sim.time();
      if (v >= 0) {
        out.rerouted = static_cast<uint32_t>(v);
        const CommandOutcome o =
            sim.apply_commands({VehicleCommand::set_route(out.rerouted, out.new_route)})[0];
        EXPECT_TRUE(o.done()) << o.error;
        EXPECT_EQ(sim.query().route_pos(out.rerouted), 0u);
        out.visited.push_back(out.new_route.front());
      }
    }
    checker.before_step();
    sim.step();
    checker.after_step();
    if (rerouted && !out.new_route.empty()) follow(out.rerouted, out.visited);
    if (waiting >= 0) follow(out.rerouted_waiting, out.waiting_visited);
    sim.sample_fcd(frame);
    for (size_t i = 0; i < frame.vehicle.size(); ++i)
      out.fcd.insert(out.fcd.end(), {frame.time, double(frame.vehicle[i]), double(frame.lane[i]),
                                     double(frame.pos[i]), double(frame.speed[i])});
  }
  checker.expect_no_failures("run with trip changes");
  out.result = RunResult{checker.stats(), sim.counts(), sim.finished(), checker.failure_count()};
  out.trips = checker.trips();
  return out;
}

/// Bit for bit: the same positions every step and the same trip records.
inline void expect_same_run(const TripChangesRun& a, const TripChangesRun& b, const std::string& what) {
  EXPECT_EQ(a.fcd.size(), b.fcd.size()) << what;
  EXPECT_TRUE(a.fcd.size() == b.fcd.size() &&
              std::memcmp(a.fcd.data(), b.fcd.data(), a.fcd.size() * sizeof(double)) == 0)
      << what << ": positions differ";
  ASSERT_EQ(a.trips.size(), b.trips.size()) << what;
  for (size_t i = 0; i < a.trips.size(); ++i) {
    const TripRecord &x = a.trips[i], &y = b.trips[i];
    EXPECT_TRUE(x.vehicle == y.vehicle && x.depart == y.depart && x.arrival == y.arrival &&
                x.arrival_lane == y.arrival_lane && x.arrival_pos == y.arrival_pos &&
                x.route_length == y.route_length && x.waiting_time == y.waiting_time &&
                x.time_loss == y.time_loss)
        << what << ": trip record " << i << " differs";
  }
  EXPECT_EQ(a.rerouted, b.rerouted) << what;
}

}  // namespace lpsim::engine_test

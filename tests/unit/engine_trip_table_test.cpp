// A trip table that grows while the run goes on: trips added mid-run are inserted and arrive like loaded
// ones, a running vehicle given a new route drives exactly that route, a waiting one departs on its new
// route, and routes that do not lead on from where a vehicle is are refused. Every invariant is checked
// after every step (tests/unit/trip_changes.hpp); the GPU suites run the same and compare bit for bit.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "unit/trip_changes.hpp"

namespace lpsim::engine_test {
namespace {

SimulationOptions with_threads(SimulationOptions o, int threads) {
  o.threads = threads;
  return o;
}

const TripRecord* record_of(const TripChangesRun& run, uint32_t v) {
  for (const TripRecord& r : run.trips)
    if (r.vehicle == v) return &r;
  return nullptr;
}

TEST(EngineTripTableTest, AddedTripsAndNewRoutesAreDrivenToTheEnd) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const TripChangesRun run = run_with_trip_changes(sc, simulation_options(sc.config));
  const Network& net = sc.network;
  EXPECT_EQ(run.result.failures, 0u);
  expect_all_arrived(run.result, "grid_tls with trip changes");
  EXPECT_EQ(run.result.counts.loaded, run.loaded + run.added.size());

  // Each added trip departed no earlier than it was due and arrived at the end of its route.
  ASSERT_EQ(run.added.size(), 12u);
  for (size_t k = 0; k < run.added.size(); ++k) {
    const uint32_t v = run.added[k];
    EXPECT_EQ(v, run.loaded + k);
    const TripRecord* r = record_of(run, v);
    ASSERT_NE(r, nullptr) << "added trip " << k << " has no trip record";
    const double due = 60.0 + (k % 3 == 0 ? 0.0 : k % 3 == 1 ? -50.0 : 30.0);
    EXPECT_GE(r->depart, std::max(due, 60.0)) << "added trip " << k;
    EXPECT_FALSE(r->teleported);
    const uint32_t last = sc.demand.route_edges[sc.demand.route_begin[k] + sc.demand.route_length[k] - 1];
    EXPECT_EQ(net.lane_edge[r->arrival_lane], last) << "added trip " << k;
  }

  // The rerouted running vehicle drove exactly its new route from where it was, and arrived at its end.
  ASSERT_GE(run.new_route.size(), 3u);
  EXPECT_EQ(run.visited, run.new_route);
  const TripRecord* r = record_of(run, run.rerouted);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(net.lane_edge[r->arrival_lane], run.new_route.back());
  // Its second edge is not the one its loaded route took next.
  const std::vector<uint32_t>& old = sc.demand.route_edges;
  const uint32_t* b = old.data() + sc.demand.route_begin[run.rerouted];
  const uint32_t* e = b + sc.demand.route_length[run.rerouted];
  const auto at = std::find(b, e, run.new_route[0]);
  ASSERT_NE(at, e);
  EXPECT_NE(*(at + 1), run.new_route[1]);

  // The vehicle rerouted before it departed drove its new route, not its loaded one.
  ASSERT_GE(run.waiting_route.size(), 3u);
  EXPECT_EQ(run.waiting_visited, run.waiting_route);
  EXPECT_NE(run.waiting_route[1], sc.demand.route_edges[sc.demand.route_begin[run.rerouted_waiting] + 1]);
}

TEST(EngineTripTableTest, ThreadCountsGiveTheSameRun) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  expect_same_run(run_with_trip_changes(sc, simulation_options(sc.config)),
                  run_with_trip_changes(sc, with_threads(simulation_options(sc.config), 2)),
                  "1 vs 2 threads");
}

TEST(EngineTripTableTest, RoutesThatDoNotLeadOnAreRefused) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
  const Network& net = sc.network;
  while (sim.time() < 100) sim.step();
  std::vector<uint32_t> route;
  const int64_t v = pick_reroute(sim, net, route);
  ASSERT_GE(v, 0);
  const uint32_t vehicle = static_cast<uint32_t>(v);
  auto refused = [&](std::vector<uint32_t> r, const std::string& what) {
    EXPECT_FALSE(sim.apply_commands({VehicleCommand::set_route(vehicle, r)})[0].done()) << what;
  };
  refused({}, "empty");
  refused(std::vector<uint32_t>(route.begin() + 1, route.end()), "not starting at the vehicle's edge");
  std::vector<uint32_t> gap = route;
  gap.erase(gap.begin() + 1);
  refused(gap, "not connected");
  refused({route[0], net.num_edges()}, "no such edge");
  // An arrived vehicle's trip has ended.
  while (!sim.finished() && sim.counts().arrived == 0) sim.step();
  for (uint32_t a = 0; a < sim.demand().size(); ++a)
    if (sim.query().status(a) == kArrived) {
      const Demand& d = sim.demand();
      const CommandOutcome o = sim.apply_commands({VehicleCommand::set_route(
          a, std::vector<uint32_t>(d.route_edges.begin() + d.route_begin[a],
                                   d.route_edges.begin() + d.route_begin[a] + 1))})[0];
      EXPECT_NE(o.error.find("its trip has ended"), std::string::npos) << o.error;
      break;
    }
  // A refused route changed nothing: the vehicle still takes the same route as in a run without them.
  EXPECT_EQ(sim.demand().route_edges.size(), sc.demand.route_edges.size());
}

TEST(EngineTripTableTest, AddedTripsThatCannotRunAreRefused) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
  const Demand& d = sc.demand;
  NewTrip t;
  t.route.assign(d.route_edges.begin() + d.route_begin[0],
                 d.route_edges.begin() + d.route_begin[0] + d.route_length[0]);
  t.id = d.vehicle_id[0];
  auto add = [&](const NewTrip& trip) { return sim.apply_commands({VehicleCommand::add(trip)})[0]; };
  EXPECT_NE(add(t).error.find("the id is in use"), std::string::npos) << "an id in use";
  t.id = "fresh";
  t.type = d.types.size();
  EXPECT_FALSE(add(t).done()) << "an unknown type";
  t.type = 0;
  std::vector<uint32_t> gap = t.route;
  if (gap.size() >= 3) {
    gap.erase(gap.begin() + 1);
    NewTrip g = t;
    g.route = gap;
    EXPECT_FALSE(add(g).done()) << "an unconnected route";
  }
  NewTrip empty = t;
  empty.route.clear();
  EXPECT_FALSE(add(empty).done()) << "an empty route";
  EXPECT_EQ(sim.counts().loaded, d.size());
  const CommandOutcome added = add(t);
  EXPECT_TRUE(added.done()) << added.error;
  EXPECT_EQ(added.vehicle, d.size());
  EXPECT_EQ(sim.vehicle_index("fresh"), int64_t{d.size()});
  EXPECT_EQ(sim.vehicle_index(d.vehicle_id[3]), 3);
  EXPECT_EQ(sim.vehicle_index("no such vehicle"), -1);
  EXPECT_EQ(sim.counts().loaded, d.size() + 1);
}

}  // namespace
}  // namespace lpsim::engine_test

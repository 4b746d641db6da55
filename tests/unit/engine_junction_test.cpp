// Junction behaviour of the whole engine on the bundled flows scenario: at the priority junction B1 the
// west-east flow (minor road, 'm' links) crosses the north-south flows. SUMO 1.15 lets these vehicles
// through with about 1 s of waiting (mean trip 28.7 s) because a prioritised vehicle that has not yet
// announced its arrival brakes for a yielding vehicle already inside the junction.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kernels/right_of_way.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

struct FlowStats {
  int trips = 0;
  double duration_sum = 0, waiting_sum = 0;
};

FlowStats run_flow(const Scenario& sc, const std::string& prefix) {
  Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
  FlowStats st;
  while (!sim.finished() && sim.time() < 3600) {
    sim.step();
    for (const TripRecord& t : sim.take_finished_trips()) {
      if (sc.demand.vehicle_id[t.vehicle].rfind(prefix, 0) != 0) continue;
      ++st.trips;
      st.duration_sum += t.arrival - t.depart;
      st.waiting_sum += t.waiting_time;
    }
  }
  return st;
}

TEST(EngineJunctionTest, MinorFlowCrossesBetweenPrioritisedVehicles) {
  const Scenario sc = load_sumo_scenario("flows");
  const FlowStats st = run_flow(sc, "by_period.");
  ASSERT_EQ(st.trips, 60);
  // Both edges are 129 m at 13.9 m/s (about 19 s free flow). Waiting at B1 for gaps that fit the whole
  // crossing time of a standing vehicle in both major flows took 128 s per trip on average.
  EXPECT_LT(st.duration_sum / st.trips, 45.0);
  EXPECT_LT(st.waiting_sum / st.trips, 15.0);
}

TEST(EngineJunctionTest, PrioritisedFlowKeepsMoving) {
  const Scenario sc = load_sumo_scenario("flows");
  // The slow north-south flow (10 m/s, 2 x 129 m) has priority at B1: braking for minor vehicles already
  // in the junction may cost it a little, never a queue.
  const FlowStats st = run_flow(sc, "by_number.");
  ASSERT_EQ(st.trips, 40);
  EXPECT_LT(st.duration_sum / st.trips, 40.0);
}

TEST(EngineJunctionTest, MinorLinkIsCrossedOnlyFromWithinTheFoeVisibilityDistance) {
  // A1B1's links at B1 are 'm' without an internal junction. As in SUMO, a vehicle that cannot yet see the
  // foes (farther than 4.5 m from the line) plans to stop at the line, so it crosses only from closer, even
  // with no foe in sight.
  const Scenario sc = load_sumo_scenario("flows");
  Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
  const Network& net = sc.network;
  std::vector<uint32_t> tracked;
  for (uint32_t v = 0; v < sc.demand.vehicle_id.size(); ++v)
    if (sc.demand.vehicle_id[v].rfind("by_period.", 0) == 0) tracked.push_back(v);
  ASSERT_EQ(tracked.size(), 60u);
  auto on_approach = [&](int32_t lane) { return lane >= 0 && net.edge_id[net.lane_edge[lane]] == "A1B1"; };
  int crossings = 0, from_afar = 0;
  std::vector<int32_t> lane(tracked.size(), -1);
  std::vector<float> dist(tracked.size(), 0.0f);
  while (!sim.finished() && sim.time() < 3600) {
    for (size_t k = 0; k < tracked.size(); ++k) {
      lane[k] = sim.query().lane(tracked[k]);
      dist[k] = lane[k] >= 0 ? net.lane_length[lane[k]] - sim.query().pos(tracked[k]) : 0.0f;
    }
    sim.step();
    for (size_t k = 0; k < tracked.size(); ++k) {
      if (!on_approach(lane[k]) || on_approach(sim.query().lane(tracked[k]))) continue;
      ++crossings;
      if (dist[k] > 4.5f) ++from_afar;
    }
  }
  EXPECT_EQ(crossings, 60);
  EXPECT_EQ(from_afar, 0);
}

TEST(EngineJunctionTest, InternalJunctionIsCrossedOnlyFromWithinTheFoeVisibilityDistance) {
  // grid_tls's turns with an internal junction: a vehicle that entered on a link without priority waits at
  // the internal junction until it is within 4.5 m of it, as SUMO's do (not after a 'G' or yellow entry).
  const Scenario sc = load_sumo_scenario("grid_tls");
  const Network& net = sc.network;
  Simulation sim(sc.network, sc.demand, simulation_options(sc.config));
  std::vector<int32_t> entry(net.lane_id.size(), -1);  // first internal lane -> the connection entering it
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    const int32_t via = net.conn_via_lane[c];
    if (via < 0) continue;
    const uint32_t b = net.lane_conn_begin[via];
    if (b < net.lane_conn_begin[via + 1] && net.conn_via_lane[b] >= 0) entry[via] = static_cast<int32_t>(c);
  }
  const uint32_t n = static_cast<uint32_t>(sc.demand.vehicle_id.size());
  std::vector<int32_t> lane(n);
  std::vector<float> dist(n);
  int crossings = 0, from_afar = 0;
  while (!sim.finished() && sim.time() < 3600) {
    for (uint32_t v = 0; v < n; ++v) {
      lane[v] = sim.query().lane(v);
      dist[v] = lane[v] >= 0 ? net.lane_length[lane[v]] - sim.query().pos(v) : 0.0f;
    }
    sim.step();
    for (uint32_t v = 0; v < n; ++v) {
      if (lane[v] < 0 || entry[lane[v]] < 0 || sim.query().lane(v) == lane[v]) continue;
      if (link_rule(sim.query(StateParts::Full).link_state(static_cast<uint32_t>(entry[lane[v]]))) ==
          LinkRule::Priority)
        continue;
      ++crossings;
      if (dist[v] > 4.5f) ++from_afar;
    }
  }
  EXPECT_GT(crossings, 100);
  EXPECT_EQ(from_afar, 0);
}

}  // namespace
}  // namespace lpsim::engine_test

// Lanes another simulator drives (the co-simulation's corridor): a vehicle whose route enters one leaves the
// simulation at the end of the step its front reaches it, there, once, at its position and speed, with every
// vehicle counted in exactly one state each step; vehicles written onto those lanes from outside hold the
// traffic behind them (the queue spills back; a vehicle standing time-to-teleport re-enters in the corridor,
// handed out), and once they are gone it flows in again. The lane map stays
// consistent throughout (check_lane_map counts the cells written from outside).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/simulation_options.hpp"
#include "engine/outside_link.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {
namespace {

// The `n` edges most routes use: a corridor most vehicles cross.
std::vector<uint32_t> busiest_edges(const Demand& d, size_t n) {
  std::map<uint32_t, uint32_t> uses;
  for (uint32_t v = 0; v < d.size(); ++v)
    for (uint32_t i = 1; i < d.route_length[v]; ++i) ++uses[d.route_edges[d.route_begin[v] + i]];
  std::vector<std::pair<uint32_t, uint32_t>> by_use;
  for (const auto& [e, u] : uses) by_use.push_back({u, e});
  std::sort(by_use.rbegin(), by_use.rend());
  std::vector<uint32_t> edges;
  for (size_t i = 0; i < n && i < by_use.size(); ++i) edges.push_back(by_use[i].second);
  return edges;
}

std::vector<uint8_t> lanes_of(const Network& net, const std::vector<uint32_t>& edges) {
  std::vector<uint8_t> outside(net.num_lanes(), 0);
  for (const uint32_t e : edges)
    for (uint32_t l = net.edge_first_lane[e]; l < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++l)
      outside[l] = 1;
  return outside;
}

// Route position of the first outside edge of v's route after its first edge (-1: none).
int32_t first_outside(const Demand& d, uint32_t v, const std::set<uint32_t>& outside) {
  for (uint32_t i = 1; i < d.route_length[v]; ++i)
    if (outside.count(d.route_edges[d.route_begin[v] + i])) return static_cast<int32_t>(i);
  return -1;
}

uint64_t not_yet_due(const Simulation& sim, const Scenario& sc) {
  uint64_t n = 0;
  for (uint32_t v = 0; v < sc.demand.size(); ++v) n += sc.demand.depart[v] > sim.time() + 1e-9 ? 1 : 0;
  return n;
}

TEST(EngineOutsideLanesTest, VehiclesLeaveWhereTheirRouteEntersTheCorridorOnceAtSpeed) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const Network& net = sc.network;
  const Demand& d = sc.demand;
  const std::vector<uint32_t> corridor = busiest_edges(d, 3);
  const std::set<uint32_t> corridor_set(corridor.begin(), corridor.end());
  const std::vector<uint8_t> outside = lanes_of(net, corridor);
  SimulationOptions options = simulation_options(sc.config);
  options.outside_lanes = &outside;
  Simulation sim(net, d, options);
  std::map<uint32_t, OutsideLink::HandOut> out;
  uint64_t departed_outside = 0;
  for (int step = 0; step < 4000 && !sim.finished(); ++step) {
    sim.step();
    for (const OutsideLink::HandOut& h : sim.outside_link().hand_outs()) {
      EXPECT_TRUE(out.emplace(h.vehicle, h).second) << "vehicle " << h.vehicle << " handed out twice";
      EXPECT_EQ(sim.query().status(h.vehicle), kMigrated);
      departed_outside += h.lane < 0 ? 1 : 0;
    }
    // No vehicle stays on a corridor lane, and every one is in exactly one state.
    for (const uint32_t v : sim.active())
      if (sim.query().status(v) == kRunning) {
        ASSERT_GE(sim.query().lane(v), 0);
        EXPECT_FALSE(corridor_set.count(net.lane_edge[static_cast<uint32_t>(sim.query().lane(v))])) << v;
      }
    const Simulation::Counts& c = sim.counts();
    EXPECT_EQ(c.inserted + departed_outside, c.arrived + c.running + sim.outside_link().handed_out())
        << "t=" << sim.time();
    if (step % 50 == 0) {
      ASSERT_EQ(sim.check_lane_map(), "") << "t=" << sim.time();
    }
  }
  EXPECT_TRUE(sim.finished());
  EXPECT_EQ(sim.outside_link().handed_out(), out.size());
  // Exactly the vehicles whose route enters the corridor left, each on the first corridor edge of its route,
  // near the start of its lane and at a speed it could drive.
  uint32_t entering = 0;
  for (uint32_t v = 0; v < d.size(); ++v) {
    if (corridor_set.count(d.route_edges[d.route_begin[v]])) {  // departs in the corridor: never drove here
      ASSERT_TRUE(out.count(v)) << "vehicle " << v << " departing in the corridor was not handed out";
      EXPECT_EQ(out.at(v).lane, -1);
      continue;
    }
    const int32_t rp = first_outside(d, v, corridor_set);
    if (rp < 0) {
      EXPECT_FALSE(out.count(v)) << "vehicle " << v << " never enters the corridor";
      continue;
    }
    ++entering;
    ASSERT_TRUE(out.count(v)) << "vehicle " << v << " was not handed out";
    const OutsideLink::HandOut& h = out.at(v);
    EXPECT_EQ(h.route_pos, static_cast<uint32_t>(rp)) << v;
    EXPECT_EQ(net.lane_edge[static_cast<uint32_t>(h.lane)], d.route_edges[d.route_begin[v] + h.route_pos]);
    EXPECT_GE(h.pos, 0.0f);
    EXPECT_LE(h.pos, h.speed * 1.0f + 0.01f) << v;  // it reached the lane in this step
    EXPECT_LE(h.speed, net.lane_speed[static_cast<uint32_t>(h.lane)] * 2.0f) << v;
  }
  EXPECT_GT(entering, 20u);
  EXPECT_GT(std::count_if(out.begin(), out.end(), [](const auto& o) { return o.second.speed > 1.0f; }), 10)
      << "vehicles enter the corridor moving";
}

TEST(EngineOutsideLanesTest, VehiclesMirroredOnTheCorridorHoldTheTrafficBehindThem) {
  const Scenario sc = load_sumo_scenario("grid_tls");
  const Network& net = sc.network;
  const std::vector<uint32_t> corridor = busiest_edges(sc.demand, 3);
  const std::vector<uint8_t> outside = lanes_of(net, corridor);
  SimulationOptions options = simulation_options(sc.config);
  options.outside_lanes = &outside;
  Simulation sim(net, sc.demand, options);
  // A standing vehicle at the start of every corridor lane: nothing can enter.
  std::vector<OutsideLink::OutsideVehicle> blockers;
  for (uint32_t l = 0; l < net.num_lanes(); ++l)
    if (outside[l])
      blockers.push_back(OutsideLink::OutsideVehicle{static_cast<int32_t>(l), 5.0f, 5.0f, 0.0f});
  uint64_t teleported_in = 0;
  for (int step = 0; step < 600; ++step) {
    sim.outside_link().mirror_outside_vehicles(blockers);
    if (step % 100 == 0) {
      ASSERT_EQ(sim.check_lane_map(), "") << "t=" << sim.time();
    }
    sim.step();
    for (const OutsideLink::HandOut& h : sim.outside_link().hand_outs()) {
      teleported_in += h.lane < 0 && h.route_pos > 0 ? 1 : 0;
      EXPECT_EQ(h.lane, -1) << "t=" << sim.time() << ": vehicle " << h.vehicle
                            << " drove into the corridor at " << h.pos << " speed " << h.speed;
    }
  }
  // Every vehicle is in one state: on the road, waiting, arrived, or handed out (at its departure, or
  // teleported into the corridor after standing time-to-teleport).
  const Simulation::Counts& c = sim.counts();
  EXPECT_EQ(c.loaded, c.removed + c.arrived + c.running + c.waiting + sim.outside_link().handed_out() +
                          not_yet_due(sim, sc));
  EXPECT_GT(teleported_in, 0u) << "vehicles stood time-to-teleport and re-entered in the corridor";
  // The queues before the corridor stand.
  uint32_t standing = 0;
  for (const uint32_t v : sim.active())
    if (sim.query().status(v) == kRunning && sim.query().speed(v) < 0.1f) ++standing;
  EXPECT_GT(standing, 5u);
  // The blockers leave: traffic flows in.
  const uint64_t before = sim.outside_link().handed_out();
  uint64_t drove_in = 0;
  for (int step = 0; step < 300; ++step) {
    sim.outside_link().mirror_outside_vehicles({});
    sim.step();
    for (const OutsideLink::HandOut& h : sim.outside_link().hand_outs()) drove_in += h.lane >= 0 ? 1 : 0;
  }
  EXPECT_GT(sim.outside_link().handed_out(), before);
  EXPECT_GT(drove_in, standing / 2);
  EXPECT_EQ(sim.check_lane_map(), "");
}

}  // namespace
}  // namespace lpsim::engine_test

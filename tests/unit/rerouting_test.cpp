// The rerouting device's parts: SUMO's averaged edge speeds (RoutingSpeeds), the router on them, and which
// vehicles SUMO equips (ReroutingEquipment).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "core/demand_spec.hpp"
#include "core/vclass.hpp"
#include "demand/rerouting_equipment.hpp"
#include "engine/routing_speeds.hpp"
#include "lpsim_cli.hpp"
#include "net/network_builder.hpp"
#include "net/router.hpp"
#include "temp_dir.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

// A two-lane corridor at 13.89 m/s whose first edge has a sidewalk LPSim leaves out (1.39 m/s).
Network corridor_with_sidewalk() {
  NetSpec spec = test::make_corridor_spec(3, 100, 2);
  LaneSpec walk = spec.edges.front().lanes.front();
  walk.id = spec.edges.front().id + "_walk";
  walk.index = 2;
  walk.speed = 1.39;
  walk.allow = "pedestrian";
  walk.permissions = vclass_name_bit("pedestrian");
  spec.edges.front().lanes.push_back(walk);
  return build_network(spec);
}

TEST(RoutingSpeedsTest, AnEdgesMeanSpeedWeighsLanesByTheirVehiclesAndCountsEmptyLanesOnce) {
  const Network net = corridor_with_sidewalk();
  const uint32_t e0 = net.edge_index.at("E0"), e1 = net.edge_index.at("E1");
  ASSERT_EQ(net.edge_num_lanes[e0], 2);
  ASSERT_EQ(net.edge_other_lanes[e0], 1);
  const RoutingSpeeds speeds(net, 3, 0);
  LaneSpeedSums lanes(net.num_lanes());
  // Empty: the lanes' speed limits, the sidewalk's too.
  EXPECT_NEAR(speeds.mean_speed(e0, &lanes), (13.89 + 13.89 + 1.39) / 3, 1e-5);
  EXPECT_NEAR(speeds.mean_speed(e1, &lanes), 13.89, 1e-5);
  // Two vehicles at 5 and 7 m/s on E1's first lane, the second lane empty: (5 + 7 + 13.89) / 3.
  const uint32_t l = net.edge_first_lane[e1];
  lanes.add(l, 5.0f);
  lanes.add(l, 7.0f);
  EXPECT_NEAR(speeds.mean_speed(e1, &lanes), (5.0 + 7.0 + 13.89) / 3, 1e-5);
}

TEST(RoutingSpeedsTest, SamplesAreAveragedOverTheLastStepsOrExponentially) {
  const Network net = build_network(test::make_corridor_spec(2, 100, 1));
  const uint32_t e = net.edge_index.at("E0");
  const uint32_t l = net.edge_first_lane[e];
  LaneSpeedSums stopped(net.num_lanes());
  stopped.add(l, 0.0f);
  const LaneSpeedSums empty(net.num_lanes());
  const double limit = net.lane_speed[l];

  RoutingSpeeds moving(net, 3, 0);
  EXPECT_NEAR(moving.speeds()[e], limit, 1e-6);
  moving.add_sample(stopped);
  EXPECT_NEAR(moving.speeds()[e], limit * 2 / 3, 1e-5);
  moving.add_sample(stopped);
  moving.add_sample(stopped);
  EXPECT_NEAR(moving.speeds()[e], 0.0, 1e-5);
  moving.add_sample(empty);  // the oldest stopped sample leaves the average
  EXPECT_NEAR(moving.speeds()[e], limit / 3, 1e-5);
  EXPECT_EQ(moving.samples(), 4u);

  RoutingSpeeds exponential(net, 0, 0.25);
  exponential.add_sample(stopped);
  EXPECT_NEAR(exponential.speeds()[e], limit * 0.25, 1e-5);
}

// On a 3 x 3 grid from the bottom-left corner's edge east to the far one: a slow edge on the free-flow path
// sends the route round it; free-flow speeds give back the free-flow costs exactly.
TEST(RouterSpeedsTest, SlowEdgesCostTheirLengthOverTheAveragedSpeed) {
  const Network net = build_network(test::make_grid_spec(3, 3));
  Router router(net);
  const Router free_flow(net);
  RouteRequest q;
  q.origins = {net.edge_index.at(test::grid_edge(0, 0, 1, 0))};
  q.destinations = {net.edge_index.at(test::grid_edge(2, 1, 2, 2))};
  const std::vector<uint32_t> direct = free_flow.route_all({q}, 1).at(0);
  ASSERT_GE(direct.size(), 3u);
  std::vector<double> speeds(net.num_edges());
  for (uint32_t e = 0; e < net.num_edges(); ++e) speeds[e] = net.edge_speed[e];
  router.set_speeds(speeds);
  EXPECT_EQ(router.cost(direct), free_flow.cost(direct));
  const uint32_t middle = direct[1];
  speeds[middle] = 0.5;
  router.set_speeds(speeds);
  EXPECT_NEAR(router.cost(direct) - free_flow.cost(direct),
              net.edge_length[middle] / 0.5 - net.edge_length[middle] / net.edge_speed[middle], 1e-3);
  const std::vector<uint32_t> around = router.route_all({q}, 1).at(0);
  EXPECT_EQ(std::count(around.begin(), around.end(), middle), 0) << "still through the slow edge";
  EXPECT_EQ(around.front(), direct.front());
  EXPECT_EQ(around.back(), direct.back());
  // Faster than the limit is never cheaper than free flow.
  speeds[middle] = 100;
  router.set_speeds(speeds);
  EXPECT_EQ(router.cost(direct), free_flow.cost(direct));
  EXPECT_THROW(router.set_speeds({1.0}), std::invalid_argument);
}

VehicleTypes one_type(const std::string& id) {
  VehicleTypes t;
  t.id = {id};
  return t;
}

TEST(ReroutingEquipmentTest, ExplicitThenOwnParamThenTypeParamThenProbability) {
  DemandSpec spec;
  VTypeSpec typed;
  typed.id = "typed";
  typed.params["has.rerouting.device"] = "false";
  spec.vtypes.push_back(typed);
  ReroutingSpec options;
  options.probability = 1;
  options.explicit_ids = {"named"};
  const ReroutingEquipment plain(options, spec, one_type("car"), 1);
  EXPECT_TRUE(plain.equipped("anyone", 7, 0, 0, -1));
  EXPECT_FALSE(plain.equipped("anyone", 7, 0, 0, 0));  // its own param says no
  EXPECT_TRUE(plain.equipped("named", 7, 0, 0, 0));    // named explicitly: always
  const ReroutingEquipment by_type(options, spec, one_type("typed"), 1);
  EXPECT_FALSE(by_type.equipped("anyone", 7, 0, 0, -1));
  EXPECT_TRUE(by_type.equipped("anyone", 7, 0, 0, 1));
  options = ReroutingSpec{};
  const ReroutingEquipment none(options, spec, one_type("car"), 1);
  EXPECT_FALSE(none.equipped("anyone", 7, 0, 0, -1));
}

TEST(ReroutingEquipmentTest, AProbabilityEquipsThatShareRandomlyOrExactlyWhenDeterministic) {
  const DemandSpec spec;
  ReroutingSpec options;
  options.probability = 0.3;
  const ReroutingEquipment random(options, spec, one_type("car"), 5);
  options.deterministic = true;
  const ReroutingEquipment counted(options, spec, one_type("car"), 5);
  int drawn = 0, quota = 0;
  for (uint32_t k = 0; k < 1000; ++k) {
    const std::string id = "v" + std::to_string(k);
    drawn += random.equipped(id, std::hash<std::string>{}(id), k, 0, -1) ? 1 : 0;
    quota += counted.equipped(id, 0, k, 0, -1) ? 1 : 0;
  }
  EXPECT_EQ(quota, 300);
  EXPECT_NEAR(drawn, 300, 50);
  EXPECT_TRUE(counted.equipped("a", 0, 0, 0, -1));  // SUMO's quota takes the first vehicle
}

// `lpsim info` says who has the device: every vehicle of reroute_block (probability 1), all but the one with
// a stop re-routing while driving; random_net's trips only by being trips.
TEST(ReroutingInfoTest, InfoCountsTheVehiclesWithTheDevice) {
  const std::string dir = LPSIM_SCENARIOS_DIR;
  const test::TempDir tmp("lpsim_rerouting_info");  // run_lpsim leaves stdout.txt and stderr.txt there
  const test::CliResult block =
      test::run_lpsim(tmp.path(), {"info", "-c", dir + "/reroute_block/reroute_block.sumocfg"});
  ASSERT_EQ(block.exit_code, 0) << block.err;
  EXPECT_NE(
      block.out.find("rerouting device: 121 (routed when due; equipped by options or params 121, of them "
                     "re-routing while driving 120; routes to repair 0)"),
      std::string::npos)
      << block.out;
  const test::CliResult trips =
      test::run_lpsim(tmp.path(), {"info", "-c", dir + "/random_net/random_net.sumocfg"});
  ASSERT_EQ(trips.exit_code, 0) << trips.err;
  EXPECT_NE(trips.out.find("rerouting device: 300 (routed when due; equipped by options or params 0,"),
            std::string::npos)
      << trips.out;
}

}  // namespace
}  // namespace lpsim

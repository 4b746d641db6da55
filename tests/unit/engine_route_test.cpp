// Routes through the whole engine: a route that comes back to a lane it used before is followed on the
// second visit as on the first, turning where the route turns (the connection chosen at a lane's end is
// cached per vehicle by lane and route position, so a revisit must not reuse the first visit's turn).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "demand/demand_builder.hpp"
#include "engine/engine_net.hpp"
#include "engine/simulation.hpp"
#include "kernels/vehicle_step.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

// A 3x2 grid of 100 m single-lane edges with 5 m internal lanes, and a route around its left square and then
// along the bottom row: J0_0toJ1_0 is left northwards the first time and straight on eastwards the second.
struct LoopRoute {
  Network net;
  std::vector<std::string> route;
  Demand demand;

  LoopRoute() {
    test::GridOptions grid;
    grid.with_internal = true;  // as in SUMO nets: the turn is taken over an internal lane
    net = build_network(test::make_grid_spec(3, 2, grid));
    route = {test::grid_edge(0, 0, 1, 0), test::grid_edge(1, 0, 1, 1), test::grid_edge(1, 1, 0, 1),
             test::grid_edge(0, 1, 0, 0), test::grid_edge(0, 0, 1, 0), test::grid_edge(1, 0, 2, 0)};
    DemandSpec spec;
    VehicleSpec v;
    v.id = "looper";
    v.loc = {"test.rou.xml", 1};
    v.edges = route;
    spec.vehicles = {v};
    demand = build_demand(spec, net, {});
  }
};

TEST(EngineRouteTest, TheCachedLaneEndConnectionFollowsTheRoutePosition) {
  const LoopRoute s;
  const EngineNet engine_net(s.net);
  StepContext ctx{};
  ctx.net = engine_net.view(s.net);
  ctx.types.vclass_mask = s.demand.types.vclass_mask.data();  // the only type column these passes read
  ctx.trips = TripView{s.demand.vehicle_type.data(),
                       s.demand.route_begin.data(),
                       s.demand.route_length.data(),
                       s.demand.route_edges.data(),
                       s.demand.speed_factor.data(),
                       s.demand.arrival_pos_kind.data(),
                       s.demand.arrival_pos.data(),
                       nullptr,
                       nullptr,
                       nullptr,
                       nullptr,
                       nullptr,
                       nullptr};
  // One slot holding vehicle 0, with empty caches (as activate_slot leaves them) and no scheduled stops.
  std::vector<uint32_t> best_rp(kBestLaneEntries, 0xFFFFFFFFu), best_mask(kBestLaneEntries, 0);
  int32_t conn_lane = -1, conn = -1;
  uint32_t conn_rp = 0;
  ctx.veh.best_rp = best_rp.data();
  ctx.veh.best_mask = best_mask.data();
  ctx.veh.conn_lane = &conn_lane;
  ctx.veh.conn_rp = &conn_rp;
  ctx.veh.conn = &conn;
  // Its trip fields, as activate_slot copies them.
  uint32_t type = s.demand.vehicle_type[0], route_begin = s.demand.route_begin[0],
           route_size = s.demand.route_length[0];
  float speed_factor = s.demand.speed_factor[0];
  ctx.veh.trip_type = &type;
  ctx.veh.trip_speed_factor = &speed_factor;
  ctx.veh.trip_route_begin = &route_begin;
  ctx.veh.trip_route_size = &route_size;
  uint32_t next_stop = 0, stops_end = 0;
  ctx.veh.next_stop = &next_stop;
  ctx.veh.stops_end = &stops_end;
  const VehicleRef r{0, 0};
  const int32_t lane = static_cast<int32_t>(s.net.lane_index_by_id.at(test::lane_of(s.route[0], 0)));
  // The same lane at route positions 0 and 4, asked for one after the other (no other lane in between).
  for (const uint32_t rp : {0u, 4u, 0u}) {
    const int32_t c = current_lane_connection(ctx, r, lane, rp);
    ASSERT_GE(c, 0) << "rp " << rp;
    EXPECT_EQ(c, choose_connection(ctx, r, lane, rp)) << "rp " << rp;
    EXPECT_EQ(ctx.net.conn_to_edge[c], s.net.edge_index.at(s.route[rp + 1])) << "rp " << rp;
  }
}

TEST(EngineRouteTest, ALaneVisitedTwiceIsLeftByTheRoutesNextEdgeEachTime) {
  const LoopRoute s;
  const Network& net = s.net;
  const std::vector<std::string>& route = s.route;
  Simulation sim(net, s.demand, SimulationOptions{});
  std::vector<TripRecord> trips;
  for (int k = 0; k < 600 && !sim.finished(); ++k) {
    sim.step();
    for (const TripRecord& t : sim.take_finished_trips()) trips.push_back(t);
  }
  ASSERT_EQ(trips.size(), 1u);
  EXPECT_FALSE(trips[0].teleported);
  EXPECT_EQ(net.lane_id[trips[0].arrival_lane], test::lane_of(route.back(), 0));
  // Six 100 m edges and the five junctions' internal lanes between them (5 m each), from the front's depart
  // position to the arrival at the last edge's end.
  EXPECT_NEAR(trips[0].route_length, 6 * 100.0 + 5 * 5.0 - trips[0].depart_pos, 0.5);
}

}  // namespace
}  // namespace lpsim

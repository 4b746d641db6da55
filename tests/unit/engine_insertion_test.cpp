// Insertion through the whole engine: a queue is inserted from its head until a vehicle does not fit, a
// lane's start takes one vehicle per step, and vehicles with a departure position of their own still go in
// behind those (the host offers a queue's head only as far as it can fit, inserts_at_lane_start).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "demand/demand_builder.hpp"
#include "engine/simulation.hpp"
#include "kernels/step_view.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

VehicleSpec departing(const std::string& id, DepartPos pos, double pos_value = 0) {
  VehicleSpec v;
  v.id = id;
  v.loc = {"test.rou.xml", 1};
  v.edges = {"E0", "E1"};
  v.depart_spec.lane = DepartLane::Free;
  v.depart_spec.pos = pos;
  v.depart_spec.pos_value = pos_value;
  return v;
}

// Queue on a 2-lane edge, all due at 0: base, base, given 50 m, given 80 m, base, given 30 m.
struct QueueOnTwoLanes {
  Network net = build_network(test::make_corridor_spec(2, 100, 2));
  Demand demand;
  QueueOnTwoLanes() {
    DemandSpec spec;
    spec.vehicles = {departing("b0", DepartPos::Base),       departing("b1", DepartPos::Base),
                     departing("g50", DepartPos::Given, 50), departing("g80", DepartPos::Given, 80),
                     departing("b2", DepartPos::Free),       departing("g30", DepartPos::Given, 30)};
    demand = build_demand(spec, net, {});
  }
  uint32_t index(const std::string& id) const {
    for (uint32_t v = 0; v < demand.size(); ++v)
      if (demand.vehicle_id[v] == id) return v;
    ADD_FAILURE() << "no vehicle " << id;
    return 0;
  }
};

TEST(EngineInsertionTest, ALaneStartTakesOneVehiclePerStepAndGivenPositionsGoInBehind) {
  const QueueOnTwoLanes s;
  SimulationOptions opt;
  opt.threads = 1;
  Simulation sim(s.net, s.demand, opt);  // inserts what is due at the begin time
  // One base vehicle per lane at the lane start, then both given positions; the third vehicle at a lane
  // start does not fit, and the queue stops there (g30 behind it waits although its place is free).
  for (const char* id : {"b0", "b1", "g50", "g80"}) EXPECT_EQ(sim.status(s.index(id)), kRunning) << id;
  EXPECT_NE(sim.lane(s.index("b0")), sim.lane(s.index("b1")));
  EXPECT_NEAR(sim.pos(s.index("b0")), 5.1f, 1e-4f);
  EXPECT_NEAR(sim.pos(s.index("g50")), 50.0f, 1e-4f);
  EXPECT_NEAR(sim.pos(s.index("g80")), 80.0f, 1e-4f);
  EXPECT_NE(sim.status(s.index("b2")), kRunning);
  EXPECT_NE(sim.status(s.index("g30")), kRunning);
  EXPECT_EQ(sim.counts().running, 4u);
  EXPECT_EQ(sim.counts().waiting, 2u);
  EXPECT_EQ(sim.check_lane_map(), "");

  // Once the lane starts are clear again, the rest go in, in queue order, and every trip ends.
  while (!sim.finished() && sim.time() < 300) {
    sim.step();
    EXPECT_EQ(sim.check_lane_map(), "") << "t=" << sim.time();
  }
  EXPECT_TRUE(sim.finished());
  EXPECT_EQ(sim.counts().arrived, 6u);
  EXPECT_EQ(sim.counts().inserted, 6u);
}

}  // namespace
}  // namespace lpsim

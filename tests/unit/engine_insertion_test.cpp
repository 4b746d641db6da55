// Insertion through the whole engine: every queued vehicle is tried on the lane its departLane picks (the
// least occupied for free), one that cannot go in does not hold up those behind it, and departPos free finds
// the first wide enough gap from upstream, as SUMO 1.15 does on the same queue.
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

// SUMO 1.15 on the same queue (netconvert corridor, all six departing at 0 with departLane free) inserts all
// six at once: b0 E0_0 5.10, b1 E0_1 5.10, g50 E0_0 50, g80 E0_1 80, b2 E0_0 12.70 (departPos free: the first
// gap from upstream with the secure gaps to both neighbours), g30 E0_1 30. Each vehicle takes the least
// occupied lane, and a vehicle that cannot go in does not hold up those behind it.
TEST(EngineInsertionTest, EveryQueuedVehicleIsTriedOnTheLeastOccupiedLaneAsSumo) {
  const QueueOnTwoLanes s;
  SimulationOptions opt;
  opt.threads = 1;
  Simulation sim(s.net, s.demand, opt);  // inserts what is due at the begin time
  for (const char* id : {"b0", "b1", "g50", "g80", "b2", "g30"})
    EXPECT_EQ(sim.query().status(s.index(id)), kRunning) << id;
  const int32_t lane0 = sim.query().lane(s.index("b0"));
  const int32_t lane1 = sim.query().lane(s.index("b1"));
  EXPECT_NE(lane0, lane1);
  EXPECT_EQ(sim.query().lane(s.index("g50")), lane0);
  EXPECT_EQ(sim.query().lane(s.index("g80")), lane1);
  EXPECT_EQ(sim.query().lane(s.index("b2")), lane0);
  EXPECT_EQ(sim.query().lane(s.index("g30")), lane1);
  EXPECT_NEAR(sim.query().pos(s.index("b0")), 5.1f, 1e-4f);
  EXPECT_NEAR(sim.query().pos(s.index("g50")), 50.0f, 1e-4f);
  EXPECT_NEAR(sim.query().pos(s.index("g80")), 80.0f, 1e-4f);
  EXPECT_NEAR(sim.query().pos(s.index("b2")), 12.7f, 0.5f);  // the follower's front known to the metre
  EXPECT_NEAR(sim.query().pos(s.index("g30")), 30.0f, 1e-4f);
  EXPECT_EQ(sim.counts().running, 6u);
  EXPECT_EQ(sim.counts().waiting, 0u);
  EXPECT_EQ(sim.check_lane_map(), "");

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

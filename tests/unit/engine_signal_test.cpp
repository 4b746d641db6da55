// Signal timing of the whole engine, as SUMO has it: the lights switch at the start of the step that
// produces a time's state, so a vehicle standing at a red line moves in the step that ends when its green
// begins (not one step later).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "demand/demand_builder.hpp"
#include "engine/simulation.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

// make_signal_spec's program: N/S green for the first 30 s, yellow 3 s, then W/E green 30 s, yellow 3 s.
constexpr double kWestGreenStarts = 33.0;

Demand one_vehicle(const Network& net, const std::string& from, const std::string& to) {
  DemandSpec spec;
  VehicleSpec v;
  v.id = "v";
  v.depart = 0;
  v.loc = {"test.rou.xml", 1};
  v.edges = {from, to};
  spec.vehicles = {v};
  return build_demand(spec, net, {});
}

void step_to(Simulation& sim, double t) {
  while (sim.time() < t - 1e-9) sim.step();
}

TEST(EngineSignalTest, StandingVehicleMovesInTheStepEndingAtItsGreen) {
  for (const double dt : {1.0, 0.5}) {
    const Network net = build_network(test::make_signal_spec());
    const Demand demand = one_vehicle(net, "WtoC", "CtoE");
    SimulationOptions o;
    o.step_ms = std::llround(dt * 1000.0);
    Simulation sim(net, demand, o);
    // 100 m at up to 13.9 m/s: at the line, standing, well before the green.
    step_to(sim, kWestGreenStarts - dt);
    const int32_t waiting_lane = sim.query().lane(0);
    ASSERT_EQ(sim.query().status(0), kRunning);
    EXPECT_EQ(sim.query().speed(0), 0.0f) << "dt " << dt;
    EXPECT_GT(sim.query().pos(0), 95.0f) << "dt " << dt;
    const float waiting_pos = sim.query().pos(0);
    sim.step();  // ends at the green's start
    EXPECT_DOUBLE_EQ(sim.time(), kWestGreenStarts);
    EXPECT_GT(sim.query().speed(0), 0.0f) << "dt " << dt;
    EXPECT_TRUE(sim.query().lane(0) != waiting_lane || sim.query().pos(0) > waiting_pos) << "dt " << dt;
  }
}

}  // namespace
}  // namespace lpsim

// Strategic lane choice where no lane of an edge leads onto a best lane of the next one (a motorway entry
// that widens by an on-ramp's lane, which alone leads to the off-ramp after it): the lanes leading nearest
// to the next edge's best lane are this edge's best lanes, as SUMO ranks them (by continuation, then by the
// connection's offset to the next best lane), so that exiting vehicles move over before the weaving
// section. Every lane counted as best instead let them arrive there on the far lanes and stand at its end.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/vclass.hpp"
#include "engine/engine_net.hpp"
#include "kernels/vehicle_step.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

// K0 -E0 (3 lanes)-> K1 -E1 (4 lanes)-> K2 -E2 (1 lane)-> K3, E0 lane k onto E1 lane k + 1 (lane 0 of E1
// is the ramp's), and only E1's lane 0 onto E2. `shift` 0 connects E0 lane k onto E1 lane k instead.
Network weaving_net(int shift) {
  NetSpec s;
  s.source = "weaving.net.xml";
  for (int k = 0; k <= 3; ++k) {
    JunctionSpec j;
    j.id = "K" + std::to_string(k);
    j.type = (k == 0 || k == 3) ? "dead_end" : "priority";
    j.x = k * 300.0;
    j.loc = {s.source, k + 1};
    s.junctions.push_back(j);
  }
  test::add_edge(s, "E0", s.junctions[0], s.junctions[1], 3, 36.11);
  test::add_edge(s, "E1", s.junctions[1], s.junctions[2], 4, 36.11);
  test::add_edge(s, "E2", s.junctions[2], s.junctions[3], 1, 22.22);
  auto connect = [&](const std::string& from, int from_lane, const std::string& to, int to_lane) {
    ConnectionSpec c;
    c.from = from;
    c.to = to;
    c.from_lane = from_lane;
    c.to_lane = to_lane;
    s.connections.push_back(c);
  };
  for (int k = 0; k < 3; ++k) connect("E0", k, "E1", k + shift);
  connect("E1", 0, "E2", 0);
  for (auto& j : s.junctions)
    for (const auto& e : s.edges)
      if (e.to == j.id)
        for (const auto& l : e.lanes) j.inc_lanes.push_back(l.id);
  return build_network(s);
}

uint32_t best_mask_of_first_edge(int shift) {
  const Network net = weaving_net(shift);
  const EngineNet engine_net(net);
  const NetView view = engine_net.view(net);
  const std::vector<uint32_t> route = {net.edge_index.at("E0"), net.edge_index.at("E1"),
                                       net.edge_index.at("E2")};
  const BestLanes b = best_lanes(view, route.data(), 3, 0, kVClassPassenger);
  EXPECT_EQ(b.mask[1], 1u) << "on E1 only lane 0 leads to E2";
  return b.mask[0];
}

TEST(EngineBestLanesTest, WithoutALaneOntoTheNextBestLaneTheNearestLanesAreBest) {
  EXPECT_EQ(best_mask_of_first_edge(1), 1u) << "E0's lane 0 leads one change away from E1's lane 0";
}

TEST(EngineBestLanesTest, LanesOntoTheNextBestLaneAreBest) {
  EXPECT_EQ(best_mask_of_first_edge(0), 1u) << "E0's lane 0 leads onto E1's lane 0";
}

}  // namespace
}  // namespace lpsim

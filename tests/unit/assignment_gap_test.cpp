// The relative gap of an assignment (app/assignment.hpp), checked by hand on a grid with one jammed edge.
#include <gtest/gtest.h>

#include "app/assignment.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

using test::grid_edge;

TEST(AssignmentGap, RouteThroughAJamAgainstTheWayAround) {
  NetSpec s = test::make_grid_spec(4, 4);
  for (auto& e : s.edges)
    for (auto& l : e.lanes) l.speed = 10;
  const Network net = build_network(s);
  const Router router(net);
  auto edge = [&](int c0, int r0, int c1, int r1) { return net.edge_index.at(grid_edge(c0, r0, c1, r1)); };
  // Two vehicles from (0,0)->(1,0) to (3,1)->(3,2): one along row 0, through the edge (2,0)->(3,0) that
  // takes 500 s instead of 10 s, the other north first, along row 1 (five free-flow edges as well).
  const std::vector<uint32_t> jammed{edge(0, 0, 1, 0), edge(1, 0, 2, 0), edge(2, 0, 3, 0), edge(3, 0, 3, 1),
                                     edge(3, 1, 3, 2)};
  const std::vector<uint32_t> around{edge(0, 0, 1, 0), edge(1, 0, 1, 1), edge(1, 1, 2, 1), edge(2, 1, 3, 1),
                                     edge(3, 1, 3, 2)};
  Demand d;
  d.types.vclass_mask = {kAllVClasses};
  for (int v = 0; v < 2; ++v) {
    d.vehicle_id.push_back("v" + std::to_string(v));
    d.vehicle_type.push_back(0);
    d.depart.push_back(0);
    const auto& route = v == 0 ? jammed : around;
    d.route_begin.push_back(static_cast<uint32_t>(d.route_edges.size()));
    d.route_length.push_back(static_cast<uint32_t>(route.size()));
    d.route_edges.insert(d.route_edges.end(), route.begin(), route.end());
  }
  IntervalTravelTimes times;
  times.period = 3600;
  times.resize(net.num_edges(), 1);
  times.time[edge(2, 0, 3, 0)] = 500;
  const double free_cost = router.cost(around);  // both vehicles' best
  const GapSums g = relative_gap(net, router, d, times, 1);
  EXPECT_EQ(g.vehicles, 2u);
  EXPECT_NEAR(g.best_cost_sum, 2 * free_cost, 1e-9);
  EXPECT_NEAR(g.route_cost_sum, 2 * free_cost + 490, 1e-9);
  EXPECT_NEAR(g.relative_gap(), 490 / (2 * free_cost), 1e-12);

  // Best routes from an approximate search (the hierarchy on one interval's times) may cost more than the
  // route driven: the driven one is then the best known, and the vehicle adds nothing to the gap.
  const std::vector<double> approximate{free_cost + 20, free_cost + 30};
  const GapSums a = gap_sums(router, d, times, approximate);
  EXPECT_NEAR(a.best_cost_sum, 2 * free_cost + 20, 1e-9);  // v0: its best's cost; v1: its own route's
  EXPECT_NEAR(a.route_cost_sum, 2 * free_cost + 490, 1e-9);
  EXPECT_GE(a.relative_gap(), 0.0);
}

}  // namespace
}  // namespace lpsim

// Time-dependent routing on interval travel times (Router::route_timed), as duarouter routes on the
// weights of an iteration's edgeData.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "net/network_builder.hpp"
#include "net/router.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

using test::grid_edge;
using Path = std::vector<uint32_t>;

// 4x4 grid at 10 m/s, 100 m edges: every edge 10 s at free flow.
Network slow_grid() {
  NetSpec s = test::make_grid_spec(4, 4);
  for (auto& e : s.edges)
    for (auto& l : e.lanes) l.speed = 10;
  return build_network(s);
}

uint32_t edge(const Network& net, int c0, int r0, int c1, int r1) {
  return net.edge_index.at(grid_edge(c0, r0, c1, r1));
}

TEST(RouterTimed, WithoutMeasuredTimesEqualsFreeFlowRouting) {
  Network net = slow_grid();
  Router router(net);
  IntervalTravelTimes times;
  times.resize(net.num_edges(), 1);  // all NaN: free flow
  std::mt19937 rng(7);
  std::vector<uint32_t> normal;
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (!net.edge_is_internal[e]) normal.push_back(e);
  std::vector<RouteRequest> reqs;
  std::vector<double> depart;
  for (int k = 0; k < 200; ++k) {
    reqs.push_back({{normal[rng() % normal.size()]}, {normal[rng() % normal.size()]}, {}});
    depart.push_back(rng() % 3600);
  }
  std::vector<double> costs;
  auto timed = router.route_timed(reqs, depart, times, 2, &costs);
  auto plain = router.route_all(reqs, 1);
  for (size_t k = 0; k < reqs.size(); ++k) {
    ASSERT_EQ(timed[k].empty(), plain[k].empty());
    if (plain[k].empty()) continue;
    EXPECT_NEAR(costs[k], router.cost(plain[k]), 1e-9) << k;
    EXPECT_NEAR(router.timed_cost(timed[k], depart[k], times), costs[k], 1e-9) << k;
  }
}

TEST(RouterTimed, AnEdgeCostsItsTimeInTheIntervalItIsEnteredIn) {
  Network net = slow_grid();
  Router router(net);
  // From (0,0)->(1,0) to (3,1)->(3,2): along row 0 then north, or north first then along row 1, both five
  // edges. Edge (2,0)->(3,0) of the first is slow only in the second interval, [100, 200).
  IntervalTravelTimes times;
  times.begin = 0;
  times.period = 100;
  times.resize(net.num_edges(), 2);
  const uint32_t jam = edge(net, 2, 0, 3, 0);
  times.time[size_t(1) * net.num_edges() + jam] = 500;
  const Path through_jam{edge(net, 0, 0, 1, 0), edge(net, 1, 0, 2, 0), jam, edge(net, 3, 0, 3, 1),
                         edge(net, 3, 1, 3, 2)};
  const double free_cost = router.cost(through_jam);
  // Entered at about 20 s (first interval) the edge costs its free-flow time; at 110 s or later, 500 s.
  EXPECT_NEAR(router.timed_cost(through_jam, 0.0, times), free_cost, 1e-9);
  EXPECT_NEAR(router.timed_cost(through_jam, 90.0, times), free_cost - 10 + 500, 1e-9);
  // After the last interval its times go on (duarouter's --weights.expand), before the first the first's.
  EXPECT_NEAR(router.timed_cost(through_jam, 5000.0, times), free_cost - 10 + 500, 1e-9);
  EXPECT_NEAR(router.timed_cost(through_jam, -500.0, times), free_cost, 1e-9);

  RouteRequest r{{through_jam.front()}, {through_jam.back()}, {}};
  std::vector<double> costs;
  auto early = router.route_timed({r}, {0.0}, times, 1, &costs);
  EXPECT_NEAR(costs[0], free_cost, 1e-9);
  // Departing at 90 s the route avoids the jammed edge, at the free-flow cost of the other way.
  auto late = router.route_timed({r}, {90.0}, times, 1, &costs);
  ASSERT_FALSE(late[0].empty());
  EXPECT_EQ(std::find(late[0].begin(), late[0].end(), jam), late[0].end());
  EXPECT_NEAR(costs[0], free_cost, 1e-9);
  EXPECT_NEAR(router.timed_cost(late[0], 90.0, times), costs[0], 1e-9);
}

TEST(RouterTimed, ViaEdgesInOrderAndTheSamePathsOnAnyThreadCount) {
  Network net = slow_grid();
  Router router(net);
  IntervalTravelTimes times;
  times.period = 60;
  times.resize(net.num_edges(), 5);
  std::mt19937 rng(3);
  for (float& t : times.time)
    if (rng() % 3 == 0) t = 5 + rng() % 40;
  RouteRequest r{{edge(net, 0, 0, 1, 0)}, {edge(net, 3, 2, 3, 3)}, {edge(net, 1, 2, 2, 2)}};
  std::vector<double> c1, c2;
  auto one = router.route_timed({r, r, r}, {0, 100, 200}, times, 1, &c1);
  auto two = router.route_timed({r, r, r}, {0, 100, 200}, times, 2, &c2);
  EXPECT_EQ(one, two);
  EXPECT_EQ(c1, c2);
  for (size_t k = 0; k < 3; ++k) {
    ASSERT_FALSE(one[k].empty());
    EXPECT_NE(std::find(one[k].begin(), one[k].end(), edge(net, 1, 2, 2, 2)), one[k].end());
    for (size_t i = 1; i < one[k].size(); ++i) EXPECT_TRUE(net.connected(one[k][i - 1], one[k][i]));
    EXPECT_NEAR(router.timed_cost(one[k], k * 100.0, times), c1[k], 1e-9);
  }
}

}  // namespace
}  // namespace lpsim

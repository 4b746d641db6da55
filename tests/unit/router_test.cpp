#include "net/router.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

using test::grid_edge;
using Path = std::vector<uint32_t>;

void set_speed(NetSpec& s, const std::string& edge, double speed) {
  for (auto& e : s.edges)
    if (e.id == edge)
      for (auto& l : e.lanes) l.speed = speed;
}

Path ids_to_path(const Network& net, const std::vector<std::string>& ids) {
  Path p;
  for (const auto& id : ids) p.push_back(net.edge_index.at(id));
  return p;
}

bool is_connected_path(const Network& net, const Path& p) {
  for (size_t i = 1; i < p.size(); ++i)
    if (!net.connected(p[i - 1], p[i])) return false;
  return true;
}

// 4x4 grid, all edges 10 m/s except a fast row 0 eastwards and a fast column 3 northwards (30 m/s).
NetSpec fast_l_grid() {
  NetSpec s = test::make_grid_spec(4, 4);
  for (auto& e : s.edges)
    for (auto& l : e.lanes) l.speed = 10;
  for (int c = 0; c < 3; ++c) set_speed(s, grid_edge(c, 0, c + 1, 0), 30);
  for (int r = 0; r < 3; ++r) set_speed(s, grid_edge(3, r, 3, r + 1), 30);
  return s;
}

TEST(Router, KnownPathOnGrid) {
  Network net = build_network(fast_l_grid());
  Router router(net);
  RouteRequest r{{net.edge_index.at(grid_edge(0, 0, 1, 0))}, {net.edge_index.at(grid_edge(3, 2, 3, 3))}, {}};
  auto out = router.route_all({r}, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], ids_to_path(net, {grid_edge(0, 0, 1, 0), grid_edge(1, 0, 2, 0), grid_edge(2, 0, 3, 0),
                                      grid_edge(3, 0, 3, 1), grid_edge(3, 1, 3, 2), grid_edge(3, 2, 3, 3)}));
  // Cost counts the first and the last edge: 6 edges of 100 m at 30 m/s.
  EXPECT_NEAR(router.cost(out[0]), 6 * 100.0 / 30.0, 1e-4);
}

TEST(Router, CorridorAndTrivialPaths) {
  Network net = build_network(test::make_corridor_spec(5, 50, 2));
  Router router(net);
  const uint32_t e0 = net.edge_index.at("E0"), e4 = net.edge_index.at("E4"), e2 = net.edge_index.at("E2");
  auto out = router.route_all({{{e0}, {e4}, {}}, {{e2}, {e2}, {}}, {{e4}, {e0}, {}}, {{e0}, {}, {}}}, 1);
  EXPECT_EQ(out[0], ids_to_path(net, {"E0", "E1", "E2", "E3", "E4"}));
  EXPECT_EQ(out[1], Path{e2});  // origin is the destination: the edge alone
  EXPECT_TRUE(out[2].empty());  // one-way corridor: unreachable
  EXPECT_TRUE(out[3].empty());  // no destination
  EXPECT_NEAR(router.cost(out[0]), 5 * 50 / 13.89, 1e-3);
}

TEST(Router, ForbiddenTurnForcesDetour) {
  NetSpec s = fast_l_grid();
  test::remove_connection(s, grid_edge(2, 0, 3, 0), grid_edge(3, 0, 3, 1));
  Network net = build_network(s);
  ASSERT_FALSE(
      net.connected(net.edge_index.at(grid_edge(2, 0, 3, 0)), net.edge_index.at(grid_edge(3, 0, 3, 1))));
  Router router(net);
  const uint32_t from = net.edge_index.at(grid_edge(0, 0, 1, 0)),
                 to = net.edge_index.at(grid_edge(3, 2, 3, 3));
  Path p = router.route_all({{{from}, {to}, {}}}, 1)[0];
  ASSERT_FALSE(p.empty());
  EXPECT_TRUE(is_connected_path(net, p));
  EXPECT_EQ(p.front(), from);
  EXPECT_EQ(p.back(), to);
  // Best detour: fast row to J2_0, up one block at 10 m/s, right at 10 m/s, then the fast column.
  EXPECT_EQ(p, ids_to_path(net, {grid_edge(0, 0, 1, 0), grid_edge(1, 0, 2, 0), grid_edge(2, 0, 2, 1),
                                 grid_edge(2, 1, 3, 1), grid_edge(3, 1, 3, 2), grid_edge(3, 2, 3, 3)}));
  EXPECT_NEAR(router.cost(p), 4 * 100.0 / 30.0 + 2 * 100.0 / 10.0, 1e-4);
}

TEST(Router, ViaEdgesInOrder) {
  Network net = build_network(fast_l_grid());
  Router router(net);
  const uint32_t from = net.edge_index.at(grid_edge(0, 0, 1, 0)),
                 to = net.edge_index.at(grid_edge(3, 2, 3, 3));
  const uint32_t via1 = net.edge_index.at(grid_edge(1, 1, 1, 2)),
                 via2 = net.edge_index.at(grid_edge(1, 2, 2, 2));
  auto out = router.route_all({{{from}, {to}, {via1, via2}}, {{from}, {via1}, {}}, {{via2}, {to}, {}}}, 1);
  const Path& p = out[0];
  ASSERT_FALSE(p.empty());
  EXPECT_TRUE(is_connected_path(net, p));
  // The via route is the leg to via1, via1 -> via2 (adjacent), then the leg from via2.
  Path expect = out[1];
  expect.insert(expect.end(), out[2].begin(), out[2].end());
  EXPECT_EQ(p, expect);
  // A via edge that cannot be reached (against the one-way corridor) gives no path.
  Network corridor = build_network(test::make_corridor_spec(3));
  Router rc(corridor);
  EXPECT_TRUE(rc.route_all({{{1}, {2}, {0}}}, 1)[0].empty());
}

TEST(Router, MultiOriginMultiDestination) {
  Network net = build_network(fast_l_grid());
  Router router(net);
  const uint32_t far = net.edge_index.at(grid_edge(0, 3, 0, 2)),
                 near = net.edge_index.at(grid_edge(2, 2, 3, 2));
  const uint32_t d1 = net.edge_index.at(grid_edge(3, 2, 3, 3)), d2 = net.edge_index.at(grid_edge(0, 1, 0, 0));
  auto out = router.route_all({{{far, near}, {d1}, {}}, {{near}, {d1, d2}, {}}}, 1);
  EXPECT_EQ(out[0], ids_to_path(net, {grid_edge(2, 2, 3, 2), grid_edge(3, 2, 3, 3)}));
  EXPECT_EQ(out[1].back(), d1);  // the nearer of the two destinations
  EXPECT_EQ(out[1].size(), 2u);
}

TEST(Router, GroupedRequestsMatchSingleRequestsAndThreadCount) {
  NetSpec s = test::make_grid_spec(8, 8);
  std::mt19937 rng(7);
  for (auto& e : s.edges) {
    const double v = std::uniform_real_distribution<double>(5, 30)(rng);
    for (auto& l : e.lanes) l.speed = v;
  }
  Network net = build_network(s);
  Router router(net);
  std::uniform_int_distribution<uint32_t> pick(0, net.num_edges() - 1);
  std::vector<RouteRequest> reqs;
  for (int i = 0; i < 300; ++i) {
    RouteRequest r;
    r.origins = {i % 10 == 0 ? pick(rng) : static_cast<uint32_t>(i % 7)};  // many share origins 0..6
    r.destinations = {pick(rng)};
    if (i % 5 == 0) r.destinations.push_back(pick(rng));
    if (i % 11 == 0) r.via = {pick(rng)};
    if (i % 13 == 0) r.origins.push_back(pick(rng));
    reqs.push_back(r);
  }
  auto one = router.route_all(reqs, 1);
  auto four = router.route_all(reqs, 4);
  EXPECT_EQ(one, four);
  for (size_t i = 0; i < reqs.size(); i += 7) EXPECT_EQ(router.route_all({reqs[i]}, 1)[0], one[i]) << i;
  size_t found = 0;
  for (const auto& p : one) found += p.empty() ? 0 : 1;
  EXPECT_EQ(found, reqs.size());  // a grid without U-turns is still strongly connected
}

TEST(Router, InternalEdgesNeverInRoutes) {
  test::GridOptions o;
  o.with_internal = true;
  Network net = build_network(test::make_grid_spec(3, 3, o));
  Router router(net);
  const uint32_t from = net.edge_index.at(grid_edge(0, 0, 1, 0)),
                 to = net.edge_index.at(grid_edge(2, 1, 2, 2));
  Path p = router.route_all({{{from}, {to}, {}}, {{net.edge_index.at(":J1_1_0")}, {to}, {}}}, 2)[0];
  ASSERT_EQ(p.size(), 4u);
  for (uint32_t e : p) EXPECT_FALSE(net.edge_is_internal[e]);
  EXPECT_TRUE(is_connected_path(net, p));
}

// Two four-edge paths of equal length on a grid with 5 m internal lanes, over junction (2,0) or over (1,1):
// a link without priority on one of them (SUMO's minor-link penalty) sends the route over the other, either
// way round; the path's cost counts its three crossings.
TEST(Router, CrossingsCostTheirInternalLanesAndMinorLinksAPenalty) {
  const std::string from = grid_edge(0, 0, 1, 0), to = grid_edge(2, 1, 2, 2);
  const std::vector<std::string> over_20 = {from, grid_edge(1, 0, 2, 0), grid_edge(2, 0, 2, 1), to};
  const std::vector<std::string> over_11 = {from, grid_edge(1, 0, 1, 1), grid_edge(1, 1, 2, 1), to};
  for (int minor_on_20 = 0; minor_on_20 < 2; ++minor_on_20) {
    test::GridOptions o;
    o.with_internal = true;
    o.internal_length = 5;
    NetSpec s = test::make_grid_spec(3, 3, o);
    const auto& slowed = minor_on_20 ? over_20 : over_11;
    for (auto& c : s.connections)
      if (c.from == slowed[1] && c.to == slowed[2]) c.state = 'm';
    Network net = build_network(s);
    Router router(net);
    const Path p = router.route_all({{{net.edge_index.at(from)}, {net.edge_index.at(to)}, {}}}, 1)[0];
    EXPECT_EQ(p, ids_to_path(net, minor_on_20 ? over_11 : over_20)) << minor_on_20;
    EXPECT_NEAR(router.cost(p), 4 * 100 / 13.89 + 3 * 5 / 13.89, 1e-4);
    const uint32_t a = net.edge_index.at(slowed[1]), b = net.edge_index.at(slowed[2]);
    int found = 0;
    for (uint32_t i = net.edge_succ_begin[a]; i < net.edge_succ_begin[a + 1]; ++i) {
      if (net.edge_succ[i] != b) continue;
      EXPECT_NEAR(router.step_cost(i), (100 + 5) / 13.89 + kMinorLinkPenalty, 1e-4);
      ++found;
    }
    EXPECT_EQ(found, 1);
  }
}

// SUMO's --weights.minor-penalty sets the penalty: a route's cost grows by it for each minor crossing.
TEST(Router, MinorPenaltyIsAParameter) {
  test::GridOptions o;
  o.with_internal = true;
  o.internal_length = 5;
  NetSpec s = test::make_grid_spec(3, 3, o);
  const std::string a = grid_edge(0, 0, 1, 0), b = grid_edge(1, 0, 2, 0);
  for (auto& c : s.connections)
    if (c.from == a && c.to == b) c.state = 'm';
  Network net = build_network(s);
  const Path p = ids_to_path(net, {a, b});
  for (double penalty : {0.0, 1.5, 7.0})
    EXPECT_NEAR(Router(net, penalty).cost(p), (2 * 100 + 5) / 13.89 + penalty, 1e-4) << penalty;
}

// Random strongly-or-not connected nets: the router's cost equals the Bellman-Ford optimum on edge_succ
// (with the router's step costs; crossing costs are tested on their own below).
TEST(Router, MatchesBellmanFordOnRandomGraphs) {
  std::mt19937 rng(12345);
  size_t reachable = 0, unreachable = 0;
  for (int round = 0; round < 20; ++round) {
    NetSpec s;
    s.source = "random.net.xml";
    const int nj = 6 + round % 5;
    for (int j = 0; j < nj; ++j) {
      JunctionSpec js;
      js.id = "n" + std::to_string(j);
      js.type = "priority";
      js.x = std::uniform_real_distribution<double>(0, 500)(rng);
      js.y = std::uniform_real_distribution<double>(0, 500)(rng);
      s.junctions.push_back(js);
    }
    const int ne = nj * 2 + round % 7;
    for (int k = 0; k < ne; ++k) {
      int a = std::uniform_int_distribution<int>(0, nj - 1)(rng),
          b = std::uniform_int_distribution<int>(0, nj - 2)(rng);
      if (b >= a) ++b;
      EdgeSpec& e = test::add_edge(s, "e" + std::to_string(k), s.junctions[a], s.junctions[b], 1,
                                   std::uniform_real_distribution<double>(3, 30)(rng));
      e.lanes[0].length = std::uniform_int_distribution<int>(1, 40)(rng) * 10.0;  // many equal costs
    }
    test::connect_all(s, round % 2 == 1, 5, /*allow_uturn=*/true);
    std::erase_if(s.connections, [&](const ConnectionSpec& c) {  // forbid ~30% of turns
      return c.from[0] != ':' && std::uniform_int_distribution<int>(0, 9)(rng) < 3;
    });
    Network net = build_network(s);
    Router router(net);
    std::vector<float> cost(net.num_edges());
    for (uint32_t e = 0; e < net.num_edges(); ++e) cost[e] = net.edge_length[e] / net.edge_speed[e];
    for (uint32_t i = 0; i < net.edge_succ.size(); ++i)  // a step costs at least its edge
      ASSERT_GE(router.step_cost(i), cost[net.edge_succ[i]] * (1 - 1e-6));

    std::vector<RouteRequest> reqs;
    std::vector<uint32_t> normal;
    for (uint32_t e = 0; e < net.num_edges(); ++e)
      if (!net.edge_is_internal[e]) normal.push_back(e);
    for (uint32_t a : normal)
      for (uint32_t b : normal) reqs.push_back({{a}, {b}, {}});
    auto out = router.route_all(reqs, 2);

    for (uint32_t a : normal) {
      // Bellman-Ford from a: dist includes the cost of a and of the destination edge.
      std::vector<double> dist(net.num_edges(), std::numeric_limits<double>::infinity());
      dist[a] = cost[a];
      for (uint32_t it = 0; it < net.num_edges(); ++it)
        for (uint32_t e = 0; e < net.num_edges(); ++e)
          for (uint32_t i = net.edge_succ_begin[e]; i < net.edge_succ_begin[e + 1]; ++i)
            dist[net.edge_succ[i]] = std::min(dist[net.edge_succ[i]], dist[e] + router.step_cost(i));
      for (size_t q = 0; q < reqs.size(); ++q) {
        if (reqs[q].origins[0] != a) continue;
        const uint32_t b = reqs[q].destinations[0];
        const Path& p = out[q];
        if (std::isinf(dist[b])) {
          EXPECT_TRUE(p.empty()) << "round " << round << " " << net.edge_id[a] << "->" << net.edge_id[b];
          ++unreachable;
          continue;
        }
        ASSERT_FALSE(p.empty()) << "round " << round << " " << net.edge_id[a] << "->" << net.edge_id[b];
        EXPECT_EQ(p.front(), a);
        EXPECT_EQ(p.back(), b);
        EXPECT_TRUE(is_connected_path(net, p));
        EXPECT_NEAR(router.cost(p), dist[b], 1e-6 * dist[b]);
        ++reachable;
      }
    }
  }
  // The sample must exercise both outcomes and real detours, not only neighbours.
  EXPECT_GT(reachable, 2000u);
  EXPECT_GT(unreachable, 200u);
}

}  // namespace
}  // namespace lpsim

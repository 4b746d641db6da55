// The customizable contraction hierarchy against the Dijkstra router it must equal: on every bundled SUMO
// network and a synthetic grid, for all classes and for classes some lanes exclude, every sampled query has a
// path exactly when Dijkstra finds one, a connected path from the origin to the destination, and Dijkstra's
// path cost. A metric customized for new costs answers with those costs.
#include "net/cch_router.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "converters/cli_options.hpp"
#include "converters/net_reader.hpp"
#include "core/error.hpp"
#include "core/vclass.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

const std::string kScenarios = LPSIM_SCENARIOS_DIR;

// Equal costs summed in another order differ in the last bits only.
bool same_cost(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max(1.0, std::fabs(a)); }

// Checks `queries` random origin-destination pairs (every pair when the network has few edges) for `vclass`;
// returns how many had a path.
int expect_dijkstra_costs(const Network& net, const Router& router, const CchRouter& cch, uint32_t vclass,
                          int queries, const std::string& what) {
  const CchRouter::Metric metric = cch.customize(router, vclass);
  CchRouter::Workspace ws(cch);
  const uint32_t n = net.num_edges();
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  if (static_cast<uint64_t>(n) * n <= static_cast<uint64_t>(queries)) {
    for (uint32_t o = 0; o < n; ++o)
      for (uint32_t d = 0; d < n; ++d) pairs.emplace_back(o, d);
  } else {
    std::mt19937 rng(12345);
    std::uniform_int_distribution<uint32_t> pick(0, n - 1);
    for (int q = 0; q < queries; ++q) pairs.emplace_back(pick(rng), pick(rng));
  }
  std::vector<RouteRequest> requests;
  for (const auto& [o, d] : pairs) {
    RouteRequest r;
    r.origins = {o};
    r.destinations = {d};
    r.vclass = vclass;
    requests.push_back(r);
  }
  const std::vector<std::vector<uint32_t>> reference = router.route_all(requests, 1);
  int found = 0, failures = 0;
  for (size_t q = 0; q < pairs.size() && failures < 5; ++q) {
    const auto [o, d] = pairs[q];
    double cost = 0;
    const std::vector<uint32_t> path = cch.route(metric, o, d, ws, &cost);
    const std::string at = what + ": " + net.edge_id[o] + " -> " + net.edge_id[d];
    if (path.empty() != reference[q].empty()) {
      ADD_FAILURE() << at << ": CCH " << (path.empty() ? "finds no path" : "finds a path") << ", Dijkstra "
                    << (reference[q].empty() ? "none" : "one");
      ++failures;
      continue;
    }
    if (path.empty()) continue;
    ++found;
    bool ok = path.front() == o && path.back() == d;
    for (size_t k = 1; k < path.size() && ok; ++k) ok = net.connected(path[k - 1], path[k]);
    const double expected = router.cost(reference[q]);
    ok = ok && same_cost(router.cost(path), expected) && same_cost(cost, expected);
    if (!ok) {
      ADD_FAILURE() << at << ": CCH cost " << cost << " (path " << router.cost(path) << ", " << path.size()
                    << " edges), Dijkstra " << expected << " (" << reference[q].size() << " edges)";
      ++failures;
    }
  }
  return found;
}

class CchBundledNetTest : public ::testing::TestWithParam<std::string> {};

TEST_P(CchBundledNetTest, PathCostsEqualDijkstras) {
  const Network net =
      build_network(read_sumo_net(kScenarios + "/" + GetParam() + "/" + GetParam() + ".net.xml"));
  const Router router(net);
  const CchRouter cch(net);
  EXPECT_EQ(cch.num_nodes(), net.num_edges());
  EXPECT_GT(expect_dijkstra_costs(net, router, cch, kAllVClasses, 4000, GetParam()), 0);
  expect_dijkstra_costs(net, router, cch, kVClassPassenger, 4000, GetParam() + " passenger");
  expect_dijkstra_costs(net, router, cch, vclass_name_bit("bus"), 4000, GetParam() + " bus");
  expect_dijkstra_costs(net, router, cch, vclass_name_bit("truck"), 4000, GetParam() + " truck");
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CchBundledNetTest,
                         ::testing::Values("grid_tls", "random_net", "motorway_ramps", "city_mixed", "flows",
                                           "cosim_line", "actuated_cross", "keep_clear"));

// A bigger synthetic grid, its edges' speeds spread so that paths differ from the fewest turns; then one
// metric customized from other costs (a faster column) answers with those.
TEST(CchRouterTest, GridQueriesAndACustomizedMetricMatchDijkstra) {
  NetSpec spec = test::make_grid_spec(12, 12);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> speed(5.0, 30.0);
  for (auto& e : spec.edges)
    for (auto& l : e.lanes) l.speed = speed(rng);
  const Network net = build_network(spec);
  const CchRouter cch(net);
  EXPECT_GT(cch.num_arcs(), 0u);
  EXPECT_LT(cch.elimination_tree_height(), net.num_edges());
  const Router router(net);
  EXPECT_GT(expect_dijkstra_costs(net, router, cch, kAllVClasses, 5000, "grid"), 4000);
  const Router slower(net, 20.0);  // another metric: a minor link costs 20 s
  EXPECT_GT(expect_dijkstra_costs(net, slower, cch, kAllVClasses, 5000, "grid, minor penalty 20 s"), 4000);
}

// An edge buses may not use: no path from it, none through it (buses go around), and a bad edge index is an
// error.
TEST(CchRouterTest, EdgesAClassMayNotUseAreNeitherOriginsNorOnItsPaths) {
  NetSpec spec = test::make_grid_spec(3, 3);
  const std::string closed = test::grid_edge(0, 0, 1, 0);
  for (auto& e : spec.edges)
    if (e.id == closed)
      for (auto& l : e.lanes) l.permissions = kVClassPassenger;
  const Network net = build_network(spec);
  const Router router(net);
  const CchRouter cch(net);
  const CchRouter::Metric buses = cch.customize(router, vclass_name_bit("bus"));
  CchRouter::Workspace ws(cch);
  const uint32_t from = net.edge_index.at(closed), to = net.edge_index.at(test::grid_edge(1, 0, 2, 0));
  double cost = 0;
  EXPECT_TRUE(cch.route(buses, from, to, ws, &cost).empty());
  EXPECT_TRUE(std::isinf(cost));
  const CchRouter::Metric all = cch.customize(router);
  int through = 0;
  for (uint32_t o = 0; o < net.num_edges(); ++o)
    for (uint32_t d = 0; d < net.num_edges(); ++d) {
      if (o == from || d == from) continue;
      const std::vector<uint32_t> bus = cch.route(buses, o, d, ws);
      EXPECT_EQ(std::count(bus.begin(), bus.end(), from), 0);
      const std::vector<uint32_t> any = cch.route(all, o, d, ws);
      through += std::count(any.begin(), any.end(), from) > 0 ? 1 : 0;
    }
  EXPECT_GT(through, 0) << "no path of all classes uses the edge: no test";
  EXPECT_GT(expect_dijkstra_costs(net, router, cch, vclass_name_bit("bus"), 10000, "grid, bus"), 0);
  EXPECT_THROW(cch.route(buses, net.num_edges(), to, ws), std::out_of_range);
}

// route_all: requests with via edges answered leg by leg, those with several origins or destinations by the
// Dijkstra router; the same paths on one thread and two, at Dijkstra's costs.
TEST(CchRouterTest, RouteAllAnswersViaAndSeveralOriginsAtDijkstrasCosts) {
  const Network net = build_network(test::make_grid_spec(6, 6));
  const Router router(net);
  const CchRouter cch(net);
  std::mt19937 rng(3);
  std::uniform_int_distribution<uint32_t> pick(0, net.num_edges() - 1);
  std::vector<RouteRequest> requests(600);
  for (size_t i = 0; i < requests.size(); ++i) {
    RouteRequest& r = requests[i];
    r.origins = {pick(rng)};
    r.destinations = {pick(rng)};
    if (i % 3 == 1) r.via = {pick(rng), pick(rng)};
    if (i % 3 == 2) r.origins.push_back(pick(rng));
  }
  const auto one = cch.route_all(router, requests, 1);
  const auto two = cch.route_all(router, requests, 2);
  const auto reference = router.route_all(requests, 1);
  EXPECT_EQ(one, two);
  int found = 0;
  for (size_t i = 0; i < requests.size(); ++i) {
    ASSERT_EQ(one[i].empty(), reference[i].empty()) << i;
    if (one[i].empty()) continue;
    ++found;
    EXPECT_TRUE(same_cost(router.cost(one[i]), router.cost(reference[i]))) << i;
    for (const uint32_t v : requests[i].via)
      EXPECT_NE(std::find(one[i].begin(), one[i].end(), v), one[i].end());
  }
  EXPECT_GT(found, 500);
}

// SUMO's --routing-algorithm CH: random_net's 300 trips are routed by the hierarchy, each at the cost the
// Dijkstra router's route has; other names SUMO knows load too, an unknown one is refused.
TEST(CchRouterTest, TripsRoutedWithRoutingAlgorithmChCostWhatDijkstrasRoutesCost) {
  const std::string cfg = kScenarios + "/random_net/random_net.sumocfg";
  const Scenario dijkstra = load_scenario(parse_cli_options({"-c", cfg}));
  const Scenario cch = load_scenario(parse_cli_options({"-c", cfg, "--routing-algorithm", "CH"}));
  const Demand& a = dijkstra.demand;
  const Demand& b = cch.demand;
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 300u);
  const Router router(dijkstra.network);
  int differ = 0, longer = 0;
  for (uint32_t v = 0; v < a.size(); ++v) {
    const std::vector<uint32_t> ra(a.route_edges.begin() + a.route_begin[v],
                                   a.route_edges.begin() + a.route_begin[v] + a.route_length[v]);
    const std::vector<uint32_t> rb(b.route_edges.begin() + b.route_begin[v],
                                   b.route_edges.begin() + b.route_begin[v] + b.route_length[v]);
    longer += rb.size() > 1 ? 1 : 0;
    EXPECT_TRUE(same_cost(router.cost(ra), router.cost(rb))) << a.vehicle_id[v];
    differ += ra != rb ? 1 : 0;
  }
  EXPECT_GT(longer, 250);
  EXPECT_LT(differ, 30) << "routes of equal cost may differ, not most of them";
  EXPECT_NO_THROW(parse_cli_options({"-c", cfg, "--routing-algorithm", "astar"}));
  EXPECT_THROW(parse_cli_options({"-c", cfg, "--routing-algorithm", "bellman"}), InputError);
}

}  // namespace
}  // namespace lpsim

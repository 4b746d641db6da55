// Requests that share a multi-edge origin set (trips between junctions or zones) are answered by one shared
// search; each must still get exactly the path its own search would give.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "net/network_builder.hpp"
#include "net/router.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

TEST(RouterOriginSets, SharedOriginSetsMatchSeparateSearches) {
  NetSpec s = test::make_grid_spec(7, 7);
  std::mt19937 rng(11);
  for (auto& e : s.edges) {
    const double v = std::uniform_real_distribution<double>(5, 30)(rng);
    for (auto& l : e.lanes) l.speed = v;
  }
  Network net = build_network(s);
  Router router(net);
  std::uniform_int_distribution<uint32_t> pick(0, net.num_edges() - 1);
  // Four origin sets of 1-3 edges, as the edges leaving a junction; 200 requests over them.
  std::vector<std::vector<uint32_t>> origin_sets;
  for (int k = 0; k < 4; ++k) {
    std::vector<uint32_t> set;
    for (int j = 0; j <= k % 3; ++j) set.push_back(pick(rng));
    origin_sets.push_back(set);
  }
  std::vector<RouteRequest> reqs;
  for (int i = 0; i < 200; ++i) {
    RouteRequest r;
    r.origins = origin_sets[static_cast<size_t>(i) % origin_sets.size()];
    r.destinations = {pick(rng)};
    if (i % 3 == 0) r.destinations.push_back(pick(rng));
    reqs.push_back(r);
  }
  const auto together = router.route_all(reqs, 2);
  ASSERT_EQ(together.size(), reqs.size());
  size_t routed = 0;
  for (size_t i = 0; i < reqs.size(); ++i) {
    EXPECT_EQ(router.route_all({reqs[i]}, 1)[0], together[i]) << "request " << i;
    // Optimal: no single origin of the set reaches a destination faster.
    double best = 1e300;
    for (uint32_t o : reqs[i].origins) {
      const auto p = router.route_all({{{o}, reqs[i].destinations, {}}}, 1)[0];
      if (!p.empty()) best = std::min(best, router.cost(p));
    }
    EXPECT_NEAR(router.cost(together[i]), best, 1e-6) << "request " << i;
    routed += together[i].empty() ? 0 : 1;
  }
  EXPECT_EQ(routed, reqs.size());  // the grid is strongly connected
  EXPECT_EQ(router.route_all(reqs, 1), together);
}

}  // namespace
}  // namespace lpsim

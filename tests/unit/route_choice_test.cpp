// Gawron's route choice between assignment iterations (demand/route_choice.hpp), checked by hand.
#include "demand/route_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace lpsim {
namespace {

using Edges = std::vector<uint32_t>;

TEST(RouteChoice, FirstRouteIsTheOnlyAlternative) {
  RouteAlternatives alts;
  const uint32_t k = choose_route(
      alts, {1, 2, 3}, [](const Edges& e) { return 10.0 * e.size(); }, {}, 0.7);
  EXPECT_EQ(k, 0u);
  ASSERT_EQ(alts.routes.size(), 1u);
  EXPECT_EQ(alts.routes[0].edges, (Edges{1, 2, 3}));
  EXPECT_DOUBLE_EQ(alts.routes[0].cost, 30.0);
  EXPECT_DOUBLE_EQ(alts.routes[0].probability, 1.0);
}

TEST(RouteChoice, NewFasterRouteGetsGawronsProbability) {
  // Route A was driven and now takes 120 s; the new best route B takes 80 s.
  const Edges a{1, 2}, b{1, 3};
  std::map<Edges, double> cost{{a, 120.0}, {b, 80.0}};
  auto cost_of = [&](const Edges& e) { return cost.at(e); };
  RouteAlternatives alts;
  alts.routes.push_back({a, 100.0, 1.0});
  GawronOptions g;  // beta 0.9, a 0.5
  // By hand: both at 1/2; delta = (80 - 120) / 200 = -0.2; g = exp(0.5 * -0.2 / 0.96);
  // p_A = 0.5 * 1 * g / (0.5 g + 0.5).
  const double gx = std::exp(0.5 * -0.2 / 0.96);
  const double pa = 0.5 * gx / (0.5 * gx + 0.5);
  RouteAlternatives first = alts;
  EXPECT_EQ(choose_route(first, b, cost_of, g, pa - 1e-9), 0u);
  ASSERT_EQ(first.routes.size(), 2u);
  EXPECT_DOUBLE_EQ(first.routes[0].cost, 120.0);  // driven: its new cost whole
  EXPECT_DOUBLE_EQ(first.routes[1].cost, 80.0);
  EXPECT_NEAR(first.routes[0].probability, pa, 1e-15);
  EXPECT_NEAR(first.routes[1].probability, 1 - pa, 1e-15);
  RouteAlternatives second = alts;
  EXPECT_EQ(choose_route(second, b, cost_of, g, pa + 1e-9), 1u);
  EXPECT_EQ(second.last, 1u);

  // Next iteration B was driven and the times are the other way round; A (not driven) is smoothed:
  // 0.9 * 70 + 0.1 * 120 = 75.
  cost = {{a, 70.0}, {b, 90.0}};
  choose_route(second, b, cost_of, g, 0.0);
  ASSERT_EQ(second.routes.size(), 2u);
  EXPECT_DOUBLE_EQ(second.routes[0].cost, 75.0);
  EXPECT_DOUBLE_EQ(second.routes[1].cost, 90.0);
  const double d = (90.0 - 75.0) / 165.0, g2 = std::exp(0.5 * d / (1 - d * d));
  const double pa2 = pa * (pa + (1 - pa)) * g2 / (pa * g2 + (1 - pa));
  EXPECT_NEAR(second.routes[0].probability, pa2, 1e-15);
  EXPECT_GT(pa2, pa);  // A is cheaper now: more likely
}

TEST(RouteChoice, AtMostMaxAlternativesTheMostProbableKept) {
  GawronOptions g;
  g.max_alternatives = 3;
  RouteAlternatives alts;
  for (uint32_t k = 0; k < 3; ++k) alts.routes.push_back({{k}, 100.0, 1.0 / 3});
  // The new route is the cheapest by far: it stays, and the two dearest old ones... one of them goes.
  auto cost_of = [](const Edges& e) { return e[0] == 9 ? 10.0 : 100.0 + e[0]; };
  choose_route(alts, {9}, cost_of, g, 0.5);
  ASSERT_EQ(alts.routes.size(), 3u);
  double sum = 0;
  for (const auto& r : alts.routes) sum += r.probability;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_EQ(alts.routes[0].edges, (Edges{9}));                       // sorted by probability, highest first
  for (const auto& r : alts.routes) EXPECT_NE(r.edges, (Edges{2}));  // the dearest is dropped
}

TEST(RouteChoice, KnownBestRouteAddsNothing) {
  RouteAlternatives alts;
  alts.routes.push_back({{1}, 50.0, 0.6});
  alts.routes.push_back({{2}, 60.0, 0.4});
  choose_route(
      alts, {2}, [](const Edges& e) { return e[0] == 1 ? 50.0 : 40.0; }, {}, 0.99);
  ASSERT_EQ(alts.routes.size(), 2u);
  EXPECT_NEAR(alts.routes[0].probability + alts.routes[1].probability, 1.0, 1e-12);
  EXPECT_GT(alts.routes[1].probability, 0.4);
  EXPECT_EQ(alts.last, 1u);
}

}  // namespace
}  // namespace lpsim

// Gawron's route choice between assignment iterations (demand/route_choice.hpp), checked by hand.
#include "demand/route_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace lpsim {
namespace {

using Edges = std::vector<uint32_t>;

double unit_time(uint32_t) { return 1.0; }

TEST(RouteChoice, FirstRouteIsTheOnlyAlternative) {
  RouteAlternatives alts;
  const uint32_t k = choose_route(
      alts, {1, 2, 3}, [](const Edges& e) { return 10.0 * e.size(); }, unit_time, {}, 0.7);
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
  RouteChoiceOptions g;  // beta 0.9, a 0.5
  // By hand: both at 1/2; delta = (80 - 120) / 200 = -0.2; g = exp(0.5 * -0.2 / 0.96);
  // p_A = 0.5 * 1 * g / (0.5 g + 0.5).
  const double gx = std::exp(0.5 * -0.2 / 0.96);
  const double pa = 0.5 * gx / (0.5 * gx + 0.5);
  RouteAlternatives first = alts;
  EXPECT_EQ(choose_route(first, b, cost_of, unit_time, g, pa - 1e-9), 0u);
  ASSERT_EQ(first.routes.size(), 2u);
  EXPECT_DOUBLE_EQ(first.routes[0].cost, 120.0);  // driven: its new cost whole
  EXPECT_DOUBLE_EQ(first.routes[1].cost, 80.0);
  EXPECT_NEAR(first.routes[0].probability, pa, 1e-15);
  EXPECT_NEAR(first.routes[1].probability, 1 - pa, 1e-15);
  RouteAlternatives second = alts;
  EXPECT_EQ(choose_route(second, b, cost_of, unit_time, g, pa + 1e-9), 1u);
  EXPECT_EQ(second.last, 1u);

  // Next iteration B was driven and the times are the other way round; A (not driven) is smoothed:
  // 0.9 * 70 + 0.1 * 120 = 75.
  cost = {{a, 70.0}, {b, 90.0}};
  choose_route(second, b, cost_of, unit_time, g, 0.0);
  ASSERT_EQ(second.routes.size(), 2u);
  EXPECT_DOUBLE_EQ(second.routes[0].cost, 75.0);
  EXPECT_DOUBLE_EQ(second.routes[1].cost, 90.0);
  const double d = (90.0 - 75.0) / 165.0, g2 = std::exp(0.5 * d / (1 - d * d));
  const double pa2 = pa * (pa + (1 - pa)) * g2 / (pa * g2 + (1 - pa));
  EXPECT_NEAR(second.routes[0].probability, pa2, 1e-15);
  EXPECT_GT(pa2, pa);  // A is cheaper now: more likely
}

TEST(RouteChoice, AtMostMaxAlternativesTheMostProbableKept) {
  RouteChoiceOptions g;
  g.max_alternatives = 3;
  RouteAlternatives alts;
  for (uint32_t k = 0; k < 3; ++k) alts.routes.push_back({{k}, 100.0, 1.0 / 3});
  // The new route is the cheapest by far: it stays, and the two dearest old ones... one of them goes.
  auto cost_of = [](const Edges& e) { return e[0] == 9 ? 10.0 : 100.0 + e[0]; };
  choose_route(alts, {9}, cost_of, unit_time, g, 0.5);
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
      alts, {2}, [](const Edges& e) { return e[0] == 1 ? 50.0 : 40.0; }, unit_time, {}, 0.99);
  ASSERT_EQ(alts.routes.size(), 2u);
  EXPECT_NEAR(alts.routes[0].probability + alts.routes[1].probability, 1.0, 1e-12);
  EXPECT_GT(alts.routes[1].probability, 0.4);
  EXPECT_EQ(alts.last, 1u);
}

TEST(RouteChoice, LogitOnCostsAlone) {
  RouteChoiceOptions logit;
  logit.method = RouteChoiceOptions::Method::Logit;
  logit.logit_beta = 0;  // no commonality
  logit.logit_theta = 0.05;
  RouteAlternatives alts;
  alts.routes.push_back({{1}, 999.0, 0.5});
  alts.routes.push_back({{2}, 999.0, 0.5});
  choose_route(
      alts, {1}, [](const Edges& e) { return e[0] == 1 ? 100.0 : 120.0; }, unit_time, logit, 0.0);
  // The new costs whole (no smoothing); p = 1 / sum exp(theta (c_i - c_j)): 1 / (1 + e^-1) for the cheaper.
  EXPECT_DOUBLE_EQ(alts.routes[0].cost, 100.0);
  EXPECT_DOUBLE_EQ(alts.routes[1].cost, 120.0);
  EXPECT_NEAR(alts.routes[0].probability, 1 / (1 + std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(alts.routes[1].probability, 1 / (1 + std::exp(1.0)), 1e-12);
}

TEST(RouteChoice, CLogitFavoursTheRouteSharingLeast) {
  RouteChoiceOptions logit;
  logit.method = RouteChoiceOptions::Method::Logit;
  logit.logit_beta = 1;
  logit.logit_gamma = 1;
  logit.logit_theta = 0.05;
  // A and B share edge 1, C shares nothing; all cost 100 s. Each edge takes 1 s: A's commonality is
  // log(2/2 + 1/2 + 0) = log 1.5, B's too, C's log 1 = 0.
  RouteAlternatives alts;
  alts.routes.push_back({{1, 2}, 100.0, 1.0 / 3});
  alts.routes.push_back({{1, 3}, 100.0, 1.0 / 3});
  alts.routes.push_back({{4}, 100.0, 1.0 / 3});
  choose_route(
      alts, {1, 2}, [](const Edges&) { return 100.0; }, unit_time, logit, 0.0);
  const double cf = std::log(1.5);
  EXPECT_NEAR(alts.routes[0].probability, 1 / (2 + std::exp(0.05 * cf)), 1e-12);
  EXPECT_NEAR(alts.routes[1].probability, 1 / (2 + std::exp(0.05 * cf)), 1e-12);
  EXPECT_NEAR(alts.routes[2].probability, 1 / (2 * std::exp(-0.05 * cf) + 1), 1e-12);
  EXPECT_GT(alts.routes[2].probability, alts.routes[0].probability);
}

}  // namespace
}  // namespace lpsim

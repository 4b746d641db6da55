#pragma once
// A vehicle's route alternatives and how it chooses among them between assignment iterations, as duarouter
// does for duaIterate.py (RORouteDef::addAlternative with Gawron's cost and probability update).
#include <cstdint>
#include <functional>
#include <vector>

namespace lpsim {

struct RouteAlternative {
  std::vector<uint32_t> edges;
  double cost = 0;         // s: the smoothed travel time Gawron's model keeps
  double probability = 0;  // of being chosen
};

/// One vehicle's alternatives (SUMO's <routeDistribution>) and the one it drove last (`last`).
struct RouteAlternatives {
  std::vector<RouteAlternative> routes;
  uint32_t last = 0;
};

/// How a vehicle chooses among its alternatives: Gawron's model with duaIterate's defaults (--gA 0.5, --gBeta
/// 0.9; not duarouter's own), or duarouter's (C-)logit with its defaults.
struct RouteChoiceOptions {
  enum class Method { Gawron, Logit } method = Method::Gawron;
  double gawron_beta = 0.9;  // weight of the new travel time in a route's cost (the route driven last: whole)
  double gawron_a = 0.5;     // sensitivity of the probabilities to cost differences
  // Logit: utilities -theta * cost, less beta * log of each route's commonality with the others (C-logit,
  // its overlap in travel time raised to gamma); theta < 0: from the costs' spread, as duarouter does.
  double logit_beta = 0.15, logit_gamma = 1.0, logit_theta = -1;
  uint32_t max_alternatives = 5;
  bool keep_all_routes = false;  // keep routes whose probability fell to 0
};

/// Adds `best` (the fastest route at the new travel times) to `alts` unless it is one of them (a new route
/// starts at probability 1/n, the others scaled by (n-1)/n), re-costs every alternative with `cost_of`
/// (Gawron: the route driven last takes its new cost, the others beta * new + (1 - beta) * old; logit: the
/// new cost), updates the probabilities (Gawron: pairwise by Gawron's formula; logit: by the logit formula on
/// the costs and, for C-logit, the commonalities, each edge weighing `edge_time` of it), drops routes of
/// probability 0 (unless keep_all_routes) and all but the max_alternatives most probable ones (renormalized),
/// and chooses a route by `draw` (uniform in [0, 1)): the first whose cumulative probability reaches it.
/// Returns the chosen index, also in alts.last. With no alternatives yet, `best` becomes the only one,
/// chosen with probability 1.
uint32_t choose_route(RouteAlternatives& alts, std::vector<uint32_t> best,
                      const std::function<double(const std::vector<uint32_t>&)>& cost_of,
                      const std::function<double(uint32_t)>& edge_time, const RouteChoiceOptions& options,
                      double draw);

}  // namespace lpsim

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

/// Gawron's model as duaIterate runs it: its defaults (--gA 0.5, --gBeta 0.9), not duarouter's own.
struct GawronOptions {
  double beta =
      0.9;         // weight of the new travel time in a route's cost (the route driven last takes it whole)
  double a = 0.5;  // sensitivity of the probabilities to cost differences
  uint32_t max_alternatives = 5;
  bool keep_all_routes = false;  // keep routes whose probability fell to 0
};

/// Adds `best` (the fastest route at the new travel times) to `alts` unless it is one of them (a new route
/// starts at probability 1/n, the others scaled by (n-1)/n), re-costs every alternative with `cost_of`
/// (Gawron: the route driven last takes its new cost, the others beta * new + (1 - beta) * old), updates the
/// probabilities pairwise by Gawron's formula, drops routes of probability 0 (unless keep_all_routes) and all
/// but the max_alternatives most probable ones (renormalized), and chooses a route by `draw` (uniform in
/// [0, 1)): the first whose cumulative probability reaches it. Returns the chosen index, also in alts.last.
/// With no alternatives yet, `best` becomes the only one, chosen with probability 1.
uint32_t choose_route(RouteAlternatives& alts, std::vector<uint32_t> best,
                      const std::function<double(const std::vector<uint32_t>&)>& cost_of,
                      const GawronOptions& options, double draw);

}  // namespace lpsim

#include "demand/route_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lpsim {
namespace {

// Gawron (1998), "Simulation-based traffic assignment", (4.3): g(x) = exp(a x / (1 - x^2)) and the new
// probability of route r against route s, f(p_r, p_s, x) = p_r (p_r + p_s) g / (p_r g + p_s).
double gawron_g(double a, double x) {
  const double d = 1.0 - x * x;
  return d == 0 ? std::numeric_limits<double>::max() : std::exp(a * x / d);
}

double gawron_f(double pr, double ps, double a, double x) {
  const double g = gawron_g(a, x);
  const double denominator = pr * g + ps;
  return denominator == 0 ? std::numeric_limits<double>::max() : pr * (pr + ps) * g / denominator;
}

void update_probabilities(std::vector<RouteAlternative>& routes, double a) {
  for (size_t i = 0; i + 1 < routes.size(); ++i)
    for (size_t j = i + 1; j < routes.size(); ++j) {
      RouteAlternative& r = routes[i];
      RouteAlternative& s = routes[j];
      const double delta = (s.cost - r.cost) / (s.cost + r.cost);
      double pr = gawron_f(r.probability, s.probability, a, delta);
      double ps = r.probability + s.probability - pr;
      if (std::isnan(pr) || std::isnan(ps)) {
        pr = s.cost > r.cost ? 1.0 : 0.0;
        ps = 1.0 - pr;
      }
      r.probability = std::clamp(pr, 0.0, 1.0);
      s.probability = std::clamp(ps, 0.0, 1.0);
    }
}

// duarouter's LogitCalculator: theta and beta from the costs (in hours) where not given.
double logit_theta(const std::vector<RouteAlternative>& routes) {
  double sum = 0, min = std::numeric_limits<double>::max();
  for (const RouteAlternative& r : routes) {
    sum += r.cost / 3600.0;
    min = std::min(min, r.cost / 3600.0);
  }
  const double mean = sum / double(routes.size());
  double diff = 0;
  for (const RouteAlternative& r : routes) diff += (r.cost / 3600.0 - mean) * (r.cost / 3600.0 - mean);
  const double cv = std::sqrt(diff / double(routes.size())) / mean;
  return M_PI / (std::sqrt(6.0) * cv * (min + 1.1)) / 3600.0;
}

double logit_beta(const std::vector<RouteAlternative>& routes) {
  double min = std::numeric_limits<double>::max();
  for (const RouteAlternative& r : routes) min = std::min(min, r.cost / 3600.0);
  return min;
}

void update_logit_probabilities(std::vector<RouteAlternative>& routes, const RouteChoiceOptions& o,
                                const std::function<double(uint32_t)>& edge_time) {
  const double theta = o.logit_theta >= 0 ? o.logit_theta : logit_theta(routes);
  const double beta = o.logit_beta >= 0 ? o.logit_beta : logit_beta(routes);
  std::vector<double> commonality(routes.size(), 0.0);
  if (beta > 0) {
    for (size_t i = 0; i < routes.size(); ++i) {
      const std::vector<uint32_t>& r = routes[i].edges;
      double length_r = 0;
      for (uint32_t e : r) length_r += edge_time(e);
      double overlap_sum = 0;
      for (const RouteAlternative& s : routes) {
        double overlap = 0, length_s = 0;
        for (uint32_t e : s.edges) {
          length_s += edge_time(e);
          if (std::find(r.begin(), r.end(), e) != r.end()) overlap += edge_time(e);
        }
        overlap_sum += std::pow(overlap / std::sqrt(length_r * length_s), o.logit_gamma);
      }
      commonality[i] = beta * std::log(overlap_sum);
    }
  }
  for (size_t i = 0; i < routes.size(); ++i) {
    double weighted = 0;
    for (size_t j = 0; j < routes.size(); ++j)
      weighted += std::exp(theta * (routes[i].cost - routes[j].cost + commonality[i] - commonality[j]));
    routes[i].probability = 1.0 / weighted;
  }
}

}  // namespace

uint32_t choose_route(RouteAlternatives& alts, std::vector<uint32_t> best,
                      const std::function<double(const std::vector<uint32_t>&)>& cost_of,
                      const std::function<double(uint32_t)>& edge_time, const RouteChoiceOptions& options,
                      double draw) {
  const bool gawron = options.method == RouteChoiceOptions::Method::Gawron;
  auto& routes = alts.routes;
  if (routes.empty()) {
    const double cost = cost_of(best);
    routes.push_back({std::move(best), cost, 1.0});
    alts.last = 0;
    return 0;
  }
  const uint32_t driven = std::min<uint32_t>(alts.last, static_cast<uint32_t>(routes.size() - 1));
  const bool is_new =
      std::none_of(routes.begin(), routes.end(), [&](const RouteAlternative& r) { return r.edges == best; });
  if (is_new) routes.push_back({std::move(best), 0.0, 0.0});
  const double n = double(routes.size());
  for (size_t i = 0; i < routes.size(); ++i) {
    RouteAlternative& r = routes[i];
    const double cost = cost_of(r.edges);
    if (is_new) {
      if (i + 1 == routes.size()) {
        r.probability = 1.0 / n;
        r.cost = cost;
      } else {
        r.probability *= (n - 1) / n;
      }
    }
    r.cost =
        !gawron || i == driven ? cost : options.gawron_beta * cost + (1.0 - options.gawron_beta) * r.cost;
  }
  if (gawron)
    update_probabilities(routes, options.gawron_a);
  else
    update_logit_probabilities(routes, options, edge_time);
  if (!options.keep_all_routes)
    std::erase_if(routes, [](const RouteAlternative& r) { return r.probability == 0; });
  if (routes.size() > options.max_alternatives) {
    std::stable_sort(routes.begin(), routes.end(), [](const RouteAlternative& x, const RouteAlternative& y) {
      return x.probability > y.probability;
    });
    routes.resize(options.max_alternatives);
    double sum = 0;
    for (const RouteAlternative& r : routes) sum += r.probability;
    for (RouteAlternative& r : routes) r.probability /= sum;
  }
  double left = draw;
  uint32_t chosen = 0;
  for (; chosen + 1 < routes.size(); ++chosen) {
    left -= routes[chosen].probability;
    if (left <= 0) break;
  }
  alts.last = chosen;
  return chosen;
}

}  // namespace lpsim

#include "partition/kmeans.hpp"

#include <cstddef>
#include <limits>

#include "kernels/rng.hpp"

namespace lpsim {

using std::size_t;

namespace {
constexpr uint64_t kKmeansSalt = 0x4b4d45414e53ull;  // "KMEANS"
constexpr int kMaxIterations = 200;

double dist2(double ax, double ay, double bx, double by) {
  return (ax - bx) * (ax - bx) + (ay - by) * (ay - by);
}
}  // namespace

std::vector<int32_t> kmeans(const std::vector<double>& x, const std::vector<double>& y, int32_t k,
                            uint64_t seed) {
  const size_t n = x.size();
  std::vector<double> cx, cy;
  // k-means++: the first centre at random, each next one drawn with probability proportional to the squared
  // distance to the nearest centre so far.
  std::vector<double> d2(n, std::numeric_limits<double>::max());
  size_t first = static_cast<size_t>(rng_uniform_double(seed ^ kKmeansSalt, 0, 0) * static_cast<double>(n));
  if (first >= n) first = n - 1;
  cx.push_back(x[first]);
  cy.push_back(y[first]);
  for (int32_t c = 1; c < k; ++c) {
    double total = 0;
    for (size_t i = 0; i < n; ++i) {
      const double d = dist2(x[i], y[i], cx.back(), cy.back());
      if (d < d2[i]) d2[i] = d;
      total += d2[i];
    }
    size_t pick = 0;
    if (total > 0) {
      double r = rng_uniform_double(seed ^ kKmeansSalt, 1, static_cast<uint64_t>(c)) * total;
      for (pick = 0; pick + 1 < n && r >= d2[pick]; ++pick) r -= d2[pick];
    } else {
      pick = static_cast<size_t>(c) % n;  // every point coincides with a centre
    }
    cx.push_back(x[pick]);
    cy.push_back(y[pick]);
  }
  std::vector<int32_t> cluster(n, -1);
  for (int it = 0; it < kMaxIterations; ++it) {
    bool changed = false;
    for (size_t i = 0; i < n; ++i) {
      int32_t best = 0;
      double bd = std::numeric_limits<double>::max();
      for (int32_t c = 0; c < k; ++c) {
        const double d = dist2(x[i], y[i], cx[static_cast<size_t>(c)], cy[static_cast<size_t>(c)]);
        if (d < bd) bd = d, best = c;
      }
      if (cluster[i] != best) cluster[i] = best, changed = true;
    }
    // An empty cluster takes the point farthest from its own centre.
    std::vector<int64_t> count(static_cast<size_t>(k), 0);
    for (size_t i = 0; i < n; ++i) ++count[static_cast<size_t>(cluster[i])];
    for (int32_t c = 0; c < k; ++c) {
      if (count[static_cast<size_t>(c)] > 0) continue;
      size_t far = n;
      double fd = -1;
      for (size_t i = 0; i < n; ++i) {
        const size_t own = static_cast<size_t>(cluster[i]);
        if (count[own] < 2) continue;
        const double d = dist2(x[i], y[i], cx[own], cy[own]);
        if (d > fd) fd = d, far = i;
      }
      --count[static_cast<size_t>(cluster[far])];
      cluster[far] = c;
      count[static_cast<size_t>(c)] = 1;
      changed = true;
    }
    std::vector<double> sx(static_cast<size_t>(k), 0), sy(static_cast<size_t>(k), 0);
    for (size_t i = 0; i < n; ++i)
      sx[static_cast<size_t>(cluster[i])] += x[i], sy[static_cast<size_t>(cluster[i])] += y[i];
    for (int32_t c = 0; c < k; ++c) {
      const size_t s = static_cast<size_t>(c);
      cx[s] = sx[s] / static_cast<double>(count[s]);
      cy[s] = sy[s] / static_cast<double>(count[s]);
    }
    if (!changed) break;
  }
  return cluster;
}

}  // namespace lpsim

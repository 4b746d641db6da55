#include "demand/demand_draws.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lpsim {

uint32_t draw_weighted(const std::vector<double>& cumulative_weights, uint64_t seed, uint64_t stream,
                       uint64_t counter) {
  const double target = rng_uniform_double(seed, stream, counter) * cumulative_weights.back();
  // First member whose cumulative weight exceeds the target; members of weight 0 are never picked.
  auto it = std::upper_bound(cumulative_weights.begin(), cumulative_weights.end(), target);
  if (it == cumulative_weights.end()) --it;  // target == total only through rounding
  return static_cast<uint32_t>(it - cumulative_weights.begin());
}

double draw_speed_factor(double mean, double dev, uint64_t seed, uint64_t stream) {
  if (dev <= 0) return mean;
  // Truncation by redrawing keeps the shape of the normal inside the bounds (SUMO redraws too); the
  // attempt limit only matters for absurd parameters where the bounds hold almost no probability mass.
  constexpr int kAttempts = 64;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const uint64_t counter = kDrawSpeedFactor + 2 * static_cast<uint64_t>(attempt);
    const double u1 = 1.0 - rng_uniform_double(seed, stream, counter);  // (0, 1]: log is finite
    const double u2 = rng_uniform_double(seed, stream, counter + 1);
    const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    const double value = mean + dev * z;
    if (value >= kSpeedFactorMin && value <= kSpeedFactorMax) return value;
  }
  return std::clamp(mean, kSpeedFactorMin, kSpeedFactorMax);
}

}  // namespace lpsim

#pragma once
// k-means on points in the plane (Lloyd's iterations from a k-means++ start), deterministic in its seed.
#include <stdint.h>

#include <vector>

namespace lpsim {

/// The cluster (0..k-1) of each point; every cluster gets at least one point (1 <= k <= points).
std::vector<int32_t> kmeans(const std::vector<double>& x, const std::vector<double>& y, int32_t k,
                            uint64_t seed);

}  // namespace lpsim

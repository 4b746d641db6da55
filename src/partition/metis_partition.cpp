// METIS k-way partitioning of the junction graph (Debian's libmetis-dev, 32-bit idx_t).
#include <metis.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "partition/partition_method.hpp"

namespace lpsim {

namespace {

// METIS sums weights in its 32-bit idx_t: scale them so that every sum stays below 2^30, keeping each
// weight at least 1 (their ratios, which the partitioning depends on, are kept to that precision).
std::vector<idx_t> scaled_weights(const std::vector<int64_t>& w) {
  const int64_t total = std::accumulate(w.begin(), w.end(), int64_t{0});
  const int64_t limit = int64_t{1} << 30;
  const int64_t div = total > limit ? (total + limit - 1) / limit : 1;
  std::vector<idx_t> out(w.size());
  for (size_t i = 0; i < w.size(); ++i) out[i] = static_cast<idx_t>(std::max<int64_t>(1, w[i] / div));
  return out;
}

}  // namespace

std::vector<int32_t> metis_partition(const JunctionGraph& g, int32_t k, uint64_t seed) {
  idx_t n = static_cast<idx_t>(g.num_vertices()), ncon = 1, nparts = k, objval = 0;
  std::vector<idx_t> xadj(g.adj_begin.begin(), g.adj_begin.end()), adjncy(g.adj.begin(), g.adj.end());
  std::vector<idx_t> vwgt = scaled_weights(g.vertex_weight), adjwgt = scaled_weights(g.adj_weight);
  std::vector<idx_t> part(static_cast<size_t>(n), 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed & 0x7fffffff);
  // METIS reads adjncy/adjwgt through non-const pointers but does not change them.
  const int rc = METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.empty() ? nullptr : adjncy.data(),
                                     vwgt.data(), nullptr, adjwgt.empty() ? nullptr : adjwgt.data(), &nparts,
                                     nullptr, nullptr, options, &objval, part.data());
  if (rc != METIS_OK)
    throw std::runtime_error("METIS_PartGraphKway failed (status " + std::to_string(rc) + ")");
  return std::vector<int32_t>(part.begin(), part.end());
}

}  // namespace lpsim

// The paper's unbalanced partitioning: Leiden communities of the junction graph (igraph, modularity on the
// demand weights) merged into K parts by k-means on the communities' centroids.
#include <igraph/igraph.h>

#include <stdexcept>
#include <string>

#include "partition/kmeans.hpp"
#include "partition/partition_method.hpp"

namespace lpsim {

namespace {

constexpr int kMaxResolutionDoublings = 30;

void check(igraph_error_t rc, const char* what) {
  if (rc != IGRAPH_SUCCESS)
    throw std::runtime_error(std::string("igraph: ") + what + " failed: " + igraph_strerror(rc));
}

// The Leiden communities of g: modularity with the resolution doubled until there are at least k of them.
std::vector<int32_t> leiden_communities(const JunctionGraph& g, int32_t k, uint64_t seed) {
  const uint32_t n = g.num_vertices();
  igraph_vector_int_t edges;
  igraph_vector_t weights;
  check(igraph_vector_int_init(&edges, 0), "vector");
  check(igraph_vector_init(&weights, 0), "vector");
  double total = 0;
  for (uint32_t u = 0; u < n; ++u)
    for (int32_t a = g.adj_begin[u]; a < g.adj_begin[u + 1]; ++a) {
      const int32_t v = g.adj[static_cast<size_t>(a)];
      if (static_cast<uint32_t>(v) <= u) continue;  // each undirected edge once
      check(igraph_vector_int_push_back(&edges, u), "push_back");
      check(igraph_vector_int_push_back(&edges, v), "push_back");
      const double w = static_cast<double>(g.adj_weight[static_cast<size_t>(a)]);
      check(igraph_vector_push_back(&weights, w), "push_back");
      total += w;
    }
  igraph_t graph;
  check(igraph_create(&graph, &edges, n, IGRAPH_UNDIRECTED), "create");
  igraph_vector_t strength;
  check(igraph_vector_init(&strength, 0), "vector");
  check(igraph_strength(&graph, &strength, igraph_vss_all(), IGRAPH_ALL, IGRAPH_LOOPS, &weights), "strength");
  igraph_vector_int_t membership;
  check(igraph_vector_int_init(&membership, 0), "vector");
  igraph_integer_t clusters = 0;
  igraph_real_t quality = 0;
  // Modularity is the Leiden quality with node weights = strengths and resolution 1 / (2m).
  double resolution = total > 0 ? 1.0 / (2.0 * total) : 1.0;
  for (int i = 0; i <= kMaxResolutionDoublings; ++i, resolution *= 2) {
    igraph_rng_seed(igraph_rng_default(), static_cast<igraph_uint_t>(seed));
    check(igraph_community_leiden(&graph, &weights, &strength, resolution, 0.01, false, -1, &membership,
                                  &clusters, &quality),
          "community_leiden");
    if (clusters >= k) break;
  }
  std::vector<int32_t> community(n);
  for (uint32_t u = 0; u < n; ++u) community[u] = static_cast<int32_t>(VECTOR(membership)[u]);
  igraph_vector_int_destroy(&membership);
  igraph_vector_destroy(&strength);
  igraph_destroy(&graph);
  igraph_vector_destroy(&weights);
  igraph_vector_int_destroy(&edges);
  if (clusters < k)
    throw std::runtime_error("Leiden found " + std::to_string(clusters) + " communities, fewer than " +
                             std::to_string(k) + " parts");
  return community;
}

}  // namespace

std::vector<int32_t> leiden_kmeans_partition(const JunctionGraph& g, int32_t k, uint64_t seed) {
  const std::vector<int32_t> community = leiden_communities(g, k, seed);
  int32_t communities = 0;
  for (int32_t c : community) communities = c + 1 > communities ? c + 1 : communities;
  std::vector<double> cx(static_cast<size_t>(communities), 0), cy(cx), count(cx);
  for (uint32_t j = 0; j < g.num_vertices(); ++j) {
    const size_t c = static_cast<size_t>(community[j]);
    cx[c] += g.x[j];
    cy[c] += g.y[j];
    count[c] += 1;
  }
  for (size_t c = 0; c < cx.size(); ++c) cx[c] /= count[c], cy[c] /= count[c];
  const std::vector<int32_t> cluster = kmeans(cx, cy, k, seed);
  std::vector<int32_t> part(g.num_vertices());
  for (uint32_t j = 0; j < g.num_vertices(); ++j) part[j] = cluster[static_cast<size_t>(community[j])];
  return part;
}

}  // namespace lpsim

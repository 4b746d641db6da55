#pragma once
// The partitioners of `lpsim partition`: which part each junction of a JunctionGraph goes to. Each is
// deterministic in its seed: the same graph, part count and seed give the same parts.
#include <stdint.h>

#include <optional>
#include <string_view>
#include <vector>

#include "partition/junction_graph.hpp"

namespace lpsim {

enum class PartitionMethod {
  Metis,   // balanced: METIS k-way on the weighted graph (vertex weight balanced, cut weight minimised)
  Leiden,  // unbalanced: Leiden communities (modularity) merged into K parts by k-means on their centroids
  Random,  // baseline: each junction to a part drawn at random
};

std::optional<PartitionMethod> partition_method_from_name(std::string_view name);
const char* partition_method_name(PartitionMethod m);

/// The part (0..k-1) of each junction of the network g was built from (internal junctions: 0). k must be at
/// least 1 and at most the number of g's vertices (InputError otherwise). The methods below give the part of
/// each vertex.
std::vector<int32_t> partition_junctions(const JunctionGraph& g, int32_t k, PartitionMethod m, uint64_t seed);

std::vector<int32_t> metis_partition(const JunctionGraph& g, int32_t k, uint64_t seed);
std::vector<int32_t> leiden_kmeans_partition(const JunctionGraph& g, int32_t k, uint64_t seed);
std::vector<int32_t> random_partition(const JunctionGraph& g, int32_t k, uint64_t seed);

}  // namespace lpsim

#include "partition/partition_method.hpp"

#include <string>

#include "core/error.hpp"
#include "kernels/rng.hpp"

namespace lpsim {

namespace {
// Salt that separates the random baseline's draws from every other use of the seed.
constexpr uint64_t kRandomPartitionSalt = 0x5041525452414e44ull;  // "PARTRAND"
}  // namespace

std::optional<PartitionMethod> partition_method_from_name(std::string_view name) {
  if (name == "metis") return PartitionMethod::Metis;
  if (name == "leiden") return PartitionMethod::Leiden;
  if (name == "random") return PartitionMethod::Random;
  return std::nullopt;
}

const char* partition_method_name(PartitionMethod m) {
  switch (m) {
    case PartitionMethod::Metis:
      return "metis";
    case PartitionMethod::Leiden:
      return "leiden";
    case PartitionMethod::Random:
      return "random";
  }
  return "?";
}

std::vector<int32_t> partition_junctions(const JunctionGraph& g, int32_t k, PartitionMethod m,
                                         uint64_t seed) {
  if (k < 1) throw InputError("the number of parts must be at least 1, not " + std::to_string(k));
  if (static_cast<uint32_t>(k) > g.num_vertices())
    throw InputError(std::to_string(k) + " parts need at least as many junctions; the network has " +
                     std::to_string(g.num_vertices()) + " (SUMO's internal junctions not counted)");
  std::vector<int32_t> vertex_part(g.num_vertices(), 0);
  if (k > 1) switch (m) {
      case PartitionMethod::Metis:
        vertex_part = metis_partition(g, k, seed);
        break;
      case PartitionMethod::Leiden:
        vertex_part = leiden_kmeans_partition(g, k, seed);
        break;
      case PartitionMethod::Random:
        vertex_part = random_partition(g, k, seed);
        break;
    }
  // An internal junction owns nothing: part 0, as a partition file's junctions without roads.
  std::vector<int32_t> part(g.num_junctions, 0);
  for (uint32_t v = 0; v < g.num_vertices(); ++v) part[g.junction[v]] = vertex_part[v];
  return part;
}

std::vector<int32_t> random_partition(const JunctionGraph& g, int32_t k, uint64_t seed) {
  std::vector<int32_t> part(g.num_vertices());
  for (uint32_t j = 0; j < g.num_vertices(); ++j) {
    const int32_t p =
        static_cast<int32_t>(rng_uniform(seed ^ kRandomPartitionSalt, j, 0) * static_cast<float>(k));
    part[j] = p < k ? p : k - 1;
  }
  return part;
}

}  // namespace lpsim

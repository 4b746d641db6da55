#include "app/mpi_parts.hpp"

#include <string>

#include "app/partitioned_parts.hpp"
#include "core/error.hpp"
#include "engine/simulation.hpp"
#include "transport/mpi/mpi_transport.hpp"

namespace lpsim {
namespace {

// What ranks of one job must share to exchange their state as bytes: the version, the build, and the sizes
// of what crosses between them.
std::string build_id() {
  return std::string(LPSIM_BUILD_ID) + " vehicle " + std::to_string(sizeof(VehicleView)) + "/" +
         std::to_string(sizeof(TripRecord)) + "/" + std::to_string(sizeof(PartStats));
}

}  // namespace

RankPart join_mpi_ranks(const Scenario& sc, const std::vector<int32_t>& edge_part, int32_t parts,
                        double timeout_s) {
  RankPart r;
  r.transport = std::make_unique<MpiTransport>(timeout_s);
  r.transport->check_same_build(build_id());
  r.plan = part_plan(sc.network, edge_part, parts, longest_vehicle(sc.demand), r.transport->rank());
  return r;
}

void require_one_part_per_rank(int ranks, int32_t parts) {
  if (ranks > 1 && parts != ranks)
    throw InputError("mpirun -n " + std::to_string(ranks) + " runs one part per rank: give --parts " +
                     std::to_string(ranks) + " or a partition file of " + std::to_string(ranks) +
                     " parts (not " + std::to_string(parts) + ")");
}

}  // namespace lpsim

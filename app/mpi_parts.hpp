#pragma once
// A partitioned job under mpirun: one part per rank, each rank holding its own part's plan and a transport to
// the others. Shared by `lpsim run` and `lpsim assign`.
#include <memory>
#include <vector>

#include "app/scenario.hpp"
#include "partition/part_plan.hpp"
#include "transport/transport.hpp"

namespace lpsim {

struct RankPart {
  std::unique_ptr<Transport> transport;
  PartPlan plan;  // this rank's part
};

/// Joins the job's ranks (who refuse to work with a rank of another build) and plans this rank's part of
/// `edge_part`'s `parts`. A part waits `timeout_s` for another at most.
RankPart join_mpi_ranks(const Scenario& sc, const std::vector<int32_t>& edge_part, int32_t parts,
                        double timeout_s);

/// InputError unless a job of `ranks` ranks (more than one) has as many parts.
void require_one_part_per_rank(int ranks, int32_t parts);

}  // namespace lpsim

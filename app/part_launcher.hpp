#pragma once
// How a job's parts start, for `lpsim run` and each iteration of `lpsim assign`: in one process (part 0
// alone, or parts 1..K-1 on threads beside it, partitioned_parts) or one part per rank under mpirun. The
// caller steps part 0 through it and never asks which.
#include <functional>
#include <memory>
#include <vector>

#include "app/scenario.hpp"
#include "engine/simulation.hpp"
#include "transport/transport.hpp"

namespace lpsim {

class PartLauncher {
 public:
  virtual ~PartLauncher() = default;

  /// Whether this process runs part 0, which steps the run, writes its outputs and reports. Only an MPI rank
  /// other than 0 does not.
  virtual bool leads() const = 0;

  /// In the process that leads: one simulation of `demand` on `net`, part0(its options) stepping part 0's
  /// Simulation while the other parts serve it. An error in part 0 releases the others and goes on; else the
  /// others' first error, once they have ended, is thrown as std::runtime_error.
  virtual void run_part0(const Network& net, const Demand& demand, const SimulationOptions& options,
                         const std::function<void(const SimulationOptions&)>& part0) = 0;

  /// In a process that does not lead: this rank's part of `demand` serves part 0 until the run ends.
  virtual void serve(const Network& net, Demand demand, const SimulationOptions& options) = 0;

  /// The transport between the job's ranks, for what they agree on besides a simulation (null: one process).
  virtual Transport* ranks() const = 0;
};

/// The launcher of a job of `ranks` processes (the MPI world's size) running `parts` parts of `edge_part`:
/// under mpirun one part per rank (joined here: each refuses to work with a rank of another build), else
/// this process alone (parts 1..K-1 on threads when parts > 1). A part waits `timeout_s` for another at
/// most.
std::unique_ptr<PartLauncher> launch_parts(int ranks, const Scenario& sc,
                                           const std::vector<int32_t>& edge_part, int32_t parts,
                                           double timeout_s);

/// InputError unless a job of `ranks` ranks (more than one) has as many parts.
void require_one_part_per_rank(int ranks, int32_t parts);

}  // namespace lpsim

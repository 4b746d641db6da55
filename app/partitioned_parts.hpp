#pragma once
// A partitioned run in one process: the partition `lpsim run --parts K` or `--partition-file` asks for, and
// the parts other than part 0, each a Simulation on its own thread (with its own copy of the network and the
// demand) serving part 0's requests over an in-process transport. Part 0 is the Run's own Simulation.
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/scenario.hpp"
#include "engine/simulation.hpp"
#include "partition/part_plan.hpp"
#include "transport/in_process_transport.hpp"

namespace lpsim {

/// The part of each edge for the run `config` asks for: the partition file's, or METIS/Leiden/random with
/// config.parts parts (the demand weighting the graph, as `lpsim partition` does), or fewer when the parts
/// would carry fewer than config.parts_min_vehicles vehicles each per step (said on stderr; a job of `ranks`
/// MPI ranks keeps its parts and is warned). Empty when the run is not partitioned. InputError for a bad
/// partition file or part count (file:line).
std::vector<int32_t> run_edge_parts(const ConfigSpec& config, const Scenario& sc, int ranks, int32_t* parts);

/// The vehicles on the road at a time on average, in free flow, by the routes of `sc`'s demand: the trips
/// departing while the run lasts, each for the mean free-flow time of a trip or until the run ends, over the
/// time from the first departure to the run's end, or to the last departure plus a mean trip when that comes
/// first.
double mean_vehicles_per_step(const Scenario& sc, const ConfigSpec& config);

/// InputError when --partition-method or --partition.load-from was given without --parts, or beside
/// --partition-file.
void refuse_split_options_without_parts(const ConfigSpec& config);

/// The longest vehicle of the demand's types, metres (how far back a vehicle's tail reaches).
double longest_vehicle(const Demand& demand);

class InProcessParts {
 public:
  /// Starts parts 1..K-1 of `plans` on their threads, each with `options` and its plan, from copies of `net`
  /// and `demand` (made before the constructor returns).
  InProcessParts(const Network& net, const Demand& demand, const SimulationOptions& options,
                 std::vector<PartPlan> plans, double timeout_s);
  /// Joins the parts (after part 0's Simulation is gone, which ends them; see finish()).
  ~InProcessParts();
  InProcessParts(const InProcessParts&) = delete;
  InProcessParts& operator=(const InProcessParts&) = delete;

  /// The options part 0's Simulation runs with.
  SimulationOptions part0_options(SimulationOptions options) const;
  /// After part 0's Simulation is destroyed: waits for the other parts. `part0_failed`: part 0 stopped with
  /// an error, so the others are released at once. Returns the first error of another part ("" if none).
  std::string finish(bool part0_failed);

 private:
  std::vector<PartPlan> plans_;
  InProcessFabric fabric_;
  std::vector<std::unique_ptr<Transport>> endpoints_;
  std::vector<std::thread> threads_;
  std::vector<std::string> errors_;
  bool finished_ = false;
};

/// Runs part0() (part 0's whole run) while `others` (null: none) serve it. An error in part 0 releases the
/// others at once and goes on (it names another part's failure when that is what stopped part 0); else the
/// others' first error, once they have ended, is thrown as std::runtime_error.
template <class Part0>
void run_part0(InProcessParts* others, Part0&& part0) {
  try {
    part0();
  } catch (const std::exception&) {
    if (others) others->finish(true);
    throw;
  }
  if (others) {
    const std::string cause = others->finish(false);
    if (!cause.empty()) throw std::runtime_error(cause);
  }
}

}  // namespace lpsim

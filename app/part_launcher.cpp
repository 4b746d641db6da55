#include "app/part_launcher.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "app/partitioned_parts.hpp"
#include "core/error.hpp"
#include "partition/part_plan.hpp"
#include "transport/mpi/mpi_transport.hpp"

namespace lpsim {
namespace {

// What ranks of one job must share to exchange their state as bytes: the version, the build, and the sizes
// of what crosses between them.
std::string build_id() {
  return std::string(LPSIM_BUILD_ID) + " vehicle " + std::to_string(sizeof(VehicleView)) + "/" +
         std::to_string(sizeof(TripRecord)) + "/" + std::to_string(sizeof(PartStats));
}

// One process: part 0 alone, or with parts 1..K-1 on threads, started anew for each simulation from their
// own copies of network and demand.
class LocalParts final : public PartLauncher {
 public:
  LocalParts(std::vector<PartPlan> plans, double timeout_s)
      : plans_(std::move(plans)), timeout_s_(timeout_s) {}

  bool leads() const override { return true; }

  void run_part0(const Network& net, const Demand& demand, const SimulationOptions& options,
                 const std::function<void(const SimulationOptions&)>& part0) override {
    if (plans_.size() <= 1) return part0(options);
    InProcessParts others(net, demand, options, plans_, timeout_s_);
    lpsim::run_part0(&others, [&] { part0(others.part0_options(options)); });
  }

  void serve(const Network&, Demand, const SimulationOptions&) override {
    throw std::logic_error("a single process runs part 0 itself");
  }

  Transport* ranks() const override { return nullptr; }

 private:
  std::vector<PartPlan> plans_;  // empty: one part
  double timeout_s_;
};

// Under mpirun: this rank's part, and the transport to the others.
class MpiRanks final : public PartLauncher {
 public:
  MpiRanks(const Scenario& sc, const std::vector<int32_t>& edge_part, int32_t parts, double timeout_s)
      : transport_(std::make_unique<MpiTransport>(timeout_s)) {
    transport_->check_same_build(build_id());
    plan_ = part_plan(sc.network, edge_part, parts, longest_vehicle(sc.demand), transport_->rank());
  }

  bool leads() const override { return transport_->rank() == 0; }

  void run_part0(const Network&, const Demand&, const SimulationOptions& options,
                 const std::function<void(const SimulationOptions&)>& part0) override {
    part0(rank_options(options));
  }

  void serve(const Network& net, Demand demand, const SimulationOptions& options) override {
    Simulation sim(net, std::move(demand), rank_options(options));
    sim.serve_part();
  }

  Transport* ranks() const override { return transport_.get(); }

 private:
  SimulationOptions rank_options(SimulationOptions options) const {
    options.part = &plan_;
    options.transport = transport_.get();
    options.gpu_device = MpiSession::local_rank();  // ranks on one machine take its GPUs in turn
    return options;
  }

  std::unique_ptr<Transport> transport_;
  PartPlan plan_;
};

}  // namespace

std::unique_ptr<PartLauncher> launch_parts(int ranks, const Scenario& sc,
                                           const std::vector<int32_t>& edge_part, int32_t parts,
                                           double timeout_s) {
  if (ranks > 1) return std::make_unique<MpiRanks>(sc, edge_part, parts, timeout_s);
  std::vector<PartPlan> plans;
  if (parts > 1) plans = part_plans(sc.network, edge_part, parts, longest_vehicle(sc.demand));
  return std::make_unique<LocalParts>(std::move(plans), timeout_s);
}

void require_one_part_per_rank(int ranks, int32_t parts) {
  if (ranks > 1 && parts != ranks)
    throw InputError("mpirun -n " + std::to_string(ranks) + " runs one part per rank: give --parts " +
                     std::to_string(ranks) + " or a partition file of " + std::to_string(ranks) +
                     " parts (not " + std::to_string(parts) + ")");
}

}  // namespace lpsim

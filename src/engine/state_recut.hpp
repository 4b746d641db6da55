#pragma once
// A saved state re-cut for other parts (a partitioned run resumed in another number of parts or another
// partition, or a run of one part resumed in parts, and back): part 0 reads every saved part's pieces, puts
// together the state of the whole network (what a run of one part would hold), and cuts it for the parts
// that resume (docs/ARCHITECTURE.md, "Checkpoints").
#include <vector>

#include "demand/demand.hpp"
#include "engine/saved_state.hpp"
#include "net/network.hpp"
#include "partition/part_plan.hpp"

namespace lpsim {

struct RecutScope {
  const Network& net;
  const Demand& demand;
  double longest_vehicle;  // what the plans of the parts were made for (part_plans)
};

/// `saved` cut for the parts whose plans are `to` (empty: a run of one part); std::runtime_error, naming the
/// part, for a saved part's state that does not read as one.
SavedState recut_state(const SavedState& saved, const RecutScope& scope, const std::vector<PartPlan>& to);

}  // namespace lpsim

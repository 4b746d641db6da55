#pragma once
// Settings a scenario gives that LPSim loads but does not model: each earns one warning line, so that a run
// never ignores them silently (a carFollowModel other than IDM or Krauss, a laneChangeModel other than the
// default, actuated signal programs run as static ones).
#include <string>
#include <vector>

#include "core/additional_spec.hpp"
#include "core/demand_spec.hpp"
#include "core/net_spec.hpp"

namespace lpsim {

/// The warning lines (without the "lpsim: warning: " prefix), one per model or signal type; empty if none.
/// default_car_follow_model: the model of vTypes that name none (SUMO's --default.carfollowmodel).
std::vector<std::string> unimplemented_settings(const DemandSpec& demand, const NetSpec& net,
                                                const AdditionalSpec& additional,
                                                const std::string& default_car_follow_model);

}  // namespace lpsim

#pragma once
#include <string>

#include "app/scenario.hpp"

namespace lpsim {

/// The text `lpsim info` prints: network and demand counts, what was skipped and why.
std::string describe_scenario(const Scenario& scenario);

/// One line naming every unsupported element kind that was skipped and how many, or "" if none.
std::string unsupported_summary(const Demand& demand);

}  // namespace lpsim

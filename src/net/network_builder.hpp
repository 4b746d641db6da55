#pragma once
#include <vector>

#include "core/net_spec.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Turns a NetSpec into the lane-map layout. Programs in `tl_overrides` (from add-files) replace the net's
/// program of the same tlLogic id. Raises InputError for inconsistent specs (unknown lane in a connection,
/// ...).
Network build_network(const NetSpec& spec, const std::vector<TlLogicSpec>& tl_overrides = {});

}  // namespace lpsim

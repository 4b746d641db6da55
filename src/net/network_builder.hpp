#pragma once
#include <string>
#include <vector>

#include "core/net_spec.hpp"
#include "net/network.hpp"

namespace lpsim {

/// What a network may ask for before it is refused: the lane map is sized by the lanes' lengths alone, so
/// an absurd length in a small file would otherwise allocate gigabytes.
struct NetworkLimits {
  double max_lane_map_gib = 0;      // the lane map's two buffers together, in GiB; 0: no limit of its own
  std::string max_lane_map_option;  // how the limit is set, for the message (e.g. "--max-lane-map-gb")
};

/// Turns a NetSpec into the lane-map layout. Programs in `tl_overrides` (from add-files) replace the net's
/// program of the same tlLogic id. Raises InputError for inconsistent specs (unknown lane in a connection,
/// ...) and for a lane map larger than `limits` allow.
Network build_network(const NetSpec& spec, const std::vector<TlLogicSpec>& tl_overrides = {},
                      const NetworkLimits& limits = {});

}  // namespace lpsim

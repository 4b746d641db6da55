#pragma once
#include "core/demand_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

struct DemandOptions {
  uint64_t seed = 23423;
  bool ignore_route_errors = false;  // as SUMO's --ignore-route-errors: skip unroutable/broken, report them
  int threads = 0;                   // routing threads; 0: all hardware threads
  double begin = 0, end = -1;        // flows are expanded within [begin, end) when end >= 0
};

/// Resolves types, distributions and routes, expands flows, routes trips (fastest free-flow path over lane
/// connections) and checks every route is connected. Raises InputError naming the vehicle and the bad id.
Demand build_demand(const DemandSpec& spec, const Network& net, const DemandOptions& options);

}  // namespace lpsim

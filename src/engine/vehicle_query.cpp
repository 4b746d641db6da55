#include "engine/vehicle_query.hpp"

#include <algorithm>

namespace lpsim {

int32_t VehicleQuery::slot(uint32_t v) const {
  int32_t slot = -1;
  for (auto it = std::lower_bound(keys_.begin(), keys_.end(), uint64_t{v} << 32);
       it != keys_.end() && (*it >> 32) == v; ++it) {
    const uint32_t k = static_cast<uint32_t>(*it);
    if (slot < 0 || s_.veh.route_pos[k] > s_.veh.route_pos[static_cast<uint32_t>(slot)])
      slot = static_cast<int32_t>(k);
  }
  return slot;
}

char VehicleQuery::link_state(uint32_t conn) const {
  const int32_t sig = net_.conn_signal[conn];
  if (sig < 0 || net_.conn_link_index[conn] < 0) return net_.conn_state[conn];
  if (parts_ != StateParts::Full)
    throw std::logic_error("a vehicle query reads the signals of the full state");
  return s_.link_state[engine_net_.link_begin[static_cast<size_t>(sig)] +
                       static_cast<uint32_t>(net_.conn_link_index[conn])];
}

}  // namespace lpsim

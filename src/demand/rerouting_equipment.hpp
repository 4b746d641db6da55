#pragma once
// Which vehicles SUMO equips with the rerouting device (MSDevice::equippedByDefaultAssignmentOptions): named
// in device.rerouting.explicit; else as their own, then their vType's, <param key="has.rerouting.device">
// says; else a draw below device.rerouting.probability (their vType's param of that name first); else not.
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/config_spec.hpp"
#include "core/demand_spec.hpp"
#include "demand/demand.hpp"

namespace lpsim {

class ReroutingEquipment {
 public:
  /// `types`: the demand's vehicle types, whose ids name the vTypes of `spec` that carry params.
  ReroutingEquipment(const ReroutingSpec& options, const DemandSpec& spec, const VehicleTypes& types,
                     uint64_t seed);

  /// Whether vehicle `id` (draw stream `stream`), the `loaded`-th vehicle in depart order (from 0), of type
  /// `type`, with its own has.rerouting.device param `own_param` (-1 none, 0 false, 1 true) gets the
  /// device. SUMO draws the probability from one generator in load order; here the draw is keyed by the seed
  /// and the vehicle, so that it depends on nothing else. With device.rerouting.deterministic, SUMO's quota:
  /// exactly the fraction, by the load counter.
  bool equipped(const std::string& id, uint64_t stream, uint32_t loaded, uint32_t type,
                int8_t own_param) const;

 private:
  double probability_;
  bool deterministic_;
  std::unordered_set<std::string> explicit_ids_;
  uint64_t seed_;
  std::vector<int8_t> type_param_;        // per type: has.rerouting.device (-1 none)
  std::vector<double> type_probability_;  // per type: its device.rerouting.probability param (-1 none)
};

}  // namespace lpsim

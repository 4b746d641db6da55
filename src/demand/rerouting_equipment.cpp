#include "demand/rerouting_equipment.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "demand/demand_draws.hpp"

namespace lpsim {
namespace {

// SUMO's StringUtils::toBool of a param's value (-1: neither true nor false: SUMO would fail on it, the
// route reader has vouched for the vehicles' own; a vType's odd value counts as not given).
int8_t sumo_bool(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  if (text == "1" || text == "yes" || text == "true" || text == "on" || text == "x") return 1;
  if (text == "0" || text == "no" || text == "false" || text == "off" || text == "-") return 0;
  return -1;
}

// SUMO's MSVehicleControl::getScalingQuota for a fraction below one: whether the `loaded`-th vehicle is in.
bool in_quota(double fraction, uint32_t loaded) {
  if (fraction < 0 || fraction >= 1) return fraction >= 1;
  constexpr uint64_t kResolution = 1000;
  const auto per_mille = static_cast<uint64_t>(std::floor(fraction * kResolution + 0.5));
  return ((loaded % kResolution) * per_mille) % kResolution < per_mille;
}

}  // namespace

ReroutingEquipment::ReroutingEquipment(const ReroutingSpec& options, const DemandSpec& spec,
                                       const VehicleTypes& types, uint64_t seed)
    : probability_(options.probability),
      deterministic_(options.deterministic),
      explicit_ids_(options.explicit_ids.begin(), options.explicit_ids.end()),
      seed_(seed),
      type_param_(types.size(), -1),
      type_probability_(types.size(), -1) {
  std::unordered_map<std::string, const VTypeSpec*> by_id;
  for (const VTypeSpec& t : spec.vtypes) by_id[t.id] = &t;
  for (uint32_t k = 0; k < types.size(); ++k) {
    const auto it = by_id.find(types.id[k]);
    if (it == by_id.end()) continue;
    const auto& params = it->second->params;
    if (const auto p = params.find("has.rerouting.device"); p != params.end())
      type_param_[k] = sumo_bool(p->second);
    if (const auto p = params.find("device.rerouting.probability"); p != params.end()) {
      try {
        type_probability_[k] = std::stod(p->second);
      } catch (const std::exception&) {
      }
    }
  }
}

bool ReroutingEquipment::equipped(const std::string& id, uint64_t stream, uint32_t loaded, uint32_t type,
                                  int8_t own_param) const {
  if (explicit_ids_.count(id) > 0) return true;
  if (own_param >= 0) return own_param == 1;
  if (type_param_[type] >= 0) return type_param_[type] == 1;
  double p = probability_;
  bool counted = deterministic_;
  if (type_probability_[type] >= 0) {
    p = type_probability_[type];
    counted = false;
  }
  if (p < 0) return false;
  if (counted) return in_quota(p, loaded);
  return rng_uniform_double(seed_, stream, kDrawReroutingDevice) < p;
}

}  // namespace lpsim

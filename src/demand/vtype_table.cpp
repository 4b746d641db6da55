#include "demand/vtype_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/vclass.hpp"
#include "demand/demand_draws.hpp"
#include "demand/emission_class.hpp"
#include "kernels/idm.hpp"

namespace lpsim {
namespace {

constexpr double kDefaultIdmDelta = 4.0;             // SUMO's IDM acceleration exponent
constexpr double kDefaultShutOffStopDuration = 300;  // s, SUMO's default of the vType param

// The vType param `key` as a finite number, `fallback` when absent.
double numeric_param(const VTypeSpec& spec, const std::string& key, double fallback) {
  auto it = spec.params.find(key);
  if (it == spec.params.end()) return fallback;
  const std::string& text = it->second;
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError(spec.loc, "invalid " + key + " '" + text + "' in vType '" + spec.id + "'");
  return value;
}

EmissionClass emission_class_of(const VTypeSpec& spec) {
  if (!spec.emission_class) return default_emission_class(spec.vclass);
  std::optional<EmissionClass> c = find_emission_class(*spec.emission_class);
  if (!c)
    throw InputError(spec.loc, "vType '" + spec.id + "': emissionClass '" + *spec.emission_class +
                                   "' does not exist (as SUMO 1.15 names them: HBEFA3/<class>, "
                                   "HBEFA2/<class> or a bare HBEFA2 class, Zero)");
  return *c;
}

}  // namespace

uint8_t simulated_car_follow_model(std::string_view name) {
  return name == "Krauss" ? kCarFollowKrauss : kCarFollowIdm;
}

VTypeTable::VTypeTable(const DemandSpec& spec, std::string default_model)
    : default_model_(std::move(default_model)) {
  const size_t n = spec.vtypes.size() + 1;
  types_.id.reserve(n);
  for (const auto& t : spec.vtypes) {
    if (types_.index.count(t.id)) throw InputError(t.loc, "duplicate vType id '" + t.id + "'");
    add_type(t);
  }
  dists_.reserve(spec.vtype_dists.size());
  for (const auto& d : spec.vtype_dists) {
    if (types_.index.count(d.id) || dist_index_.count(d.id))
      throw InputError(d.loc,
                       "vTypeDistribution id '" + d.id + "' is already used by a vType or distribution");
    if (d.members.empty()) throw InputError(d.loc, "vTypeDistribution '" + d.id + "' has no members");
    Distribution dist;
    double total = 0;
    for (const auto& m : d.members) {
      uint32_t type;
      if (auto it = types_.index.find(m.id); it != types_.index.end()) {
        type = it->second;
      } else if (m.id == kDefaultVTypeId) {
        type = default_type();
      } else {
        throw InputError(d.loc, "unknown vType '" + m.id + "' in vTypeDistribution '" + d.id + "'");
      }
      if (!(m.probability >= 0) || !std::isfinite(m.probability))
        throw InputError(d.loc,
                         "invalid probability of vType '" + m.id + "' in vTypeDistribution '" + d.id + "'");
      total += m.probability;
      dist.members.push_back(type);
      dist.cumulative.push_back(total);
    }
    if (!(total > 0)) throw InputError(d.loc, "vTypeDistribution '" + d.id + "' has only zero probabilities");
    dist_index_.emplace(d.id, static_cast<uint32_t>(dists_.size()));
    dists_.push_back(std::move(dist));
  }
}

uint32_t VTypeTable::add_type(const VTypeSpec& t) {
  const auto index = types_.size();
  types_.id.push_back(t.id);
  types_.length.push_back(static_cast<float>(t.length));
  types_.min_gap.push_back(static_cast<float>(t.min_gap));
  types_.accel.push_back(static_cast<float>(t.accel));
  types_.decel.push_back(static_cast<float>(t.decel));
  types_.emergency_decel.push_back(static_cast<float>(t.emergency_decel));
  types_.max_speed.push_back(static_cast<float>(t.max_speed));
  types_.desired_max_speed.push_back(static_cast<float>(
      std::min(t.desired_max_speed, static_cast<double>(std::numeric_limits<float>::max()))));
  types_.speed_factor.push_back(static_cast<float>(t.speed_factor));
  types_.speed_dev.push_back(static_cast<float>(t.speed_dev));
  types_.tau.push_back(static_cast<float>(t.tau));
  types_.sigma.push_back(static_cast<float>(t.sigma));
  types_.delta.push_back(static_cast<float>(numeric_param(t, "delta", kDefaultIdmDelta)));
  types_.vclass.push_back(t.vclass);
  const std::string& model = t.car_follow_model_given ? t.car_follow_model : default_model_;
  types_.car_follow_model.push_back(model);
  types_.model.push_back(simulated_car_follow_model(model));
  types_.vclass_mask.push_back(vehicle_vclass_mask(t.vclass));
  add_emission_columns(t);
  types_.index.emplace(t.id, index);
  return index;
}

void VTypeTable::add_emission_columns(const VTypeSpec& t) {
  const EmissionClass c = emission_class_of(t);
  types_.emission_class.push_back(c.name);
  types_.emission_model.push_back(c.model);
  for (int k = 0; k < kCoefficientsPerClass; ++k) types_.emission_coeff.push_back(c.coeff ? c.coeff[k] : 0.0);
  const VehicleBody body = vclass_body(t.vclass);
  const CoastingParams coasting =
      coasting_params(body.mass, t.width.value_or(body.width), t.height.value_or(body.height));
  types_.coast_incl.push_back(coasting.incl);
  types_.coast_mass_term.push_back(coasting.mass_term);
  types_.fuel_density.push_back(c.fuel_density);
  types_.shut_off_stop.push_back(numeric_param(t, "shutOffStopDuration", kDefaultShutOffStopDuration));
  types_.loc.push_back(t.loc);
}

uint32_t VTypeTable::default_type() {
  if (auto it = types_.index.find(kDefaultVTypeId); it != types_.index.end()) return it->second;
  VTypeSpec defaults;  // VTypeSpec's defaults are SUMO's passenger car
  defaults.id = kDefaultVTypeId;
  return add_type(defaults);
}

uint32_t VTypeTable::resolve(const std::string& type_ref, std::string_view vehicle_id, uint64_t seed,
                             uint64_t stream, const SourceLoc& loc) {
  if (type_ref.empty()) return default_type();
  if (auto it = types_.index.find(type_ref); it != types_.index.end()) return it->second;
  if (auto it = dist_index_.find(type_ref); it != dist_index_.end()) {
    const Distribution& d = dists_[it->second];
    return d.members[draw_weighted(d.cumulative, seed, stream, kDrawVTypeMember)];
  }
  if (type_ref == kDefaultVTypeId) return default_type();
  throw InputError(loc, "unknown vType '" + type_ref + "' for vehicle '" + std::string(vehicle_id) + "'");
}

float VTypeTable::speed_factor(uint32_t type, uint64_t seed, uint64_t stream) const {
  return static_cast<float>(
      draw_speed_factor(types_.speed_factor[type], types_.speed_dev[type], seed, stream));
}

}  // namespace lpsim

#include "converters/emission_mean_data.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "demand/emission_class.hpp"
#include "demand/vtype_table.hpp"

namespace lpsim {

namespace {

constexpr double kMaxTravelTime = 100000;  // SUMO's default maxTraveltime, s
constexpr int kEmissionDecimals = 6;
constexpr int kTimeDecimals = 2;  // SUMO's default --precision
// Attribute names in Pollutant order, then electricity.
constexpr const char* kPollutantNames[kNumPollutants] = {"CO", "CO2", "HC", "PMx", "NOx", "fuel"};
// Before each group of attributes after the first: SUMO breaks the element's line there.
constexpr const char* kContinuation = "\n           ";

void write_group(OutputFile& out, const char* suffix, const double (&values)[kNumPollutants]) {
  for (int p = 0; p < kNumPollutants; ++p)
    out.attr_real(std::string(kPollutantNames[p]) + suffix, values[p], kEmissionDecimals);
  out.text(std::string(" electricity") + suffix + "=\"0\"");
}

}  // namespace

EmissionTotals sum_emission_sums(const LaneCounters& c, uint32_t first_lane, uint32_t lanes) {
  // Integer sums first: exact and independent of the order lanes are visited.
  int64_t sums[kNumEmissionSums] = {};
  for (int k = 0; k < kNumEmissionSums; ++k)
    for (uint32_t l = first_lane; l < first_lane + lanes; ++l) sums[k] += c.emission[k][l];
  EmissionTotals t;
  t.sampled_seconds = static_cast<double>(sums[kEmissionMicroseconds]) / 1e6;
  t.travelled_m = static_cast<double>(sums[kEmissionMicrometres]) / 1e6;
  for (int p = 0; p < kNumPollutants; ++p) t.mass[p] = static_cast<double>(sums[emission_mass_sum(p)]) / 1e6;
  return t;
}

DefaultEmissionVehicle default_emission_vehicle(const Demand& demand, bool volumetric_fuel) {
  DefaultEmissionVehicle d;
  const VehicleTypes& t = demand.types;
  if (auto it = t.index.find(kDefaultVTypeId); it != t.index.end()) {
    const uint32_t k = it->second;
    d.model = t.emission_model[k];
    d.coeff = t.emission_coeff.data() + static_cast<size_t>(k) * kCoefficientsPerClass;
    d.coasting = CoastingParams{t.coast_incl[k], t.coast_mass_term[k]};
    d.fuel_divisor = volumetric_fuel ? kHbefaScale * t.fuel_density[k] : kHbefaScale;
    d.max_speed = t.max_speed[k];
    d.accel = t.accel[k];
    return d;
  }
  const VTypeSpec car;  // SUMO's passenger car defaults
  const EmissionClass c = default_emission_class(car.vclass);
  const VehicleBody body = vclass_body(car.vclass);
  d.model = c.model;
  d.coeff = c.coeff;
  d.coasting = coasting_params(body.mass, body.width, body.height);
  d.fuel_divisor = volumetric_fuel ? kHbefaScale * c.fuel_density : kHbefaScale;
  d.max_speed = car.max_speed;
  d.accel = car.accel;
  return d;
}

void write_emission_values(OutputFile& out, const EmissionTotals& t, double length, double speed_limit,
                           double interval_seconds, const DefaultEmissionVehicle* defaults) {
  const double S = t.sampled_seconds, D = t.travelled_m;
  out.attr_fixed("sampledSeconds", S, kTimeDecimals);
  write_group(out, "_abs", t.mass);
  out.text(kContinuation);
  double normed[kNumPollutants];
  for (int p = 0; p < kNumPollutants; ++p) normed[p] = t.mass[p] * 3600.0 / interval_seconds / length;
  write_group(out, "_normed", normed);
  double per_vehicle[kNumPollutants];
  double traveltime = -1;
  if (S > 0) {
    const double inf = std::numeric_limits<double>::infinity();
    traveltime = std::min(kMaxTravelTime, D > 0 ? length * S / D : inf);
    const double factor = std::min(kMaxTravelTime / S, D > 0 ? length / D : inf);
    for (int p = 0; p < kNumPollutants; ++p) per_vehicle[p] = t.mass[p] * factor;
  } else if (defaults != nullptr && speed_limit > 0) {
    traveltime = length / speed_limit;
    const double v = std::min(length / traveltime, defaults->max_speed), a = defaults->accel;
    double cruise[kNumPollutants], accelerating[kNumPollutants];
    emission_rates(defaults->model, defaults->coeff, defaults->coasting, v, 0.0, false,
                   defaults->fuel_divisor, cruise);
    emission_rates(defaults->model, defaults->coeff, defaults->coasting, v - a, a, false,
                   defaults->fuel_divisor, accelerating);
    for (int p = 0; p < kNumPollutants; ++p)
      per_vehicle[p] = (cruise[p] + accelerating[p]) * traveltime / 2.0;
  }
  if (traveltime >= 0) {
    out.text(kContinuation);
    out.attr_real("traveltime", traveltime, kTimeDecimals);
    write_group(out, "_perVeh", per_vehicle);
  }
  out.text("/>\n");
}

}  // namespace lpsim

#pragma once
// The values of an emissions edgeData/laneData entry (SUMO 1.15's MSMeanData_Emissions) from the emissions
// pass's integer sums (kernels/emission_step.hpp), written as SUMO writes them.
//
// For one edge (lanes summed; L = the length of its first lane) or one lane (L = its length) over an
// interval of T = end - begin seconds:
//   sampledSeconds  S = vehicle-seconds with some part of a vehicle on it; D = metres driven meanwhile
//   X_abs           = mass of pollutant X emitted on it, mg (fuel: mg, or ml with volumetric fuel)
//   X_normed        = X_abs * 3600 / T / L                    mg/h/m, which is g/h/km
//   traveltime      = min(L * S / D, 100000)                  s; only when S > 0 (as the perVeh values)
//   X_perVeh        = X_abs * min(100000 / S, L / D)          what one vehicle passing emits there
// X in CO, CO2, HC, PMx, NOx, fuel, then electricity (always 0). Emission values have 6 decimals, "0" when
// zero and scientific below 1e-6; sampledSeconds 2 decimals; traveltime 2 decimals, scientific below 0.01.
// With excludeEmpty="defaults" an empty entry (S = 0) gets the traveltime L / v of a vehicle at the speed
// limit v and the perVeh values of SUMO's default vehicle type driving through: (rate(v, 0) + rate(v - a, a))
// * traveltime / 2, v capped at its maximum speed and a its acceleration.
#include <cstdint>

#include "converters/output_file.hpp"
#include "demand/demand.hpp"
#include "engine/samples.hpp"
#include "kernels/emissions.hpp"

namespace lpsim {

/// The sums of one edge or lane over one interval, in SI units and mg.
struct EmissionTotals {
  double sampled_seconds = 0, travelled_m = 0;
  double mass[kNumPollutants] = {};
};

/// Sums lanes [first_lane, first_lane + lanes) of the emission columns of `counters`.
EmissionTotals sum_emission_sums(const LaneCounters& counters, uint32_t first_lane, uint32_t lanes);

/// What excludeEmpty="defaults" computes with: SUMO's DEFAULT_VEHTYPE (the scenario's own if it defines
/// one, else a passenger car of class HBEFA3/PC_G_EU4).
struct DefaultEmissionVehicle {
  uint8_t model = kEmissionZero;
  const double* coeff = nullptr;
  CoastingParams coasting{};
  double fuel_divisor = kHbefaScale;
  double max_speed = 0, accel = 0;  // m/s, m/s^2
};
DefaultEmissionVehicle default_emission_vehicle(const Demand& demand, bool volumetric_fuel);

/// Writes an entry's attributes after its id, and the end of its element. `defaults`: null unless
/// excludeEmpty="defaults"; `speed_limit` is read only for them.
void write_emission_values(OutputFile& out, const EmissionTotals& totals, double length, double speed_limit,
                           double interval_seconds, const DefaultEmissionVehicle* defaults);

}  // namespace lpsim

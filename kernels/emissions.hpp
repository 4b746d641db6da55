#pragma once
// Exhaust emissions and fuel use of one vehicle in one step as SUMO 1.15 computes them for its HBEFA3 and
// HBEFA2 emission classes: per pollutant a polynomial in speed and acceleration with the class's six
// coefficients (demand/hbefa_tables.cpp), nothing while the vehicle coasts (it decelerates more than rolling
// resistance and drag alone would brake it: the engine is cut off) and nothing while its engine is off at a
// long scheduled stop. Rates in mg/s (fuel in mg/s, or ml/s when fuel is measured by volume).
//
// Double precision, as SUMO: the polynomials add terms of 1e3..1e5 that cancel. Only IEEE-exact operations
// (+ - * / sqrt) with no fused multiply-add, so that the CPU and the GPU compute the same bits; the arcsine
// HBEFA2 needs is written out with them below (the two math libraries' asin may differ in the last bit).
#include <math.h>
#include <stdint.h>

#include "kernels/hd.hpp"

namespace lpsim {

/// The pollutants, in the order SUMO writes them (CO, CO2, HC, PMx, NOx, fuel; electricity is always 0 for
/// the models implemented here).
enum Pollutant : int {
  kPollutantCO,
  kPollutantCO2,
  kPollutantHC,
  kPollutantPMx,
  kPollutantNOx,
  kPollutantFuel,
  kNumPollutants
};
constexpr int kEmissionCoefficients = 6;  // c0..c5 of each pollutant's polynomial
constexpr int kCoefficientsPerClass = kNumPollutants * kEmissionCoefficients;

/// How a vehicle type's emissions are computed. kEmissionOther: a model LPSim does not implement (HBEFA4,
/// PHEMlight, Energy, ...); a run with an emissions output refuses it, so the step never meets one.
enum EmissionModel : uint8_t {
  kEmissionZero = 0,
  kEmissionHbefa3 = 1,
  kEmissionHbefa2 = 2,
  kEmissionHbefa2NoAccel = 3,  // HBEFA2's "A0" classes: the polynomial without its acceleration terms
  kEmissionOther = 4,
};

constexpr double kEmissionPi = 3.14159265358979323846;
constexpr double kHbefaGravity = 9.80665;       // m/s^2, SUMO's GRAVITY (HBEFA2's slope angle)
constexpr double kHbefaScale = 3.6;             // the tables give g/h: mg/s = value / 3.6
constexpr double kCoastingSpeedMin = 10 / 3.6;  // m/s: below it the cut-off shrinks linearly to 0
constexpr double kCoastingSpeedEps = 0.5;       // m/s: at or below it a vehicle never coasts

/// arcsin(x) for |x| <= 1 (larger |x| count as 1), from IEEE-exact operations only: the Taylor series up
/// to |x| = 1/2, beyond it arcsin(x) = pi/2 - 2 arcsin(sqrt((1 - x) / 2)); agrees with the math library to
/// within 2e-15 (tests/unit/emission_model_test.cpp).
LPSIM_HD double exact_asin(double x) {
  const double ax = x < -1.0 ? 1.0 : x > 1.0 ? 1.0 : x < 0 ? -x : x;
  const bool reflected = ax > 0.5;
  const double y = reflected ? sqrt((1.0 - ax) * 0.5) : ax;
  const double y2 = y * y;
  // Term n of the series is y^(2n+1) (2n)! / (4^n (n!)^2 (2n+1)); each from the last. At y <= 1/2 the 28th
  // term is below 2^-60 of the first.
  double term = y, sum = y;
  for (int n = 0; n < 28; ++n) {
    const double k = 2.0 * n + 1.0;
    term = term * y2 * (k * k) / ((k + 1.0) * (k + 2.0));
    sum = sum + term;
  }
  const double r = reflected ? kEmissionPi / 2.0 - 2.0 * sum : sum;
  return x < 0 ? -r : r;
}

/// A vehicle type's coasting cut-off (SUMO's PollutantsInterface::Helper::getCoastingDecel on a flat road):
/// `incl` = -9.05337017 A / m - 0.00017774 and `mass_term` = 1.066e-5 m, from the frontal area A (pi/4 width
/// height) and the vehicle class's mass m.
struct CoastingParams {
  double incl;
  double mass_term;
};

/// The deceleration (<= 0, m/s^2) below which a vehicle at speed v coasts: the rolling and air resistance at
/// v, and below 10 km/h that of 10 km/h scaled down linearly to 0 at standstill.
LPSIM_HD double coasting_decel(double v, const CoastingParams& c) {
  const double at = v < kCoastingSpeedMin ? kCoastingSpeedMin : v;
  double decel = c.incl * at + c.mass_term - 0.38347107 - 20.0 * c.incl;
  decel = decel < 0.0 ? decel : 0.0;
  return v < kCoastingSpeedMin ? v / kCoastingSpeedMin * decel : decel;
}

/// max(x, 0).
LPSIM_HD double positive_part(double x) { return x > 0.0 ? x : 0.0; }

/// Emission rates of one vehicle (mg/s; fuel divided by `fuel_divisor`: kHbefaScale for mg/s, kHbefaScale
/// times the fuel's density in mg/ml for ml/s) at speed v (m/s) and acceleration a (m/s^2), the step's new
/// speed and (new - old speed) / dt. `coeff`: the class's kCoefficientsPerClass coefficients.
LPSIM_HD void emission_rates(uint8_t model, const double* coeff, const CoastingParams& coasting, double v,
                             double a, bool engine_off, double fuel_divisor, double out[kNumPollutants]) {
  for (int p = 0; p < kNumPollutants; ++p) out[p] = 0.0;
  if (model == kEmissionZero || model == kEmissionOther || engine_off) return;
  if (v > kCoastingSpeedEps && a < coasting_decel(v, coasting)) return;
  if (model == kEmissionHbefa3) {
    for (int p = 0; p < kNumPollutants; ++p) {
      const double* f = coeff + p * kEmissionCoefficients;
      const double scale = p == kPollutantFuel ? fuel_divisor : kHbefaScale;
      out[p] = positive_part(
          (f[0] + f[1] * a * v + f[2] * a * a * v + f[3] * v + f[4] * v * v + f[5] * v * v * v) / scale);
    }
    return;
  }
  // HBEFA2: speed in km/h, acceleration as the angle (degrees) of the slope that would give it. An
  // acceleration beyond g has no such angle: SUMO's asin gives NaN there, which its max(rate, 0) turns to 0.
  const double kmh = v * 3.6;
  const bool accel_terms = model == kEmissionHbefa2;
  if (accel_terms && !(a <= kHbefaGravity && a >= -kHbefaGravity)) return;
  const double alpha = accel_terms ? exact_asin(a / kHbefaGravity) * 180.0 / kEmissionPi : 0.0;
  for (int p = 0; p < kNumPollutants; ++p) {
    const double* f = coeff + p * kEmissionCoefficients;
    const double scale = p == kPollutantFuel ? fuel_divisor : kHbefaScale;
    const double polynomial = accel_terms ? f[0] + f[1] * alpha * kmh + f[2] * alpha * alpha * kmh +
                                                f[3] * kmh + f[4] * kmh * kmh + f[5] * kmh * kmh * kmh
                                          : f[0] + f[3] * kmh + f[4] * kmh * kmh + f[5] * kmh * kmh * kmh;
    out[p] = positive_part(polynomial / scale);
  }
}

// Below this a time on a lane counts as none (SUMO's NUMERICAL_EPS) [s].
constexpr double kTimeOnLaneEps = 0.001;

/// Seconds of a step of `dt` in which a vehicle `length` long occupied a lane `lane_length` long with some
/// part of its body, its front having moved from `from` to `to` (metres from the lane's start, negative
/// before it) at constant speed (SUMO's meandata rule for the Euler update): the whole step, less the part
/// before the front entered and after the back left. 0 when it was never on the lane.
LPSIM_HD double time_on_lane(double from, double to, double length, double lane_length, double dt) {
  const double back_from = from - length, back_to = to - length;
  if (to < 0.0 || back_from > lane_length) return 0.0;
  double t = dt;
  if (from < 0.0) t -= dt * (0.0 - from) / (to - from);     // the front entered in the step
  if (back_from <= lane_length && lane_length < back_to) {  // the back left in the step
    t -= dt - dt * (lane_length - back_from) / (back_to - back_from);
    if (t < kTimeOnLaneEps && t > -kTimeOnLaneEps) t = 0.0;
  }
  return t > 0.0 ? t : 0.0;
}

}  // namespace lpsim

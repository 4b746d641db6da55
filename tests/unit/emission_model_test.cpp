// The emission model against SUMO 1.15 itself: rates of HBEFA3 and HBEFA2 classes as its emissionsMap prints
// them (6 significant digits), the coasting cut-off as measured inside sumo with TraCI (bisected to 2e-8
// m/s^2 for each vehicle class), the arcsine HBEFA2 computes with, the time a vehicle's body spends on a lane
// in a step at the lane's boundaries, and how emissionClass names resolve (what sumo 1.15 accepts and
// refuses).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "demand/emission_class.hpp"
#include "kernels/emissions.hpp"

namespace lpsim {
namespace {

struct MapPoint {
  const char* eclass;
  double v, a;
  int pollutant;
  double value;  // mg/s, as emissionsMap prints it
};

// emissionsMap -e CLASS --v-min 0 --v-max 30 --v-step 2.5 --a-min -1 --a-max 2 --a-step 0.5 (sumo 1.15): rows
// at (7.5, 1) and (15, 2) for every pollutant, (0, 0), (2.5, -0.5) and (30, 0) for CO2 and fuel.
constexpr MapPoint kMap[] = {
    {"HBEFA3/PC_G_EU4", 0, 0, kPollutantCO2, 2624.72},
    {"HBEFA3/PC_G_EU4", 0, 0, kPollutantFuel, 837.222},
    {"HBEFA3/PC_G_EU4", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA3/PC_G_EU4", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantCO, 85.0174},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantCO2, 4048.16},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantHC, 0.480903},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantPMx, 0.0699878},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantNOx, 1.67366},
    {"HBEFA3/PC_G_EU4", 7.5, 1, kPollutantFuel, 1291.19},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantCO, 150.944},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantCO2, 10264.7},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantHC, 0.936111},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantPMx, 0.217493},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantNOx, 4.41632},
    {"HBEFA3/PC_G_EU4", 15, 2, kPollutantFuel, 3273.93},
    {"HBEFA3/PC_G_EU4", 30, 0, kPollutantCO2, 5797.22},
    {"HBEFA3/PC_G_EU4", 30, 0, kPollutantFuel, 1849.06},
    {"HBEFA3/HDV", 0, 0, kPollutantCO2, 7380.56},
    {"HBEFA3/HDV", 0, 0, kPollutantFuel, 2321.67},
    {"HBEFA3/HDV", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA3/HDV", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA3/HDV", 7.5, 1, kPollutantCO, 35.0604},
    {"HBEFA3/HDV", 7.5, 1, kPollutantCO2, 25774.3},
    {"HBEFA3/HDV", 7.5, 1, kPollutantHC, 0},
    {"HBEFA3/HDV", 7.5, 1, kPollutantPMx, 4.23701},
    {"HBEFA3/HDV", 7.5, 1, kPollutantNOx, 219.858},
    {"HBEFA3/HDV", 7.5, 1, kPollutantFuel, 8107.92},
    {"HBEFA3/HDV", 15, 2, kPollutantCO, 87.6875},
    {"HBEFA3/HDV", 15, 2, kPollutantCO2, 73651.4},
    {"HBEFA3/HDV", 15, 2, kPollutantHC, 0},
    {"HBEFA3/HDV", 15, 2, kPollutantPMx, 9.82347},
    {"HBEFA3/HDV", 15, 2, kPollutantNOx, 585.16},
    {"HBEFA3/HDV", 15, 2, kPollutantFuel, 23169.2},
    {"HBEFA3/HDV", 30, 0, kPollutantCO2, 21988.9},
    {"HBEFA3/HDV", 30, 0, kPollutantFuel, 6916.67},
    {"HBEFA3/Bus", 0, 0, kPollutantCO2, 5286.11},
    {"HBEFA3/Bus", 0, 0, kPollutantFuel, 1671.11},
    {"HBEFA3/Bus", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA3/Bus", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA3/Bus", 7.5, 1, kPollutantCO, 37.0794},
    {"HBEFA3/Bus", 7.5, 1, kPollutantCO2, 23094.4},
    {"HBEFA3/Bus", 7.5, 1, kPollutantHC, 7.14438},
    {"HBEFA3/Bus", 7.5, 1, kPollutantPMx, 3.92799},
    {"HBEFA3/Bus", 7.5, 1, kPollutantNOx, 180.417},
    {"HBEFA3/Bus", 7.5, 1, kPollutantFuel, 7307.78},
    {"HBEFA3/Bus", 15, 2, kPollutantCO, 85.1644},
    {"HBEFA3/Bus", 15, 2, kPollutantCO2, 67881.9},
    {"HBEFA3/Bus", 15, 2, kPollutantHC, 12.9692},
    {"HBEFA3/Bus", 15, 2, kPollutantPMx, 9.19319},
    {"HBEFA3/Bus", 15, 2, kPollutantNOx, 492.458},
    {"HBEFA3/Bus", 15, 2, kPollutantFuel, 21481.9},
    {"HBEFA3/Bus", 30, 0, kPollutantCO2, 22561.1},
    {"HBEFA3/Bus", 30, 0, kPollutantFuel, 7142.78},
    {"HBEFA3/LDV_G_EU6", 0, 0, kPollutantCO2, 1228.61},
    {"HBEFA3/LDV_G_EU6", 0, 0, kPollutantFuel, 391.944},
    {"HBEFA3/LDV_G_EU6", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA3/LDV_G_EU6", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantCO, 132.413},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantCO2, 3776.31},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantHC, 0.581944},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantPMx, 0.188009},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantNOx, 0.857618},
    {"HBEFA3/LDV_G_EU6", 7.5, 1, kPollutantFuel, 1204.62},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantCO, 347.569},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantCO2, 10390.2},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantHC, 1.63194},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantPMx, 0.58366},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantNOx, 2.15968},
    {"HBEFA3/LDV_G_EU6", 15, 2, kPollutantFuel, 3314.41},
    {"HBEFA3/LDV_G_EU6", 30, 0, kPollutantCO2, 5686.61},
    {"HBEFA3/LDV_G_EU6", 30, 0, kPollutantFuel, 1813.84},
    {"HBEFA2/P_7_7", 0, 0, kPollutantCO2, 601.693},
    {"HBEFA2/P_7_7", 0, 0, kPollutantFuel, 189.51},
    {"HBEFA2/P_7_7", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA2/P_7_7", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantCO, 21.8706},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantCO2, 2572.94},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantHC, 0.747469},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantPMx, 0.212851},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantNOx, 4.83644},
    {"HBEFA2/P_7_7", 7.5, 1, kPollutantFuel, 810.376},
    {"HBEFA2/P_7_7", 15, 2, kPollutantCO, 132.186},
    {"HBEFA2/P_7_7", 15, 2, kPollutantCO2, 8105.89},
    {"HBEFA2/P_7_7", 15, 2, kPollutantHC, 2.68719},
    {"HBEFA2/P_7_7", 15, 2, kPollutantPMx, 1.08352},
    {"HBEFA2/P_7_7", 15, 2, kPollutantNOx, 18.0995},
    {"HBEFA2/P_7_7", 15, 2, kPollutantFuel, 2553.04},
    {"HBEFA2/P_7_7", 30, 0, kPollutantCO2, 5917.45},
    {"HBEFA2/P_7_7", 30, 0, kPollutantFuel, 1863.78},
    {"HBEFA2/P_A0_7_7", 0, 0, kPollutantCO2, 601.693},
    {"HBEFA2/P_A0_7_7", 0, 0, kPollutantFuel, 189.51},
    {"HBEFA2/P_A0_7_7", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA2/P_A0_7_7", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantCO, 0},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantCO2, 1418.29},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantHC, 0.296798},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantPMx, 0.0777552},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantNOx, 2.18657},
    {"HBEFA2/P_A0_7_7", 7.5, 1, kPollutantFuel, 446.707},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantCO, 0.408932},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantCO2, 2285.1},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantHC, 0.359155},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantPMx, 0.151299},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantNOx, 3.90816},
    {"HBEFA2/P_A0_7_7", 15, 2, kPollutantFuel, 719.719},
    {"HBEFA2/P_A0_7_7", 30, 0, kPollutantCO2, 5917.45},
    {"HBEFA2/P_A0_7_7", 30, 0, kPollutantFuel, 1863.78},
    {"HBEFA2/HDV_A0_12_3", 0, 0, kPollutantCO2, 1677.08},
    {"HBEFA2/HDV_A0_12_3", 0, 0, kPollutantFuel, 528.216},
    {"HBEFA2/HDV_A0_12_3", 2.5, -0.5, kPollutantCO2, 0},
    {"HBEFA2/HDV_A0_12_3", 2.5, -0.5, kPollutantFuel, 0},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantCO, 16.8119},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantCO2, 5695.54},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantHC, 6.67642},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantPMx, 3.09167},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantNOx, 59.4553},
    {"HBEFA2/HDV_A0_12_3", 7.5, 1, kPollutantFuel, 1793.87},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantCO, 21.9127},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantCO2, 9028.35},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantHC, 7.88428},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantPMx, 3.89464},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantNOx, 93.0567},
    {"HBEFA2/HDV_A0_12_3", 15, 2, kPollutantFuel, 2843.58},
    {"HBEFA2/HDV_A0_12_3", 30, 0, kPollutantCO2, 17970.5},
    {"HBEFA2/HDV_A0_12_3", 30, 0, kPollutantFuel, 5659.98},
};

EmissionClass class_named(const char* name) {
  std::optional<EmissionClass> c = find_emission_class(name);
  EXPECT_TRUE(c.has_value()) << name;
  return c.value_or(EmissionClass{});
}

// emissionsMap computes with the default vehicle's body (a passenger car) whatever the class.
CoastingParams passenger_coasting() { return coasting_params(1500, 1.8, 1.5); }

TEST(EmissionRates, MatchSumosEmissionsMap) {
  for (const MapPoint& m : kMap) {
    const EmissionClass c = class_named(m.eclass);
    double rate[kNumPollutants];
    emission_rates(c.model, c.coeff, passenger_coasting(), m.v, m.a, false, kHbefaScale, rate);
    // 6 significant digits printed: half a unit of the 6th digit, and the digit's own rounding.
    EXPECT_NEAR(rate[m.pollutant], m.value, std::abs(m.value) * 6e-6 + 1e-9)
        << m.eclass << " v=" << m.v << " a=" << m.a << " pollutant " << m.pollutant;
  }
}

TEST(EmissionRates, ZeroClassAndEngineOffEmitNothing) {
  double rate[kNumPollutants];
  const EmissionClass zero = class_named("Zero");
  emission_rates(zero.model, zero.coeff, passenger_coasting(), 10, 1, false, kHbefaScale, rate);
  for (const double r : rate) EXPECT_EQ(r, 0.0);
  const EmissionClass car = class_named("HBEFA3/PC_G_EU4");
  emission_rates(car.model, car.coeff, passenger_coasting(), 0, 0, true, kHbefaScale, rate);
  for (const double r : rate) EXPECT_EQ(r, 0.0);
  emission_rates(car.model, car.coeff, passenger_coasting(), 0, 0, false, kHbefaScale, rate);
  EXPECT_NEAR(rate[kPollutantCO2], 2624.72, 0.01);  // idling
}

TEST(EmissionRates, HbefaTwoAccelerationBeyondGravityEmitsNothingButTheA0ClassesDo) {
  double rate[kNumPollutants];
  const EmissionClass p77 = class_named("HBEFA2/P_7_7"), a0 = class_named("HBEFA2/P_A0_7_7");
  emission_rates(p77.model, p77.coeff, passenger_coasting(), 0.2, 10.5, false, kHbefaScale, rate);
  EXPECT_EQ(rate[kPollutantCO2], 0.0);  // sumo's asin gives NaN, its max(rate, 0) 0
  emission_rates(a0.model, a0.coeff, passenger_coasting(), 0.2, 10.5, false, kHbefaScale, rate);
  EXPECT_GT(rate[kPollutantCO2], 600.0);
}

TEST(EmissionRates, FuelByVolumeDividesByTheFuelsDensity) {
  // SUMO: diesel 836 mg/ml for HBEFA3 classes with "_D_", petrol 742 for the others (HDV, Bus and Coach
  // included), 790 for every HBEFA2 class.
  EXPECT_EQ(class_named("HBEFA3/PC_D_EU6").fuel_density, 836);
  EXPECT_EQ(class_named("HBEFA3/HDV").fuel_density, 742);
  EXPECT_EQ(class_named("HBEFA3/PC_G_EU4").fuel_density, 742);
  EXPECT_EQ(class_named("HBEFA2/HDV_12_3").fuel_density, 790);
  const EmissionClass car = class_named("HBEFA3/PC_G_EU4");
  double mass[kNumPollutants], volume[kNumPollutants];
  emission_rates(car.model, car.coeff, passenger_coasting(), 15, 2, false, kHbefaScale, mass);
  emission_rates(car.model, car.coeff, passenger_coasting(), 15, 2, false, kHbefaScale * 742, volume);
  EXPECT_NEAR(volume[kPollutantFuel], mass[kPollutantFuel] / 742, 1e-9);
  EXPECT_EQ(volume[kPollutantCO2], mass[kPollutantCO2]);
}

struct CoastingPoint {
  const char* vclass;
  double width, height;
  double v, decel;  // m/s, m/s^2 (measured)
};

// coast_sim.py: sumo 1.15 with TraCI (speedMode 0), the largest deceleration that still emits, per vClass.
constexpr CoastingPoint kCoasting[] = {
    {"passenger", 1.8, 1.5, 1.0, -0.051838},  {"passenger", 1.8, 1.5, 10.0, -0.237715},
    {"passenger", 1.8, 1.5, 20.0, -0.367481}, {"passenger", 1.8, 1.5, 30.0, -0.497247},
    {"bus", 2.5, 3.4, 5.0, -0.179976},        {"bus", 2.5, 3.4, 20.0, -0.303521},
    {"truck", 2.4, 2.4, 2.0, -0.139471},      {"truck", 2.4, 2.4, 15.0, -0.237597},
    {"trailer", 2.55, 4.0, 10.0, -0.173442},  {"delivery", 2.16, 2.86, 10.0, -0.240542},
    {"motorcycle", 0.9, 1.5, 10.0, 0.0},      {"motorcycle", 0.9, 1.5, 20.0, -0.381339},
    {"moped", 0.78, 1.7, 15.0, 0.0},          {"coach", 2.6, 4.0, 15.0, -0.223850},
    {"passenger", 3.0, 1.5, 5.0, -0.044842},  // a vType's own width
};

TEST(EmissionRates, CoastingCutOffMatchesSumo) {
  for (const CoastingPoint& c : kCoasting) {
    const VehicleBody body = vclass_body(c.vclass);
    const CoastingParams p = coasting_params(body.mass, c.width, c.height);
    EXPECT_NEAR(coasting_decel(c.v, p), c.decel, 1e-6) << c.vclass << " v=" << c.v;
  }
  // Below the cut-off nothing is emitted; at or below 0.5 m/s a vehicle never coasts.
  const EmissionClass car = class_named("HBEFA3/PC_G_EU4");
  double rate[kNumPollutants];
  emission_rates(car.model, car.coeff, passenger_coasting(), 10, -0.2378, false, kHbefaScale, rate);
  EXPECT_EQ(rate[kPollutantCO2], 0.0);
  emission_rates(car.model, car.coeff, passenger_coasting(), 10, -0.2376, false, kHbefaScale, rate);
  EXPECT_GT(rate[kPollutantCO2], 0.0);
  emission_rates(car.model, car.coeff, passenger_coasting(), 0.5, -4.5, false, kHbefaScale, rate);
  EXPECT_GT(rate[kPollutantCO2], 0.0);
}

TEST(EmissionRates, ExactArcsineAgreesWithTheMathLibrary) {
  for (double x = -1.0; x <= 1.0; x += 1.0 / 512) EXPECT_NEAR(exact_asin(x), std::asin(x), 2e-15) << x;
  EXPECT_NEAR(exact_asin(0.49999), std::asin(0.49999), 2e-15);
  EXPECT_NEAR(exact_asin(0.50001), std::asin(0.50001), 2e-15);
  EXPECT_EQ(exact_asin(0.0), 0.0);
}

TEST(EmissionTimeOnLane, WholeStepsAndBoundaryCrossings) {
  // A 5 m vehicle on a 100 m lane, steps of 1 s.
  EXPECT_DOUBLE_EQ(time_on_lane(10, 20, 5, 100, 1), 1.0);    // within the lane
  EXPECT_DOUBLE_EQ(time_on_lane(50, 50, 5, 100, 1), 1.0);    // standing
  EXPECT_DOUBLE_EQ(time_on_lane(3, 13, 5, 100, 1), 1.0);     // the back still before the lane's start
  EXPECT_DOUBLE_EQ(time_on_lane(-2, 8, 5, 100, 1), 0.8);     // the front entered after 0.2 s
  EXPECT_DOUBLE_EQ(time_on_lane(100, 110, 5, 100, 1), 0.5);  // the back left after 0.5 s
  EXPECT_DOUBLE_EQ(time_on_lane(-4, 106, 5, 100, 1), 1.0 - 4.0 / 110 - 1.0 / 110);  // both
  EXPECT_DOUBLE_EQ(time_on_lane(-10, -1, 5, 100, 1), 0.0);                          // not there yet
  EXPECT_DOUBLE_EQ(time_on_lane(106, 120, 5, 100, 1), 0.0);                         // gone already
  EXPECT_DOUBLE_EQ(time_on_lane(-3, 7, 5, 100, 0.5), 0.35);                         // half-second steps
  // The back leaves within SUMO's NUMERICAL_EPS of the step's start: nothing.
  EXPECT_DOUBLE_EQ(time_on_lane(104.9995, 114.9995, 5, 100, 1), 0.0);
}

TEST(EmissionClassNames, ResolveAsSumo115Does) {
  const std::pair<const char*, const char*> accepted[] = {
      {"HBEFA3/PC_G_EU4", "HBEFA3/PC_G_EU4"},
      {"HBEFA3/pc_g_eu4", "HBEFA3/PC_G_EU4"},
      {"HBEFA3/hdv", "HBEFA3/HDV"},
      {"HBEFA3/unknown", "HBEFA3/PC_G_EU4"},
      {"HBEFA3/Default", "HBEFA3/PC_G_EU4"},
      {"HBEFA3/zero", "Zero/default"},
      {"HBEFA3", "HBEFA3/PC_G_EU4"},
      {"HBEFA2", "HBEFA2/P_7_7"},
      {"P_7_7", "HBEFA2/P_7_7"},
      {"p_7_7", "HBEFA2/P_7_7"},
      {"unknown", "HBEFA2/P_7_7"},
      {"Default", "HBEFA2/P_7_7"},
      {"P_A0_7_7", "HBEFA2/P_A0_7_7"},
      {"HBEFA2/p_a0_7_7", "HBEFA2/P_A0_7_7"},
      {"HBEFA2/zero", "Zero/default"},
      {"zero", "Zero/default"},
      {"Zero", "Zero/default"},
      {"Zero/default", "Zero/default"},
      {"Zero/Unknown", "Zero/default"},
      {"Zero/zero", "Zero/default"},
  };
  for (const auto& [given, name] : accepted) EXPECT_EQ(class_named(given).name, name) << given;
  for (const char* refused :
       {"foo", "PC_G_EU4", "HBEFA3/foo", "HBEFA2/foo", "hbefa3/PC_G_EU4", "HBEFA3/ZERO", "ZERO", "hbefa3",
        "Zero/ZERO", "zero/default", "Zero/foo", "", " HBEFA3/PC_G_EU4", "Foo/bar"})
    EXPECT_FALSE(find_emission_class(refused).has_value()) << "'" << refused << "'";
  // Models LPSim does not implement load (an emissions output refuses them).
  for (const char* other : {"HBEFA4/PC_petrol_Euro-4", "HBEFA4", "PHEMlight/PC_G_EU4", "PHEMlight5/x",
                            "Energy/unknown", "Energy", "MMPEVEM/unknown"})
    EXPECT_EQ(class_named(other).model, kEmissionOther) << other;
  EXPECT_EQ(class_named("HBEFA2/HDV_A0_12_3").model, kEmissionHbefa2NoAccel);
  EXPECT_EQ(class_named("HBEFA2/HDV_12_3").model, kEmissionHbefa2);
}

TEST(EmissionClassNames, VehicleClassDefaultsAsSumo115) {
  const std::pair<const char*, const char*> defaults[] = {
      {"passenger", "HBEFA3/PC_G_EU4"},  {"taxi", "HBEFA3/PC_G_EU4"},
      {"ignoring", "HBEFA3/PC_G_EU4"},   {"delivery", "HBEFA3/LDV"},
      {"emergency", "HBEFA3/LDV"},       {"truck", "HBEFA3/HDV"},
      {"trailer", "HBEFA3/HDV"},         {"bus", "HBEFA3/Bus"},
      {"coach", "HBEFA3/Coach"},         {"motorcycle", "HBEFA3/LDV_G_EU6"},
      {"moped", "HBEFA3/LDV_G_EU6"},     {"rail", "HBEFA3/HDV_D_EU0"},
      {"ship", "HBEFA3/HDV_D_EU0"},      {"bicycle", "Zero/default"},
      {"evehicle", "Zero/default"},      {"tram", "Zero/default"},
      {"rail_electric", "Zero/default"},
  };
  for (const auto& [vclass, name] : defaults) EXPECT_EQ(default_emission_class(vclass).name, name) << vclass;
}

}  // namespace
}  // namespace lpsim

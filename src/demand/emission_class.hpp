#pragma once
// Emission classes as SUMO 1.15 names them (a vType's emissionClass, or its vehicle class's default) and
// the vehicle body the coasting cut-off reads (kernels/emissions.hpp).
#include <optional>
#include <string>
#include <string_view>

#include "kernels/emissions.hpp"

namespace lpsim {

struct EmissionClass {
  uint8_t model = kEmissionZero;  // EmissionModel
  // SUMO's name of the class ("HBEFA3/PC_G_EU4", "HBEFA2/P_7_7", "Zero/default"); for a model LPSim does
  // not implement (kEmissionOther) the text as given.
  std::string name = "Zero/default";
  const double* coeff = nullptr;  // kCoefficientsPerClass coefficients; null for Zero and other models
  double fuel_density = 742;      // mg/ml, for fuel by volume: petrol 742, diesel 836 (HBEFA3 "_D_" classes),
                                  // 790 for every HBEFA2 class (as SUMO)
};

/// The class an emissionClass attribute names, as SUMO 1.15 reads it: "<model>/<class>" with the model
/// HBEFA3, HBEFA2 or Zero (case-sensitive) and the class any case; "unknown" or "default" (any case) for the
/// model's default (PC_G_EU4, P_7_7) and "zero" for Zero/default; no model: "zero"/"Zero", a bare model name
/// for its default, else an HBEFA2 class. The models HBEFA4, PHEMlight, PHEMlight5, Energy and MMPEVEM exist
/// (kEmissionOther, any class name accepted) but are not implemented. nullopt where SUMO refuses the name.
std::optional<EmissionClass> find_emission_class(std::string_view text);

/// The class of a vType of vehicle class `vclass` that names none (SUMO 1.15's vClass defaults).
EmissionClass default_emission_class(std::string_view vclass);

/// What the coasting cut-off reads of a vehicle class: its default mass (which a vType cannot change in
/// SUMO 1.15) and default width and height (which it can).
struct VehicleBody {
  double mass, width, height;  // kg, m, m
};
VehicleBody vclass_body(std::string_view vclass);

/// The cut-off of a vehicle of `mass` with a frontal area of pi/4 * width * height.
CoastingParams coasting_params(double mass, double width, double height);

}  // namespace lpsim

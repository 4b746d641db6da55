#pragma once
// The HBEFA emission factor tables (hbefa_tables.cpp): data only, looked up by demand/emission_class.
#include <cstddef>
#include <span>

#include "kernels/emissions.hpp"

namespace lpsim {

/// One emission class: its name as SUMO spells it, and the coefficients c0..c5 of each pollutant
/// (Pollutant order), in the units of its model (kernels/emissions.hpp).
struct HbefaClass {
  const char* name;
  double coeff[kNumPollutants][kEmissionCoefficients];
};

/// HBEFA3's 45 classes and HBEFA2's 84 (42, and the same 42 as "A0" classes without acceleration terms).
std::span<const HbefaClass> hbefa3_classes();
std::span<const HbefaClass> hbefa2_classes();

}  // namespace lpsim

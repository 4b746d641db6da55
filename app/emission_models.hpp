#pragma once
// The check an emissions output needs of the vehicle types: every type's emission class must be of a model
// LPSim computes (HBEFA3, HBEFA2, Zero). A class of another of SUMO's models (HBEFA4, PHEMlight, Energy, ...)
// loads, as it cannot act until emissions are asked for.
#include "core/additional_spec.hpp"
#include "demand/demand.hpp"

namespace lpsim {

/// An InputError naming the first vType (file:line) whose class LPSim does not implement and the emissions
/// edgeData/laneData `output` that asks for it.
void check_emission_models(const VehicleTypes& types, const MeanDataSpec& output);

}  // namespace lpsim

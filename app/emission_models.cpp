#include "app/emission_models.hpp"

#include "core/error.hpp"
#include "kernels/emissions.hpp"

namespace lpsim {

void check_emission_models(const VehicleTypes& types, const MeanDataSpec& output) {
  for (uint32_t k = 0; k < types.size(); ++k) {
    if (types.emission_model[k] != kEmissionOther) continue;
    throw InputError(types.loc[k], "vType '" + types.id[k] + "': emissionClass '" + types.emission_class[k] +
                                       "' is of a model LPSim does not implement (it computes HBEFA3, HBEFA2 "
                                       "and Zero classes), and " +
                                       (output.lane_level ? "laneData '" : "edgeData '") + output.id + "' (" +
                                       output.loc.str() + ") asks for emissions");
  }
}

}  // namespace lpsim

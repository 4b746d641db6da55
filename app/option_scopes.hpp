#pragma once
// SUMO options that act only on something a scenario may lack (ConfigSpec::scoped_options): decided once
// the scenario's files are read. An option that would act here is refused, as an option LPSim does not model
// that would change the results; one that cannot act here is named in one warning, with why.
//  - BidiEdges (time-to-teleport.bidi): acts where a road edge has a bidi partner.
//  - ReroutingDevice: the rerouting device's options LPSim does not implement. bike-speeds acts where the
//    scenario has bicycles; with-taz (LPSim leaves TAZ trips out), init-with-loaded-weights (no weight files)
//    and railsignal (no rail vehicles) never act.
//  - ParkingAreaStops (parking.maneuver): acts where a vehicle stops at a parkingArea.
//  - Persons (pedestrian.*, persontrip.*, person-device.*, ride.stop-tolerance): acts where the scenario has
//    persons or containers; pedestrian.model nonInteracting never acts (LPSim's persons never meet its
//    vehicles).
#include <string>

#include "core/config_spec.hpp"
#include "core/demand_spec.hpp"
#include "core/net_spec.hpp"

namespace lpsim {

/// InputError at the option's file:line for the first scoped option that acts in this scenario; else the
/// warning line naming those that cannot act here and why ("" when none was given).
std::string decide_scoped_options(const ConfigSpec& config, const NetSpec& net, const DemandSpec& demand);

}  // namespace lpsim

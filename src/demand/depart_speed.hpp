#pragma once
// SUMO's check of a departSpeed given as a number, made when the demand is built: a speed above what the
// vehicle type allows is refused, and one above what the first edge allows at the vehicle's speed factor is
// refused too, unless the type's speed factor varies (speedDev > 0): then the vehicle gets the speed factor
// that allows it, as SUMO 1.15 does ("Choosing new speed factor ... to match departure speed").
#include <cstdint>
#include <string>

#include "core/demand_spec.hpp"
#include "demand/demand.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Slack SUMO 1.15 leaves above both limits (measured: maxSpeed 10 takes 10.0099 and refuses 10.011).
inline constexpr double kDepartSpeedSlack = 0.01;

/// The speed factor the vehicle departs with: `speed_factor`, or the raised one when a given departSpeed
/// needs it. Raises InputError at `loc` naming the vehicle, the speed and the type or edge it exceeds.
float depart_speed_factor(const VehicleTypes& types, uint32_t type, float speed_factor, const DepartSpec& ds,
                          const Network& net, uint32_t first_edge, const std::string& vehicle_id,
                          const SourceLoc& loc);

}  // namespace lpsim

#pragma once
#include <string_view>

#include "core/error.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Maps a SUMO junction type string onto the engine's JunctionType.
///   traffic_light, traffic_light_unregulated, traffic_light_right_on_red -> TrafficLight
///   priority -> Priority; priority_stop -> PriorityStop; allway_stop -> AllwayStop; zipper -> Zipper
///   right_before_left, left_before_right -> RightBeforeLeft (who yields to whom is in the connection
///     states m/M, so one "equal-rank" type serves both driving sides)
///   dead_end -> DeadEnd; internal -> Internal; unregulated -> Unregulated
///   rail_signal, rail_crossing, district -> Other (no car-relevant control of their own)
///   "" -> Priority (readers without a type, e.g. LPSim CSV; netconvert's default too)
/// Any other string raises InputError at `where` naming the junction and the type.
JunctionType parse_junction_type(std::string_view type, const SourceLoc& where, std::string_view junction_id);

/// The SUMO name of a JunctionType (the first of the names mapped onto it; "other" for Other).
const char* junction_type_name(JunctionType type);

}  // namespace lpsim

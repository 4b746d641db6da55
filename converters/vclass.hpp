#pragma once
// SUMO vehicle-class permissions (lane/edge allow and disallow lists), reduced to the one question LPSim
// asks: may a passenger car use this lane?
#include <string_view>

namespace lpsim {

/// True when `list` (space-separated SUMO vClass names) names passenger cars: "passenger" or "all".
bool vclass_list_names_passenger(std::string_view list);

/// SUMO 1.15 semantics of a lane's allow/disallow pair, for vClass "passenger":
/// - neither given (or both empty): every class may use the lane;
/// - allow given: allowed iff the list names passenger cars ("passenger" or "all"); when both lists are
///   given SUMO uses allow and ignores disallow, and so do we;
/// - only disallow given: allowed unless the list names passenger cars.
/// "private" is SUMO's own class SVC_PRIVATE (vehicles with private access), not an alias of passenger:
/// allow="private" alone keeps cars out, disallow="private" lets them in. Unknown names are ignored
/// rather than rejected, so nets written by newer SUMO versions with extra classes still load.
bool passenger_allowed(std::string_view allow, std::string_view disallow);

}  // namespace lpsim

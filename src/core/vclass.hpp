#pragma once
// SUMO vehicle classes as bits of a 32-bit mask: a lane's permissions (its allow/disallow lists) and a
// vehicle type's vClass are both masks, and a type may use a lane when the two share a bit. SUMO 1.15 knows
// the 26 classes below (custom1/2 included); "ignoring" is not a class but a vType that every lane admits,
// so its mask has every bit set.
#include <array>
#include <cstdint>
#include <string_view>

namespace lpsim {

/// Class names in bit order (bit k is kVClassNames[k]).
inline constexpr std::array<std::string_view, 26> kVClassNames{
    "private",       "emergency", "authority", "army",     "vip",      "pedestrian", "passenger",
    "hov",           "taxi",      "bus",       "coach",    "delivery", "truck",      "trailer",
    "motorcycle",    "moped",     "bicycle",   "evehicle", "tram",     "rail_urban", "rail",
    "rail_electric", "rail_fast", "ship",      "custom1",  "custom2"};

inline constexpr uint32_t kAllVClasses = (1u << kVClassNames.size()) - 1u;

/// Bit of class `name`, 0 for an unknown name.
constexpr uint32_t vclass_name_bit(std::string_view name) {
  for (size_t k = 0; k < kVClassNames.size(); ++k)
    if (kVClassNames[k] == name) return 1u << k;
  return 0;
}

inline constexpr uint32_t kVClassPassenger = vclass_name_bit("passenger");
inline constexpr uint32_t kVClassPedestrian = vclass_name_bit("pedestrian");

/// The mask a vehicle of vType class `vclass` asks lanes for: its bit; every bit for "ignoring"; passenger
/// for an empty or unknown name (as the readers default a vType's class to passenger).
constexpr uint32_t vehicle_vclass_mask(std::string_view vclass) {
  if (vclass == "ignoring") return kAllVClasses;
  const uint32_t bit = vclass_name_bit(vclass);
  return bit != 0 ? bit : kVClassPassenger;
}

/// Mask of a space-separated list of class names; "all" names every class. Unknown names are ignored, so
/// nets written by newer SUMO versions with extra classes still load.
constexpr uint32_t vclass_list_mask(std::string_view list) {
  uint32_t mask = 0;
  size_t i = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (i < list.size()) {
    while (i < list.size() && space(list[i])) ++i;
    const size_t start = i;
    while (i < list.size() && !space(list[i])) ++i;
    const std::string_view name = list.substr(start, i - start);
    mask |= name == "all" ? kAllVClasses : vclass_name_bit(name);
  }
  return mask;
}

/// A lane's permissions from its allow/disallow pair, as SUMO 1.15 reads them: allow given (non-blank):
/// exactly those classes (disallow is then ignored); only disallow given: every class but those; neither:
/// every class.
constexpr uint32_t lane_permissions(std::string_view allow, std::string_view disallow) {
  auto blank = [](std::string_view s) {
    for (char c : s)
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return false;
    return true;
  };
  if (!blank(allow)) return vclass_list_mask(allow);
  if (!blank(disallow)) return kAllVClasses & ~vclass_list_mask(disallow);
  return kAllVClasses;
}

/// Classes that are not road vehicles: pedestrians, rail vehicles and ships. LPSim simulates road traffic.
inline constexpr uint32_t kNonRoadVClasses =
    kVClassPedestrian | vclass_name_bit("tram") | vclass_name_bit("rail_urban") | vclass_name_bit("rail") |
    vclass_name_bit("rail_electric") | vclass_name_bit("rail_fast") | vclass_name_bit("ship");

/// Whether a vClass mask includes a road vehicle class ("ignoring" does).
constexpr bool road_vclass(uint32_t mask) { return (mask & ~kNonRoadVClasses) != 0; }

/// Whether LPSim keeps a lane of these permissions: every lane some road vehicle may use (with all its
/// classes, trams on a shared lane included). Sidewalks, rail tracks, waterways and closed lanes are
/// dropped.
constexpr bool vehicle_lane(uint32_t permissions) { return road_vclass(permissions); }

}  // namespace lpsim

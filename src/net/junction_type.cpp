#include "net/junction_type.hpp"

#include <string>
#include <utility>

namespace lpsim {

JunctionType parse_junction_type(std::string_view type, const SourceLoc& where,
                                 std::string_view junction_id) {
  static constexpr std::pair<std::string_view, JunctionType> kTypes[] = {
      {"", JunctionType::Priority},
      {"priority", JunctionType::Priority},
      {"traffic_light", JunctionType::TrafficLight},
      {"traffic_light_unregulated", JunctionType::TrafficLight},
      {"traffic_light_right_on_red", JunctionType::TrafficLight},
      {"priority_stop", JunctionType::PriorityStop},
      {"right_before_left", JunctionType::RightBeforeLeft},
      {"left_before_right", JunctionType::RightBeforeLeft},
      {"allway_stop", JunctionType::AllwayStop},
      {"zipper", JunctionType::Zipper},
      {"dead_end", JunctionType::DeadEnd},
      {"internal", JunctionType::Internal},
      {"unregulated", JunctionType::Unregulated},
      {"rail_signal", JunctionType::Other},
      {"rail_crossing", JunctionType::Other},
      {"district", JunctionType::Other},
  };
  for (const auto& [name, value] : kTypes)
    if (name == type) return value;
  throw InputError(
      where, "junction '" + std::string(junction_id) + "' has unknown type '" + std::string(type) + "'");
}

const char* junction_type_name(JunctionType t) {
  switch (t) {
    case JunctionType::Priority:
      return "priority";
    case JunctionType::TrafficLight:
      return "traffic_light";
    case JunctionType::RightBeforeLeft:
      return "right_before_left";
    case JunctionType::AllwayStop:
      return "allway_stop";
    case JunctionType::PriorityStop:
      return "priority_stop";
    case JunctionType::Zipper:
      return "zipper";
    case JunctionType::DeadEnd:
      return "dead_end";
    case JunctionType::Internal:
      return "internal";
    case JunctionType::Unregulated:
      return "unregulated";
    case JunctionType::Other:
      return "other";
  }
  return "other";
}

}  // namespace lpsim

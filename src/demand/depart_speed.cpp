#include "demand/depart_speed.hpp"

#include <cstdio>

namespace lpsim {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

float depart_speed_factor(const VehicleTypes& types, uint32_t type, float speed_factor, const DepartSpec& ds,
                          const Network& net, uint32_t first_edge, const std::string& vehicle_id,
                          const SourceLoc& loc) {
  if (ds.speed != DepartSpeed::Given) return speed_factor;
  const double speed = ds.speed_value;
  const std::string what =
      "departSpeed " + number(speed) + " of vehicle '" + vehicle_id + "' is too high for ";
  if (speed > types.max_speed[type] + kDepartSpeedSlack)
    throw InputError(
        loc, what + "its vType '" + types.id[type] + "' (maxSpeed " + number(types.max_speed[type]) + ")");
  // SUMO takes the limit of the edge's first lane; here the first car lane (lanes of an edge share it in
  // practice).
  const double lane_speed = net.lane_speed[net.edge_first_lane[first_edge]];
  if (speed <= lane_speed * speed_factor + kDepartSpeedSlack) return speed_factor;
  if (types.speed_dev[type] > 0) return static_cast<float>(speed / lane_speed);
  throw InputError(loc, what + "its departure edge '" + net.edge_id[first_edge] + "' (speed limit " +
                            number(lane_speed) + " m/s times the speed factor " + number(speed_factor) +
                            "; vType '" + types.id[type] + "' has speedDev 0, so the factor cannot rise)");
}

}  // namespace lpsim

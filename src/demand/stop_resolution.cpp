#include "demand/stop_resolution.hpp"

#include <cmath>

namespace lpsim {
namespace {

// SUMO's POSITION_EPS: positions this close to a lane's ends are on it.
constexpr double kPositionEps = 0.1;

// A position as SUMO reads it on a lane of `length` m: negative values count from the end.
double on_lane(double pos, double length) { return pos < 0 ? length + pos : pos; }

}  // namespace

StopResolver::StopResolver(const DemandSpec& spec, const Network& net) : net_(net) {
  for (const StoppingPlaceSpec& p : spec.stopping_places) {
    const uint32_t lane = lane_of(p.lane, p.loc, "stopping place");
    const double length = net.lane_length[lane];
    double start = on_lane(p.start_pos, length);
    double end = p.end_pos ? on_lane(*p.end_pos, length) : length;
    if (p.friendly_pos) {
      end = std::fmin(std::fmax(end, kPositionEps), length);
      start = std::fmin(std::fmax(start, 0.0), end - kPositionEps);
    }
    if (start < -kPositionEps || end > length + kPositionEps || end - start < kPositionEps)
      throw InputError(p.loc, "stopping place '" + p.id + "': invalid position: startPos " +
                                  std::to_string(start) + ", endPos " + std::to_string(end) + " on lane '" +
                                  p.lane + "' of length " + std::to_string(length) +
                                  " (give friendlyPos=\"true\" to move it onto the lane)");
    places_.emplace(p.id, Place{lane, static_cast<float>(std::fmax(start, 0.0)),
                                static_cast<float>(std::fmin(end, length))});
  }
}

uint32_t StopResolver::lane_of(const std::string& id, const SourceLoc& loc, const char* what) const {
  auto it = net_.lane_index_by_id.find(id);
  if (it == net_.lane_index_by_id.end())
    throw InputError(loc, std::string(what) + ": unknown lane '" + id +
                              "' (or a lane no road vehicle may use, which LPSim leaves out)");
  return it->second;
}

StopResolver::Place StopResolver::place_of(const StopSpec& s, uint32_t vclass) const {
  if (!s.stopping_place.empty()) {
    auto it = places_.find(s.stopping_place);
    if (it == places_.end())
      throw InputError(s.loc, "stop: unknown stopping place '" + s.stopping_place + "'");
    return it->second;
  }
  uint32_t lane = 0;
  if (!s.lane.empty()) {
    lane = lane_of(s.lane, s.loc, "stop");
  } else {
    auto e = net_.edge_index.find(s.edge);
    if (e == net_.edge_index.end() || net_.edge_is_internal[e->second])
      throw InputError(s.loc, "stop: unknown edge '" + s.edge + "'");
    const uint32_t first = net_.edge_first_lane[e->second];
    lane = first;
    for (uint32_t k = 0; k < net_.edge_num_lanes[e->second]; ++k)
      if (net_.lane_permissions[first + k] & vclass) {
        lane = first + k;
        break;
      }
  }
  const double length = net_.lane_length[lane];
  const double end = s.end_pos ? on_lane(*s.end_pos, length) : length;
  const double start = s.start_pos ? on_lane(*s.start_pos, length) : std::fmax(0.0, end - 2 * kPositionEps);
  if (end > length + kPositionEps || end < 0 || start < -kPositionEps || start > end)
    throw InputError(s.loc, "stop on lane '" + net_.lane_id[lane] + "': invalid position: startPos " +
                                std::to_string(start) + ", endPos " + std::to_string(end) +
                                " on a lane of length " + std::to_string(length));
  return Place{lane, static_cast<float>(std::fmax(start, 0.0)), static_cast<float>(std::fmin(end, length))};
}

uint32_t StopResolver::edge_of(const StopSpec& stop) const {
  return net_.lane_edge[place_of(stop, kAllVClasses).lane];
}

std::string StopResolver::append(const std::vector<const StopSpec*>& specs, const uint32_t* route,
                                 uint32_t route_len, uint32_t vclass, double until_shift,
                                 StopTable& out) const {
  uint32_t pos = 0;
  float last_end = -1.0f;
  for (const StopSpec* s : specs) {
    const Place p = place_of(*s, vclass);
    if ((net_.lane_permissions[p.lane] & vclass) == 0)
      return "may not stop on lane '" + net_.lane_id[p.lane] + "': its class may not use it";
    const uint32_t edge = net_.lane_edge[p.lane];
    // On the edge of the stop before it, further along: the same occurrence; else the next one.
    uint32_t k = pos;
    if (!(k < route_len && route[k] == edge && p.end >= last_end)) {
      if (k < route_len && route[k] == edge) ++k;
      while (k < route_len && route[k] != edge) ++k;
    }
    if (k >= route_len)
      return "stop on lane '" + net_.lane_id[p.lane] + "' is not downstream the current route";
    pos = k;
    last_end = p.end;
    out.route_pos.push_back(k);
    out.lane.push_back(p.lane);
    out.start_pos.push_back(p.start);
    out.end_pos.push_back(p.end);
    out.duration.push_back(s->duration < 0 ? 0.0 : s->duration);
    out.until.push_back(s->until < 0 ? -1.0 : s->until + until_shift);
  }
  return "";
}

}  // namespace lpsim

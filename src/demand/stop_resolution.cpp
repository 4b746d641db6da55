#include "demand/stop_resolution.hpp"

#include <cmath>

namespace lpsim {
namespace {

// SUMO's POSITION_EPS: the shortest stopping place.
constexpr double kPositionEps = 0.1;

std::string metres(double x) { return std::to_string(x); }

}  // namespace

bool stop_position_valid(double& start, double& end, double length, double min_length, bool friendly) {
  if (min_length > length) return false;
  if (start < 0) start += length;
  if (end < 0) end += length;
  if (end < min_length || end > length) {
    if (!friendly) return false;
    end = std::fmin(std::fmax(end, min_length), length);
  }
  if (start < 0 || start > end - min_length) {
    if (!friendly) return false;
    start = std::fmin(std::fmax(start, 0.0), end - min_length);
  }
  return true;
}

StopResolver::StopResolver(const DemandSpec& spec, const Network& net) : net_(net) {
  for (const StoppingPlaceSpec& p : spec.stopping_places) {
    auto left_out = net.left_out_lane_edge.find(p.lane);
    if (left_out != net.left_out_lane_edge.end()) {
      places_.emplace(p.id, Place{kLeftOut, left_out->second, 0.0f, 0.0f});
      ++left_out_places_;
      continue;
    }
    const uint32_t lane = lane_of(p.lane, p.loc, "stopping place");
    const double length = net.lane_length[lane];
    double start = p.start_pos;
    double end = p.end_pos.value_or(length);
    if (!stop_position_valid(start, end, length, kPositionEps, p.friendly_pos))
      throw InputError(p.loc, "stopping place '" + p.id + "': invalid position: startPos " +
                                  metres(p.start_pos) + ", endPos " + metres(p.end_pos.value_or(length)) +
                                  " on lane '" + p.lane + "' of length " + metres(length) +
                                  " (give friendlyPos=\"true\" to move it onto the lane)");
    places_.emplace(p.id,
                    Place{lane, net.lane_edge[lane], static_cast<float>(start), static_cast<float>(end)});
  }
}

uint32_t StopResolver::lane_of(const std::string& id, const SourceLoc& loc, const char* what) const {
  auto it = net_.lane_index_by_id.find(id);
  if (it == net_.lane_index_by_id.end())
    throw InputError(loc, std::string(what) + ": unknown lane '" + id + "'");
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
    auto left_out = net_.left_out_lane_edge.find(s.lane);
    if (left_out != net_.left_out_lane_edge.end()) return Place{kLeftOut, left_out->second, 0.0f, 0.0f};
    lane = lane_of(s.lane, s.loc, "stop");
  } else {
    auto e = net_.edge_index.find(s.edge);
    if (e == net_.edge_index.end() || net_.edge_is_internal[e->second])
      throw InputError(s.loc, "stop: unknown edge '" + s.edge + "'");
    if (net_.edge_num_lanes[e->second] == 0) return Place{kLeftOut, e->second, 0.0f, 0.0f};
    const uint32_t first = net_.edge_first_lane[e->second];
    lane = first;
    for (uint32_t k = 0; k < net_.edge_num_lanes[e->second]; ++k)
      if (net_.lane_permissions[first + k] & vclass) {
        lane = first + k;
        break;
      }
  }
  // SUMO's defaults: endPos the lane's end, startPos 0.2 m before endPos as given (so endPos -10 without a
  // startPos makes the stretch [0, length - 10] in SUMO too); no shortest length.
  const double length = net_.lane_length[lane];
  double end = s.end_pos.value_or(length);
  double start = s.start_pos.value_or(std::fmax(0.0, end - 2 * kPositionEps));
  // SUMO 1.15 reports such a stop as an error but drops it and runs on.
  if (!stop_position_valid(start, end, length, 0.0, s.friendly_pos))
    return Place{kDropped, net_.lane_edge[lane], 0.0f, 0.0f};
  return Place{lane, net_.lane_edge[lane], static_cast<float>(start), static_cast<float>(end)};
}

std::optional<uint32_t> StopResolver::edge_of(const StopSpec& stop) const {
  const Place p = place_of(stop, kAllVClasses);
  if (p.lane == kDropped) return std::nullopt;
  return p.edge;
}

std::string StopResolver::append(const std::vector<const StopSpec*>& specs, const uint32_t* route,
                                 uint32_t route_len, uint32_t vclass, double until_shift, StopTable& out) {
  uint32_t pos = 0;
  float last_end = -1.0f;
  for (const StopSpec* s : specs) {
    const Place p = place_of(*s, vclass);
    if (p.lane == kDropped) {
      ++dropped_stops_;
      continue;
    }
    if (p.lane == kLeftOut)
      return "may not stop " +
             (s->stopping_place.empty() ? "on edge '" + net_.edge_id[p.edge] + "'"
                                        : "at '" + s->stopping_place + "'") +
             ": it lies on a lane no road vehicle may use, which LPSim leaves out";
    if ((net_.lane_permissions[p.lane] & vclass) == 0)
      return "may not stop on lane '" + net_.lane_id[p.lane] + "': its class may not use it";
    const uint32_t edge = p.edge;
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

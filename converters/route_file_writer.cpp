#include "converters/route_file_writer.hpp"

#include <cfloat>
#include <charconv>

#include "converters/output_file.hpp"
#include "kernels/idm.hpp"

namespace lpsim {
namespace {

// The shortest text that reads back as the same value (floats as floats, so 12.3f is "12.3").
template <class T>
std::string shortest(T v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void attr_value(OutputFile& out, std::string_view name, float v) { out.attr(name, shortest(v)); }

void write_vtype(OutputFile& out, const VehicleTypes& t, uint32_t k) {
  out.text("    <vType");
  out.attr("id", t.id[k]);
  if (!t.vclass[k].empty()) out.attr("vClass", t.vclass[k]);
  // The model as loaded (one LPSim runs as IDM stays itself for SUMO), with the parameter LPSim's runs use.
  out.attr("carFollowModel", t.car_follow_model[k]);
  attr_value(out, "length", t.length[k]);
  attr_value(out, "minGap", t.min_gap[k]);
  attr_value(out, "accel", t.accel[k]);
  attr_value(out, "decel", t.decel[k]);
  attr_value(out, "emergencyDecel", t.emergency_decel[k]);
  attr_value(out, "maxSpeed", t.max_speed[k]);
  if (t.desired_max_speed[k] != FLT_MAX) attr_value(out, "desiredMaxSpeed", t.desired_max_speed[k]);
  attr_value(out, "speedFactor", t.speed_factor[k]);
  attr_value(out, "speedDev", t.speed_dev[k]);
  attr_value(out, "tau", t.tau[k]);
  if (t.model[k] == kCarFollowIdm)
    attr_value(out, "delta", t.delta[k]);
  else
    attr_value(out, "sigma", t.sigma[k]);
  if (!t.emission_class[k].empty()) out.attr("emissionClass", t.emission_class[k]);
  out.text("/>\n");
}

void write_depart_attributes(OutputFile& out, const Demand& d, uint32_t v) {
  out.attr("depart", shortest(d.depart[v]));
  switch (static_cast<DepartLane>(d.depart_lane_kind[v])) {
    case DepartLane::Given:
      out.attr_int("departLane", d.depart_lane[v]);
      break;
    case DepartLane::First:
      break;  // SUMO's default
    case DepartLane::Random:
      out.attr("departLane", "random");
      break;
    case DepartLane::Free:
      out.attr("departLane", "free");
      break;
    case DepartLane::Allowed:
      out.attr("departLane", "allowed");
      break;
    case DepartLane::Best:
      out.attr("departLane", "best");
      break;
  }
  switch (static_cast<DepartPos>(d.depart_pos_kind[v])) {
    case DepartPos::Given:
      attr_value(out, "departPos", d.depart_pos[v]);
      break;
    case DepartPos::Base:
      break;
    case DepartPos::Random:
      out.attr("departPos", "random");
      break;
    case DepartPos::Free:
      out.attr("departPos", "free");
      break;
    case DepartPos::RandomFree:
      out.attr("departPos", "random_free");
      break;
    case DepartPos::Last:
      out.attr("departPos", "last");
      break;
    case DepartPos::Stop:
      out.attr("departPos", "stop");
      break;
  }
  switch (static_cast<DepartSpeed>(d.depart_speed_kind[v])) {
    case DepartSpeed::Given:
      attr_value(out, "departSpeed", d.depart_speed[v]);
      break;
    case DepartSpeed::Zero:
      break;
    case DepartSpeed::Random:
      out.attr("departSpeed", "random");
      break;
    case DepartSpeed::Max:
      out.attr("departSpeed", "max");
      break;
    case DepartSpeed::Desired:
      out.attr("departSpeed", "desired");
      break;
    case DepartSpeed::SpeedLimit:
      out.attr("departSpeed", "speedLimit");
      break;
    case DepartSpeed::Last:
      out.attr("departSpeed", "last");
      break;
    case DepartSpeed::Avg:
      out.attr("departSpeed", "avg");
      break;
  }
  switch (static_cast<ArrivalPos>(d.arrival_pos_kind[v])) {
    case ArrivalPos::Given:
      attr_value(out, "arrivalPos", d.arrival_pos[v]);
      break;
    case ArrivalPos::Max:
      break;
    case ArrivalPos::Random:
      out.attr("arrivalPos", "random");
      break;
  }
}

void write_edges(OutputFile& out, const Network& net, const uint32_t* edges, size_t n) {
  out.text(" edges=\"");
  for (size_t i = 0; i < n; ++i) {
    if (i > 0) out.put(' ');
    out.escaped(net.edge_id[edges[i]]);
  }
  out.put('"');
}

void write_stops(OutputFile& out, const Network& net, const Demand& d, uint32_t v) {
  for (uint32_t k = d.stops.first(v); k < d.stops.last(v); ++k) {
    out.text("        <stop");
    out.attr("lane", net.lane_id[d.stops.lane[k]]);
    attr_value(out, "startPos", d.stops.start_pos[k]);
    attr_value(out, "endPos", d.stops.end_pos[k]);
    out.attr("duration", shortest(d.stops.duration[k]));
    if (d.stops.until[k] >= 0) out.attr("until", shortest(d.stops.until[k]));
    out.text("/>\n");
  }
}

}  // namespace

void write_route_file(const std::string& path, const Network& net, const Demand& d,
                      const std::vector<RouteAlternatives>* alternatives) {
  OutputFile out(path);
  write_sumo_xml_header(out, "routes", "routes_file.xsd");
  std::vector<char> used(d.types.size(), 0);
  for (uint32_t v = 0; v < d.size(); ++v) used[d.vehicle_type[v]] = 1;
  for (uint32_t k = 0; k < d.types.size(); ++k)
    if (used[k]) write_vtype(out, d.types, k);
  for (uint32_t v = 0; v < d.size(); ++v) {
    out.text("    <vehicle");
    out.attr("id", d.vehicle_id[v]);
    out.attr("type", d.types.id[d.vehicle_type[v]]);
    write_depart_attributes(out, d, v);
    out.text(">\n");
    const RouteAlternatives* alts = alternatives ? &(*alternatives)[v] : nullptr;
    if (alts && !alts->routes.empty()) {
      out.text("        <routeDistribution");
      out.attr_int("last", alts->last);
      out.text(">\n");
      for (const RouteAlternative& r : alts->routes) {
        out.text("            <route");
        // Every digit: an assignment resumed from this file goes on as it would have (duarouter rounds).
        out.attr("cost", shortest(r.cost));
        out.attr("probability", shortest(r.probability));
        write_edges(out, net, r.edges.data(), r.edges.size());
        out.text("/>\n");
      }
      out.text("        </routeDistribution>\n");
    } else {
      out.text("        <route");
      write_edges(out, net, d.route_edges.data() + d.route_begin[v], d.route_length[v]);
      out.text("/>\n");
    }
    write_stops(out, net, d, v);
    out.text("    </vehicle>\n");
  }
  out.text("</routes>\n");
  out.close();
}

}  // namespace lpsim

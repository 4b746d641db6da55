#include "app/option_scopes.hpp"

#include <algorithm>
#include <string_view>

#include "converters/cli_options.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

namespace {

const ScopedOption* given(const ConfigSpec& config, std::string_view name) {
  for (const ScopedOption& o : config.scoped_options)
    if (o.name == name) return &o;
  return nullptr;
}

int64_t skipped(const DemandSpec& demand, const char* element) {
  const auto it = demand.skipped.find(element);
  return it == demand.skipped.end() ? 0 : it->second;
}

bool has_bidi_road(const NetSpec& net) {
  for (const EdgeSpec& e : net.edges) {
    if (e.bidi.empty() || e.function != EdgeFunction::Normal) continue;
    for (const LaneSpec& l : e.lanes)
      if (vehicle_lane(l.permissions)) return true;
  }
  return false;
}

bool routed_at_insertion(const VehicleSpec& v) {
  return v.route.empty() && v.edges.empty() && v.edge_ref_count == 0;
}

// Trips and flows whose path SUMO computes (from/to, junctions): SUMO equips them with the rerouting device
// implicitly.
bool has_trips(const DemandSpec& demand) {
  for (const VehicleSpec& v : demand.vehicles)
    if (routed_at_insertion(v)) return true;
  for (const FlowSpec& f : demand.flows)
    if (f.route.empty() && f.edges.empty()) return true;
  return false;
}

// Why vehicles of this scenario get SUMO's rerouting device beyond the routing of trips at insertion, or "".
std::string rerouting_equipment(const ConfigSpec& config, const DemandSpec& demand) {
  if (const ScopedOption* p = given(config, "device.rerouting.probability")) {
    const auto x = parse_double(p->value);
    if (x && *x > 0 && (!demand.vehicles.empty() || !demand.flows.empty()))
      return "device.rerouting.probability " + p->value + " equips vehicles with the rerouting device";
  }
  if (const ScopedOption* e = given(config, "device.rerouting.explicit"))
    if (e->value.find_first_not_of(" \t,") != std::string::npos)
      return "device.rerouting.explicit equips vehicles with the rerouting device";
  for (const VTypeSpec& t : demand.vtypes) {
    const auto it = t.params.find("has.rerouting.device");
    if (it != t.params.end() && parse_sumo_bool(it->second).value_or(false))
      return "vType '" + t.id + "' asks for the rerouting device (has.rerouting.device)";
  }
  if (demand.rerouting_device_requests > 0)
    return std::to_string(demand.rerouting_device_requests) +
           " vehicles or flows ask for the rerouting device (has.rerouting.device)";
  if (const ScopedOption* period = given(config, "device.rerouting.period")) {
    const auto t = parse_sumo_time(period->value);
    if (t && *t > 0 && !given(config, "device.rerouting.probability") && has_trips(demand))
      return "device.rerouting.period " + period->value +
             " reroutes the trips and flows SUMO routes (from/to) while they drive";
  }
  return "";
}

}  // namespace

std::string decide_scoped_options(const ConfigSpec& config, const NetSpec& net, const DemandSpec& demand) {
  if (config.scoped_options.empty()) return "";
  const bool bidi = has_bidi_road(net);
  const std::string equipped = rerouting_equipment(config, demand);
  const bool trips = has_trips(demand);
  const int64_t persons = skipped(demand, "person") + skipped(demand, "personFlow") +
                          skipped(demand, "container") + skipped(demand, "containerFlow");
  const int64_t parking_stops = skipped(demand, "stop (parkingArea)");

  std::string cannot_act;
  for (const ScopedOption& o : config.scoped_options) {
    std::string acts_because, idle_because;
    switch (o.scope) {
      case OptionScope::BidiEdges:
        if (bidi)
          acts_because = "the network has bidirectional road edges (bidi)";
        else
          idle_because = "no bidirectional road edges";
        break;
      case OptionScope::ReroutingDevice:
        if (!equipped.empty())
          acts_because = equipped + ", and LPSim does not reroute vehicles";
        else if (trips)
          idle_because =
              "the device only routes trips and flows from/to, when SUMO inserts them, on the travel times "
              "these options tune; LPSim routes them when loading, on free-flow travel times";
        else
          idle_because = "no vehicle gets the rerouting device";
        break;
      case OptionScope::ParkingAreaStops:
        if (parking_stops > 0)
          acts_because = std::to_string(parking_stops) + " stops are made at parking areas";
        else
          idle_because = "no stop at a parking area";
        break;
      case OptionScope::Persons:
        if (o.name == "pedestrian.model" && o.value == "nonInteracting")
          idle_because = "persons never meet LPSim's vehicles: LPSim leaves them out";
        else if (persons > 0)
          acts_because = "the scenario has " + std::to_string(persons) + " persons or containers";
        else
          idle_because = "no persons";
        break;
    }
    if (!acts_because.empty())
      throw InputError(o.loc,
                       (o.loc.file == "command line" ? "--" + o.name : "<" + o.name + ">") + " '" + o.value +
                           "': SUMO option not supported by LPSim where it acts, as here: " + acts_because);
    cannot_act += (cannot_act.empty() ? "" : "; ") + o.name + " (" + idle_because + ")";
  }
  return "SUMO options accepted that cannot act in this scenario: " + cannot_act;
}

}  // namespace lpsim

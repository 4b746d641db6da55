#include "app/option_scopes.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <string_view>

#include "converters/cli_options.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

namespace {

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

// Whether a vehicle or flow of the scenario is a bicycle (its vType, or a member of its distribution).
bool has_bicycles(const DemandSpec& demand) {
  std::set<std::string> bicycle_types;
  for (const VTypeSpec& t : demand.vtypes)
    if (t.vclass == "bicycle") bicycle_types.insert(t.id);
  if (bicycle_types.empty()) return false;
  for (const VTypeDistSpec& d : demand.vtype_dists)
    for (const WeightedId& m : d.members)
      if (bicycle_types.count(m.id) > 0) bicycle_types.insert(d.id);
  for (const VehicleSpec& v : demand.vehicles)
    if (bicycle_types.count(v.type) > 0) return true;
  for (const FlowSpec& f : demand.flows)
    if (bicycle_types.count(f.type) > 0) return true;
  return false;
}

}  // namespace

std::string decide_scoped_options(const ConfigSpec& config, const NetSpec& net, const DemandSpec& demand) {
  if (config.scoped_options.empty()) return "";
  const bool bidi = has_bidi_road(net);
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
        // The device's options LPSim does not implement (it implements the others).
        if (o.name == "device.rerouting.bike-speeds") {
          if (has_bicycles(demand))
            acts_because = "the scenario has bicycles, whose own mean speeds LPSim does not keep for routing";
          else
            idle_because = "no bicycles";
        } else if (o.name == "device.rerouting.with-taz") {
          idle_because = "LPSim leaves out trips between TAZ";
        } else if (o.name == "device.rerouting.init-with-loaded-weights") {
          idle_because = "no edge weights are loaded";
        } else {
          idle_because = "LPSim does not simulate rail vehicles";
        }
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

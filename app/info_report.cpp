#include "app/info_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "net/junction_type.hpp"
#include "net/router.hpp"

namespace lpsim {

namespace {

std::string fmt(const char* f, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

}  // namespace

std::string unsupported_summary(const Demand& demand) {
  if (demand.unsupported.empty()) return "";
  std::string s = "skipped unsupported elements:";
  bool first = true;
  for (const auto& [name, n] : demand.unsupported) {
    s += fmt("%s %s %lld", first ? "" : ",", name.c_str(), static_cast<long long>(n));
    first = false;
  }
  return s;
}

std::string describe_scenario(const Scenario& sc) {
  const Network& net = sc.network;
  const Demand& d = sc.demand;
  std::string out;

  std::map<std::string, uint64_t> by_jtype;
  uint64_t real_junctions = 0;
  for (auto t : net.junction_type) {
    if (t == JunctionType::Internal) continue;
    ++real_junctions;
    ++by_jtype[junction_type_name(t)];
  }
  out += fmt("junctions: %llu", static_cast<unsigned long long>(real_junctions));
  std::string sep = " (";
  for (const auto& [name, n] : by_jtype) {
    out += fmt("%s%s %llu", sep.c_str(), name.c_str(), static_cast<unsigned long long>(n));
    sep = ", ";
  }
  out += real_junctions ? ")\n" : "\n";

  uint64_t normal_edges = 0, internal_edges = 0, normal_lanes = 0, internal_lanes = 0;
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e]) {
      ++internal_edges;
      internal_lanes += net.edge_num_lanes[e];
    } else {
      ++normal_edges;
      normal_lanes += net.edge_num_lanes[e];
    }
  }
  out += fmt("edges: %llu normal, %llu internal\n", static_cast<unsigned long long>(normal_edges),
             static_cast<unsigned long long>(internal_edges));
  out +=
      fmt("lanes: %llu vehicle lanes on normal edges (%.3f lane-km), %llu internal; skipped lanes (no road "
          "vehicle): %lld\n",
          static_cast<unsigned long long>(normal_lanes), net.lane_km(),
          static_cast<unsigned long long>(internal_lanes), static_cast<long long>(net.skipped_non_car_lanes));
  out += fmt("connections: %u (skipped, touching skipped lanes: %lld)\n", net.num_connections(),
             static_cast<long long>(net.skipped_connections));
  uint64_t actuated = 0;
  for (auto a : net.signal_actuated) actuated += a;
  out += fmt("signal programs: %u (%llu static, %llu actuated)\n", net.num_signals(),
             static_cast<unsigned long long>(net.num_signals() - actuated),
             static_cast<unsigned long long>(actuated));
  out += fmt("lane map: %llu cells (%.1f MiB)\n", static_cast<unsigned long long>(net.num_cells()),
             static_cast<double>(net.num_cells()) / (1024.0 * 1024.0));

  out += fmt("vehicles: %u\n", d.size());
  out += fmt("  by source: routes %llu, trips %llu, flows %llu, od-csv %llu\n",
             static_cast<unsigned long long>(d.count(DemandSource::Vehicle)),
             static_cast<unsigned long long>(d.count(DemandSource::Trip)),
             static_cast<unsigned long long>(d.count(DemandSource::Flow)),
             static_cast<unsigned long long>(d.count(DemandSource::OdCsv)));
  std::vector<uint64_t> per_type(d.types.size(), 0);
  for (auto t : d.vehicle_type) ++per_type[t];
  out += "  by type:";
  sep = " ";
  for (uint32_t t = 0; t < d.types.size(); ++t) {
    if (per_type[t] == 0) continue;
    out += fmt("%s%s %llu", sep.c_str(), d.types.id[t].c_str(), static_cast<unsigned long long>(per_type[t]));
    sep = ", ";
  }
  out += "\n";
  if (d.size() > 0) out += fmt("  departures: %.2f s to %.2f s\n", d.depart.front(), d.depart.back());
  if (d.size() > 0) {
    uint64_t route_edges = 0;
    for (const uint32_t n : d.route_length) route_edges += n;
    out += fmt("  routes: %.1f edges per vehicle (%llu in all)\n",
               static_cast<double>(route_edges) / static_cast<double>(d.size()),
               static_cast<unsigned long long>(route_edges));
  }
  if (!d.rerouting.empty()) {
    // SUMO's rerouting device: who has it, and how it routes them (docs/MODELS.md, "The rerouting device").
    uint64_t with = 0, equipped = 0, driving = 0, repaired = 0;
    for (const uint8_t f : d.rerouting) {
      with += f != 0 ? 1 : 0;
      equipped += (f & kRerouteEquipped) ? 1 : 0;
      driving += (f & kRerouteWhileDriving) ? 1 : 0;
      repaired += (f & kRerouteRepair) ? 1 : 0;
    }
    out += fmt(
        "  rerouting device: %llu (routed when due; equipped by options or params %llu, of them re-routing "
        "while driving %llu; routes to repair %llu)\n",
        static_cast<unsigned long long>(with), static_cast<unsigned long long>(equipped),
        static_cast<unsigned long long>(driving), static_cast<unsigned long long>(repaired));
  }
  // As SUMO, a run does not insert vehicles that depart before the begin time.
  const auto before_begin =
      std::lower_bound(d.depart.begin(), d.depart.end(), sc.config.begin) - d.depart.begin();
  if (before_begin > 0)
    out += fmt("  departing before begin (%.2f s), not simulated: %lld\n", sc.config.begin,
               static_cast<long long>(before_begin));
  if (d.routing.requests > 0)
    out += fmt("routing: %llu trips (%llu distinct requests)\n",
               static_cast<unsigned long long>(d.routing.vehicles),
               static_cast<unsigned long long>(d.routing.requests));
  // Sum over vehicles of their route's free-flow travel time (its edges and junction crossings), the measure
  // the router minimises; comparable between LPSim's routes and another router's on the same net.
  const Router router(net, sc.config.minor_penalty);
  double cost = 0;
  std::vector<uint32_t> route;
  for (uint32_t v = 0; v < d.size(); ++v) {
    route.assign(d.route_edges.begin() + d.route_begin[v],
                 d.route_edges.begin() + d.route_begin[v] + d.route_length[v]);
    const double c = router.cost(route);
    if (std::isfinite(c)) cost += c;
  }
  out += fmt("free-flow route cost: %.1f s\n", cost);
  out += fmt("unrouted or skipped vehicles: %zu\n", d.unroutable.size());
  for (size_t i = 0; i < d.unroutable.size() && i < 10; ++i)
    out +=
        "  " + d.unroutable[i].id + ": " + d.unroutable[i].reason + " (" + d.unroutable[i].loc.str() + ")\n";
  if (d.unroutable.size() > 10) out += fmt("  ... and %zu more\n", d.unroutable.size() - 10);
  std::string unsupported = unsupported_summary(d);
  out += unsupported.empty() ? "skipped unsupported elements: none\n" : unsupported + "\n";
  for (const auto& line : sc.warnings) out += "not implemented: " + line + "\n";
  out += fmt("edgeData/laneData definitions: %zu\n", sc.mean_data.size());
  out += fmt("load time: %.3f s", sc.load_seconds);
  if (d.routing.seconds > 0)  // timings vary run to run, so they stay on this one line
    out += fmt(" (routing %.3f s, %.0f trips/s)", d.routing.seconds,
               static_cast<double>(d.routing.vehicles) / d.routing.seconds);
  out += "\n";
  return out;
}

}  // namespace lpsim

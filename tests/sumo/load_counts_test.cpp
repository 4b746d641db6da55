// Loads every bundled scenario with load_scenario and compares what LPSim built with what SUMO/sumolib
// report for the same files (scenarios/<name>/sumo_reference.txt, written by tools/sumo_reference.py).
//
// What is compared, and how LPSim's notion maps onto sumolib's (see scenarios/README.md for the keys):
//  - normal_edges: LPSim edges with edge_is_internal == 0. sumolib counts function="" only; LPSim would also
//    keep function="connector" edges here, which none of the bundled nets has, so the count is exact.
//  - internal_edges: LPSim edges with edge_is_internal == 1 (function="internal"; crossings and walking
//    areas are dropped by LPSim and are not "internal" for sumolib either). Exact.
//  - junctions / junctions_<type>: LPSim junctions whose type is not internal, by type name. Exact.
//  - passenger_lanes: lanes of normal edges whose permissions include passenger cars (LPSim keeps every
//    lane some vehicle may use, each with its vClass mask). Exact.
//  - non_passenger_lanes: lanes of normal edges that forbid passenger cars, counted on the NetSpec (LPSim
//    drops the pedestrian-only ones, keeps bus lanes and the like). Exact.
//  - tl_programs: sumolib counts every <tlLogic>; LPSim keeps one program per traffic light (the one in
//    force). Each bundled light has exactly one program, so num_signals must equal tl_programs.
//  - passenger_connections: sumolib counts <connection>s from a passenger lane of a normal edge to a
//    passenger lane of a normal edge. LPSim also stores the connections that leave internal lanes and those
//    of other classes' lanes; counting only those whose from-lane and to-edge are both normal and whose
//    from- and to-lane allow passenger cars gives the same definition. Exact.
//  - vehicles: Demand::size() == sumo_vehicles_loaded, except for flows whose count is random (probability
//    flows draw with LPSim's own generator, not SUMO's): there each deterministic flow must match SUMO's
//    per-flow count exactly and the random one must be within 4 standard deviations of its mean.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "app/snapshot.hpp"
#include "converters/net_reader.hpp"
#include "converters/route_reader.hpp"
#include "converters/sumocfg_reader.hpp"
#include "net/junction_type.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::string kScenarios = LPSIM_SCENARIOS_DIR;

std::map<std::string, double> read_reference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::map<std::string, double> ref;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw std::runtime_error("bad reference line: " + line);
    ref[line.substr(0, eq)] = std::stod(line.substr(eq + 1));
  }
  return ref;
}

int64_t ref_int(const std::map<std::string, double>& ref, const std::string& key) {
  auto it = ref.find(key);
  if (it == ref.end()) throw std::runtime_error("reference has no key " + key);
  return static_cast<int64_t>(std::llround(it->second));
}

std::vector<std::string> route_of(const Scenario& sc, uint32_t v) {
  std::vector<std::string> edges;
  const Demand& d = sc.demand;
  for (uint32_t k = 0; k < d.route_length[v]; ++k)
    edges.push_back(sc.network.edge_id[d.route_edges[d.route_begin[v] + k]]);
  return edges;
}

// Every route is a chain of edges a car can drive: consecutive edges are connected by some lane connection.
void expect_routes_connected(const Scenario& sc) {
  const Demand& d = sc.demand;
  for (uint32_t v = 0; v < d.size(); ++v) {
    ASSERT_GT(d.route_length[v], 0u) << d.vehicle_id[v];
    for (uint32_t k = 0; k + 1 < d.route_length[v]; ++k) {
      const uint32_t a = d.route_edges[d.route_begin[v] + k], b = d.route_edges[d.route_begin[v] + k + 1];
      ASSERT_TRUE(sc.network.connected(a, b))
          << d.vehicle_id[v] << ": " << sc.network.edge_id[a] << " -> " << sc.network.edge_id[b];
    }
  }
}

// What the route file said a vehicle's route must be: either exact edge lists (a route or a route
// distribution's members) or endpoints from/to with vias that must appear in that order.
struct RouteExpectation {
  std::vector<std::vector<std::string>> exact;  // any one of these
  std::string from, to;
  std::vector<std::string> via;
};

// A vehicle's inline route: its edges, or the ids of its route as interned by the route reader.
std::vector<std::string> inline_edges(const DemandSpec& spec, const VehicleSpec& v) {
  std::vector<std::string> edges = v.edges;
  for (uint32_t k = 0; k < v.edge_ref_count; ++k)
    edges.push_back(spec.edge_names.at(spec.edge_refs.at(v.edge_ref_begin + k)));
  return edges;
}

class RouteExpectations {
 public:
  explicit RouteExpectations(const DemandSpec& spec) : spec_(spec) {
    for (const auto& r : spec.routes) routes_[r.id] = r.edges;
    for (const auto& rd : spec.route_dists)
      for (const auto& m : rd.members) dist_members_[rd.id].push_back(m.id);
    for (const auto& v : spec.vehicles)
      by_vehicle_[v.id] = expectation(v.route, inline_edges(spec, v), v.from, v.to, v.via);
    for (const auto& f : spec.flows) by_flow_[f.id] = expectation(f.route, f.edges, f.from, f.to, f.via);
  }

  // Vehicle `id`, or flow vehicle "<flow>.<n>".
  const RouteExpectation& of(const std::string& id) const {
    if (auto it = by_vehicle_.find(id); it != by_vehicle_.end()) return it->second;
    const auto dot = id.rfind('.');
    if (dot != std::string::npos)
      if (auto it = by_flow_.find(id.substr(0, dot)); it != by_flow_.end()) return it->second;
    throw std::runtime_error("vehicle " + id + " is in no route file");
  }

 private:
  const DemandSpec& spec_;
  std::map<std::string, std::vector<std::string>> routes_;
  std::map<std::string, std::vector<std::string>> dist_members_;
  std::map<std::string, RouteExpectation> by_vehicle_, by_flow_;

  RouteExpectation expectation(const std::string& route, const std::vector<std::string>& edges,
                               const std::string& from, const std::string& to,
                               const std::vector<std::string>& via) {
    RouteExpectation e;
    if (!route.empty()) {
      if (auto it = dist_members_.find(route); it != dist_members_.end()) {
        for (const auto& m : it->second) e.exact.push_back(routes_.at(m));
      } else {
        e.exact.push_back(routes_.at(route));
      }
    } else if (!edges.empty()) {
      e.exact.push_back(edges);
    } else {
      e.from = from, e.to = to, e.via = via;
    }
    return e;
  }
};

void expect_routes_as_specified(const Scenario& sc, const DemandSpec& spec) {
  RouteExpectations expected(spec);
  for (uint32_t v = 0; v < sc.demand.size(); ++v) {
    const std::string& id = sc.demand.vehicle_id[v];
    const auto route = route_of(sc, v);
    const RouteExpectation& e = expected.of(id);
    if (!e.exact.empty()) {
      bool any = false;
      for (const auto& r : e.exact) any = any || r == route;
      EXPECT_TRUE(any) << id << ": route is not one the route file gives";
      continue;
    }
    ASSERT_FALSE(route.empty()) << id;
    EXPECT_EQ(route.front(), e.from) << id;
    EXPECT_EQ(route.back(), e.to) << id;
    size_t k = 0;
    for (const auto& edge : route)
      if (k < e.via.size() && edge == e.via[k]) ++k;
    EXPECT_EQ(k, e.via.size()) << id << ": route misses a via edge";
  }
}

void expect_departures_sorted(const Demand& d) {
  for (uint32_t v = 1; v < d.size(); ++v) ASSERT_LE(d.depart[v - 1], d.depart[v]) << d.vehicle_id[v];
}

struct LoadedSumoScenario {
  std::map<std::string, double> ref;
  Scenario scenario;
  NetSpec net_spec;
  DemandSpec demand_spec;
};

LoadedSumoScenario load(const std::string& name) {
  const std::string dir = kScenarios + "/" + name;
  LoadedSumoScenario s;
  s.ref = read_reference(dir + "/sumo_reference.txt");
  const ConfigSpec cfg = read_sumocfg(dir + "/" + name + ".sumocfg");
  s.scenario = load_scenario(cfg);
  s.net_spec = read_sumo_net(cfg.net_file);
  AdditionalSpec additional;
  for (const auto& f : cfg.additional_files) read_sumo_routes(f, s.demand_spec, additional);
  for (const auto& f : cfg.route_files) read_sumo_routes(f, s.demand_spec, additional, cfg.route_steps > 0);
  return s;
}

void expect_network_matches_reference(const LoadedSumoScenario& s) {
  const Network& net = s.scenario.network;
  const auto& ref = s.ref;

  int64_t normal = 0, internal = 0, car_lanes = 0;
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e]) {
      ++internal;
    } else {
      ++normal;
      const uint32_t l0 = net.edge_first_lane[e];
      for (uint32_t l = l0; l < l0 + net.edge_num_lanes[e]; ++l)
        car_lanes += (net.lane_permissions[l] & kVClassPassenger) != 0 ? 1 : 0;
    }
  }
  EXPECT_EQ(normal, ref_int(ref, "normal_edges"));
  EXPECT_EQ(internal, ref_int(ref, "internal_edges"));
  EXPECT_EQ(car_lanes, ref_int(ref, "passenger_lanes"));

  int64_t spec_non_car = 0, spec_car = 0;
  for (const auto& e : s.net_spec.edges) {
    if (e.function != EdgeFunction::Normal) continue;
    for (const auto& l : e.lanes) ((l.permissions & kVClassPassenger) != 0 ? spec_car : spec_non_car) += 1;
  }
  EXPECT_EQ(spec_car, ref_int(ref, "passenger_lanes"));
  EXPECT_EQ(spec_non_car, ref_int(ref, "non_passenger_lanes"));

  std::map<std::string, int64_t> by_type;
  int64_t junctions = 0;
  for (auto t : net.junction_type) {
    if (t == JunctionType::Internal) continue;
    ++junctions;
    ++by_type[junction_type_name(t)];
  }
  EXPECT_EQ(junctions, ref_int(ref, "junctions"));
  std::map<std::string, int64_t> ref_by_type;
  for (const auto& [key, value] : ref)
    if (key.rfind("junctions_", 0) == 0) ref_by_type[key.substr(10)] = std::llround(value);
  EXPECT_EQ(by_type, ref_by_type);

  EXPECT_EQ(static_cast<int64_t>(net.num_signals()), ref_int(ref, "tl_programs"));

  int64_t normal_to_normal = 0;
  for (uint32_t c = 0; c < net.num_connections(); ++c)
    if (!net.edge_is_internal[net.lane_edge[net.conn_from_lane[c]]] &&
        !net.edge_is_internal[net.conn_to_edge[c]] &&
        (net.lane_permissions[net.conn_from_lane[c]] & kVClassPassenger) != 0 &&
        (net.lane_permissions[net.conn_to_lane[c]] & kVClassPassenger) != 0)
      ++normal_to_normal;
  EXPECT_EQ(normal_to_normal, ref_int(ref, "passenger_connections"));
}

void expect_nothing_skipped(const Demand& d) {
  EXPECT_TRUE(d.unroutable.empty()) << (d.unroutable.empty()
                                            ? ""
                                            : d.unroutable[0].id + ": " + d.unroutable[0].reason);
  EXPECT_TRUE(d.unsupported.empty());
}

TEST(SumoLoadCounts, GridTlsMatchesSumo) {
  const auto s = load("grid_tls");
  expect_network_matches_reference(s);
  const Demand& d = s.scenario.demand;
  EXPECT_EQ(static_cast<int64_t>(d.size()), ref_int(s.ref, "sumo_vehicles_loaded"));
  EXPECT_EQ(static_cast<int64_t>(d.count(DemandSource::Vehicle)), ref_int(s.ref, "xml_vehicles"));
  expect_nothing_skipped(d);
  expect_departures_sorted(d);
  expect_routes_connected(s.scenario);
  expect_routes_as_specified(s.scenario, s.demand_spec);
}

TEST(SumoLoadCounts, RandomNetMatchesSumo) {
  const auto s = load("random_net");
  expect_network_matches_reference(s);
  const Demand& d = s.scenario.demand;
  EXPECT_EQ(static_cast<int64_t>(d.size()), ref_int(s.ref, "sumo_vehicles_loaded"));
  EXPECT_EQ(static_cast<int64_t>(d.count(DemandSource::Trip)), ref_int(s.ref, "xml_trips"));
  expect_nothing_skipped(d);
  expect_departures_sorted(d);
  expect_routes_connected(s.scenario);
  expect_routes_as_specified(s.scenario, s.demand_spec);
}

TEST(SumoLoadCounts, FlowsMatchSumo) {
  const auto s = load("flows");
  expect_network_matches_reference(s);
  const Demand& d = s.scenario.demand;
  expect_nothing_skipped(d);
  expect_departures_sorted(d);
  expect_routes_connected(s.scenario);
  expect_routes_as_specified(s.scenario, s.demand_spec);

  std::map<std::string, int64_t> per_flow;
  for (const auto& id : d.vehicle_id) ++per_flow[id.substr(0, id.rfind('.'))];
  EXPECT_EQ(static_cast<int64_t>(d.count(DemandSource::Flow)), static_cast<int64_t>(d.size()));

  int64_t deterministic = 0, sumo_random = 0;
  for (const auto& f : s.demand_spec.flows) {
    const int64_t sumo = ref_int(s.ref, "sumo_arrived_flow_" + f.id);
    if (f.probability > 0) {
      // Binomial: one draw per step (1 s) over [begin, end).
      const double n = (f.end - f.begin) / s.scenario.config.step_length, p = f.probability;
      const double mean = n * p, sd = std::sqrt(n * p * (1 - p));
      EXPECT_NEAR(static_cast<double>(per_flow[f.id]), mean, 4 * sd) << f.id;
      sumo_random += sumo;
    } else {
      EXPECT_EQ(per_flow[f.id], sumo) << f.id;
      deterministic += per_flow[f.id];
    }
  }
  EXPECT_EQ(deterministic, ref_int(s.ref, "flow_vehicles_derivable"));
  EXPECT_EQ(deterministic + sumo_random, ref_int(s.ref, "sumo_vehicles_loaded"));
  EXPECT_EQ(static_cast<int64_t>(per_flow.size()), ref_int(s.ref, "xml_flows"));
}

// The original LPSim CSV network in both of the original's edge headers (u/v as osmids, or osmid_u/osmid_v
// plus dense u/v indices) must give the same network; the counts are those of scenarios/README.md.
TEST(SumoLoadCounts, LpsimCsvBothHeadersSameNetwork) {
  const std::string dir = kScenarios + "/lpsim_csv_small";
  ConfigSpec by_osmid, full_header;
  by_osmid.lpsim_nodes_csv = full_header.lpsim_nodes_csv = dir + "/nodes.csv";
  by_osmid.lpsim_edges_csv = dir + "/edges.csv";
  full_header.lpsim_edges_csv = dir + "/edges_full_header.csv";
  by_osmid.lpsim_od_csv = full_header.lpsim_od_csv = dir + "/od.csv";
  const Scenario a = load_scenario(by_osmid), b = load_scenario(full_header);

  for (const Scenario* sc : {&a, &b}) {
    const Network& net = sc->network;
    EXPECT_EQ(net.num_junctions(), 6u);
    EXPECT_EQ(net.num_edges(), 10u);
    EXPECT_EQ(net.num_lanes(), 14u);
    EXPECT_EQ(net.num_connections(), 26u);
    ASSERT_EQ(net.num_signals(), 1u);
    EXPECT_EQ(net.signal_id[0], "1001");
    const uint32_t p0 = net.signal_phase_begin[0];
    EXPECT_EQ(net.phase_state_begin[p0 + 1] - net.phase_state_begin[p0], 18u);
  }

  // Every column, via the snapshot payload (which lists each persisted column once): identical bytes.
  {
    const test::TempDir tmp("lpsim_csv_headers");
    write_snapshot(a, (tmp.path() / "a.lpsim").string());
    write_snapshot(b, (tmp.path() / "b.lpsim").string());
    auto bytes = [](const fs::path& p) {
      std::ifstream in(p, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(bytes(tmp.path() / "a.lpsim"), bytes(tmp.path() / "b.lpsim"));
  }

  // OD rows: 8 trips, each routed from its origin node to its destination node (origin_osmid and
  // destination_osmid columns, which the reader does not use: it takes the dense indices).
  std::ifstream od(dir + "/od.csv");
  std::string line;
  std::getline(od, line);
  std::map<std::string, std::pair<std::string, std::string>> od_nodes;
  while (std::getline(od, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    ASSERT_GE(cells.size(), 5u);
    od_nodes["od" + cells[0]] = {cells[3], cells[4]};
  }
  ASSERT_EQ(od_nodes.size(), 8u);
  for (const Scenario* sc : {&a, &b}) {
    const Demand& d = sc->demand;
    const Network& net = sc->network;
    ASSERT_EQ(d.size(), 8u);
    EXPECT_EQ(d.count(DemandSource::OdCsv), 8u);
    expect_nothing_skipped(d);
    expect_departures_sorted(d);
    expect_routes_connected(*sc);
    for (uint32_t v = 0; v < d.size(); ++v) {
      const auto& [origin, destination] = od_nodes.at(d.vehicle_id[v]);
      const uint32_t first = d.route_edges[d.route_begin[v]];
      const uint32_t last = d.route_edges[d.route_begin[v] + d.route_length[v] - 1];
      EXPECT_EQ(net.junction_id[net.edge_from_junction[first]], origin) << d.vehicle_id[v];
      EXPECT_EQ(net.junction_id[net.edge_to_junction[last]], destination) << d.vehicle_id[v];
    }
  }
}

}  // namespace
}  // namespace lpsim

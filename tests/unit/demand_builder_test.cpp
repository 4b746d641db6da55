// Demand builder: types, distributions, routes, trips, flows, depart attributes, errors and ordering.
#include "demand/demand_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "kernels/idm.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

constexpr const char* kFile = "test.rou.xml";

SourceLoc at(int line) { return {kFile, line}; }

VehicleSpec vehicle(const std::string& id, double depart, int line) {
  VehicleSpec v;
  v.id = id;
  v.depart = depart;
  v.loc = at(line);
  return v;
}

VehicleSpec on_route(const std::string& id, double depart, const std::string& route, int line = 10) {
  VehicleSpec v = vehicle(id, depart, line);
  v.route = route;
  return v;
}

VehicleSpec on_edges(const std::string& id, double depart, std::vector<std::string> edges, int line = 10) {
  VehicleSpec v = vehicle(id, depart, line);
  v.edges = std::move(edges);
  return v;
}

VehicleSpec trip(const std::string& id, double depart, const std::string& from, const std::string& to,
                 int line = 10) {
  VehicleSpec v = vehicle(id, depart, line);
  v.source = DemandSource::Trip;
  v.from = from;
  v.to = to;
  return v;
}

FlowSpec flow(const std::string& id, std::vector<std::string> edges, int line = 20) {
  FlowSpec f;
  f.id = id;
  f.edges = std::move(edges);
  f.loc = at(line);
  return f;
}

RouteSpec route(const std::string& id, std::vector<std::string> edges, int line = 5) {
  RouteSpec r;
  r.id = id;
  r.edges = std::move(edges);
  r.loc = at(line);
  return r;
}

VTypeSpec vtype(const std::string& id, int line = 2) {
  VTypeSpec t;
  t.id = id;
  t.loc = at(line);
  return t;
}

// Message of the InputError that building `spec` raises ("" if none).
std::string error_of(const DemandSpec& spec, const Network& net, DemandOptions options = {}) {
  try {
    build_demand(spec, net, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> route_ids(const Demand& d, const Network& net, uint32_t v) {
  std::vector<std::string> ids;
  for (uint32_t k = 0; k < d.route_length[v]; ++k)
    ids.push_back(net.edge_id[d.route_edges[d.route_begin[v] + k]]);
  return ids;
}

uint32_t index_of(const Demand& d, const std::string& id) {
  for (uint32_t v = 0; v < d.size(); ++v)
    if (d.vehicle_id[v] == id) return v;
  ADD_FAILURE() << "no vehicle " << id;
  return 0;
}

class DemandBuilderTest : public ::testing::Test {
 protected:
  // Corridor K0 -E0-> K1 -E1-> K2 -E2-> K3 -E3-> K4, 100 m edges, 2 lanes.
  Network corridor = build_network(test::make_corridor_spec(4, 100, 2));
  Network grid = build_network(test::make_grid_spec(3, 3));
};

// --- sources ---

TEST_F(DemandBuilderTest, NamedRouteIsStoredOnceAndShared) {
  DemandSpec spec;
  spec.routes.push_back(route("r", {"E0", "E1", "E2"}));
  spec.routes.push_back(route("unused", {"E1", "E2"}));
  spec.vehicles = {on_route("a", 0, "r"), on_route("b", 1, "r"), on_route("c", 2, "r")};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d.route_edges.size(), 3u);  // one copy, the unused route not stored
  for (uint32_t v = 0; v < 3; ++v) {
    EXPECT_EQ(d.route_begin[v], d.route_begin[0]);
    EXPECT_EQ(route_ids(d, corridor, v), (std::vector<std::string>{"E0", "E1", "E2"}));
    EXPECT_EQ(d.source[v], DemandSource::Vehicle);
  }
  ASSERT_EQ(d.types.size(), 1u);
  EXPECT_EQ(d.types.id[0], "DEFAULT_VEHTYPE");
  EXPECT_FLOAT_EQ(d.types.length[0], 5.0f);
  EXPECT_FLOAT_EQ(d.types.delta[0], 4.0f);
}

TEST_F(DemandBuilderTest, InlineRoutesAreResolved) {
  DemandSpec spec;
  spec.vehicles = {on_edges("a", 0, {"E1", "E2", "E3"}), on_edges("b", 0, {"E3"})};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(route_ids(d, corridor, 0), (std::vector<std::string>{"E1", "E2", "E3"}));
  EXPECT_EQ(route_ids(d, corridor, 1), (std::vector<std::string>{"E3"}));
}

TEST_F(DemandBuilderTest, TripsAreRoutedConnectedAndDeduplicated) {
  const std::string from = test::grid_edge(0, 0, 1, 0), to = test::grid_edge(1, 2, 2, 2);
  DemandSpec spec;
  spec.vehicles = {trip("t1", 0, from, to), trip("t2", 5, from, to), trip("t3", 6, to, from)};
  Demand d = build_demand(spec, grid, {});
  ASSERT_EQ(d.size(), 3u);
  for (uint32_t v = 0; v < 3; ++v) {
    EXPECT_EQ(d.source[v], DemandSource::Trip);
    for (uint32_t k = 1; k < d.route_length[v]; ++k)
      EXPECT_TRUE(
          grid.connected(d.route_edges[d.route_begin[v] + k - 1], d.route_edges[d.route_begin[v] + k]));
  }
  auto r = route_ids(d, grid, 0);
  EXPECT_EQ(r.front(), from);
  EXPECT_EQ(r.back(), to);
  EXPECT_EQ(r.size(), 4u);  // (0,0)->(1,0)->(1,1)->(1,2)->(2,2) is a fastest path: 4 edges
  EXPECT_EQ(d.route_begin[0], d.route_begin[1]);  // identical requests share their route
  EXPECT_NE(d.route_begin[0], d.route_begin[2]);
  EXPECT_EQ(d.route_edges.size(), d.route_length[0] + d.route_length[2]);
}

TEST_F(DemandBuilderTest, TripWithSameEndsDrivesThatEdge) {
  DemandSpec spec;
  spec.vehicles = {trip("t", 0, "E2", "E2")};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(route_ids(d, corridor, 0), (std::vector<std::string>{"E2"}));
}

TEST_F(DemandBuilderTest, TripViaEdgesPassesThem) {
  DemandSpec spec;
  VehicleSpec t = trip("t", 0, test::grid_edge(0, 0, 1, 0), test::grid_edge(1, 0, 2, 0));
  t.via = {test::grid_edge(1, 0, 1, 1), test::grid_edge(1, 1, 1, 0)};  // a detour up and back
  spec.vehicles = {t};
  test::GridOptions uturn;
  uturn.allow_uturn = true;
  Network net = build_network(test::make_grid_spec(3, 3, uturn));
  Demand d = build_demand(spec, net, {});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(route_ids(d, net, 0),
            (std::vector<std::string>{test::grid_edge(0, 0, 1, 0), test::grid_edge(1, 0, 1, 1),
                                      test::grid_edge(1, 1, 1, 0), test::grid_edge(1, 0, 2, 0)}));
}

TEST_F(DemandBuilderTest, JunctionTripsAndOdRowsStartAndEndAtTheirJunctions) {
  DemandSpec spec;
  VehicleSpec t = vehicle("j", 0, 3);
  t.source = DemandSource::Trip;
  t.from_junction = test::grid_junction(0, 0);
  t.to_junction = test::grid_junction(2, 2);
  VehicleSpec od = t;
  od.id = "od0";
  od.source = DemandSource::OdCsv;
  spec.vehicles = {t, od};
  Demand d = build_demand(spec, grid, {});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.count(DemandSource::OdCsv), 1u);
  EXPECT_EQ(d.count(DemandSource::Trip), 1u);
  for (uint32_t v = 0; v < 2; ++v) {
    const uint32_t first = d.route_edges[d.route_begin[v]];
    const uint32_t last = d.route_edges[d.route_begin[v] + d.route_length[v] - 1];
    EXPECT_EQ(grid.junction_id[grid.edge_from_junction[first]], test::grid_junction(0, 0));
    EXPECT_EQ(grid.junction_id[grid.edge_to_junction[last]], test::grid_junction(2, 2));
    EXPECT_EQ(d.route_length[v], 4u);  // Manhattan distance 4 blocks
  }
  EXPECT_EQ(d.route_begin[0], d.route_begin[1]);
}

// --- flows ---

std::vector<double> departs(const Demand& d) { return d.depart; }

TEST_F(DemandBuilderTest, FlowWithPeriodEndsBeforeEnd) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.end = 10;
  f.period = 3;
  spec.flows = {f};
  Demand d = build_demand(spec, corridor, {});
  EXPECT_EQ(departs(d), (std::vector<double>{0, 3, 6, 9}));
  EXPECT_EQ(d.vehicle_id, (std::vector<std::string>{"f.0", "f.1", "f.2", "f.3"}));
  EXPECT_EQ(d.count(DemandSource::Flow), 4u);
  EXPECT_EQ(d.route_edges.size(), 1u);  // the flow's route is stored once
}

TEST_F(DemandBuilderTest, FlowWithVehsPerHour) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.begin = 100;
  f.end = 110;
  f.vehs_per_hour = 1800;  // every 2 s
  spec.flows = {f};
  EXPECT_EQ(departs(build_demand(spec, corridor, {})), (std::vector<double>{100, 102, 104, 106, 108}));
}

TEST_F(DemandBuilderTest, FlowWithNumberAndEndSpreadsEvenly) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.end = 10;
  f.number = 4;
  spec.flows = {f};
  EXPECT_EQ(departs(build_demand(spec, corridor, {})), (std::vector<double>{0, 2.5, 5, 7.5}));
}

TEST_F(DemandBuilderTest, FlowWithNumberAndPeriodNeedsNoEnd) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.begin = 2;
  f.period = 5;
  f.number = 3;
  spec.flows = {f};
  EXPECT_EQ(departs(build_demand(spec, corridor, {})), (std::vector<double>{2, 7, 12}));
}

TEST_F(DemandBuilderTest, FlowWithoutEndRunsTwentyFourHours) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.begin = 50;
  f.period = 3600;
  FlowSpec g = flow("g", {"E0"});
  g.number = 3;  // number alone: spread over the default 24 h
  spec.flows = {f, g};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 27u);
  EXPECT_DOUBLE_EQ(d.depart.back(), 50 + 23 * 3600);
  EXPECT_DOUBLE_EQ(d.depart[index_of(d, "g.1")], 28800);
  EXPECT_DOUBLE_EQ(d.depart[index_of(d, "g.2")], 57600);
}

TEST_F(DemandBuilderTest, ProbabilityFlowDrawsOncePerStep) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.end = 2000;
  f.probability = 0.25;
  spec.flows = {f};
  Demand a = build_demand(spec, corridor, {});
  EXPECT_GT(a.size(), 420u);  // 2000 draws with p = 0.25: mean 500, sd 19
  EXPECT_LT(a.size(), 580u);
  std::set<double> distinct(a.depart.begin(), a.depart.end());
  EXPECT_EQ(distinct.size(), a.size());  // at most one vehicle per step
  for (double t : a.depart) {
    EXPECT_EQ(t, std::floor(t));
    EXPECT_LT(t, 2000);
  }
  EXPECT_EQ(build_demand(spec, corridor, {}).depart, a.depart);
  DemandOptions other;
  other.seed = 7;
  EXPECT_NE(build_demand(spec, corridor, other).depart, a.depart);

  DemandOptions half;
  half.step_length = 0.5;  // p is per second: p * 0.5 per step, the same rate per second
  Demand h = build_demand(spec, corridor, half);
  EXPECT_GT(h.size(), 420u);
  EXPECT_LT(h.size(), 580u);
  bool off_grid = false;
  for (double t : h.depart) off_grid |= t != std::floor(t);
  EXPECT_TRUE(off_grid);
}

TEST_F(DemandBuilderTest, ProbabilityFlowWithNumberStopsThere) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0"});
  f.begin = 10;
  f.probability = 0.1;
  f.number = 30;
  spec.flows = {f};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 30u);
  EXPECT_GE(d.depart.front(), 10);
}

TEST_F(DemandBuilderTest, FlowWithEndpointsIsRoutedOnce) {
  DemandSpec spec;
  FlowSpec f = flow("f", {});
  f.from = "E0";
  f.to = "E3";
  f.number = 5;
  f.period = 1;
  spec.flows = {f};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d.route_edges.size(), 4u);
  for (uint32_t v = 0; v < 5; ++v) EXPECT_EQ(d.route_begin[v], d.route_begin[0]);
  EXPECT_EQ(route_ids(d, corridor, 4), (std::vector<std::string>{"E0", "E1", "E2", "E3"}));
}

TEST_F(DemandBuilderTest, InconsistentFlowsAreRejected) {
  auto message = [&](FlowSpec f) {
    DemandSpec spec;
    spec.flows = {f};
    return error_of(spec, corridor);
  };
  FlowSpec two_rates = flow("fa", {"E0"}, 31);
  two_rates.period = 1;
  two_rates.vehs_per_hour = 100;
  EXPECT_NE(message(two_rates).find("test.rou.xml:31"), std::string::npos);
  EXPECT_NE(message(two_rates).find("'fa'"), std::string::npos);
  FlowSpec end_and_number = flow("fb", {"E0"});
  end_and_number.period = 1;
  end_and_number.end = 10;
  end_and_number.number = 3;
  EXPECT_NE(message(end_and_number).find("'fb'"), std::string::npos);
  FlowSpec no_rate = flow("fc", {"E0"});
  EXPECT_NE(message(no_rate).find("'fc'"), std::string::npos);
  FlowSpec bad_prob = flow("fd", {"E0"});
  bad_prob.probability = 1.5;
  EXPECT_NE(message(bad_prob).find("'fd'"), std::string::npos);
  FlowSpec backwards = flow("fe", {"E0"});
  backwards.begin = 10;
  backwards.end = 5;
  backwards.period = 1;
  EXPECT_NE(message(backwards).find("'fe'"), std::string::npos);
}

// --- types and distributions ---

TEST_F(DemandBuilderTest, VTypesAreCopiedWithIdmDelta) {
  DemandSpec spec;
  VTypeSpec car = vtype("car");
  car.length = 4.5;
  car.car_follow_model = "IDM";
  car.car_follow_model_given = true;  // as the route reader marks a model the file names
  car.params["delta"] = "2.5";
  spec.vtypes = {car, vtype("unused")};
  VehicleSpec v = on_edges("v", 0, {"E0"});
  v.type = "car";
  spec.vehicles = {v};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.types.size(), 2u);  // DEFAULT_VEHTYPE is not needed
  EXPECT_EQ(d.vehicle_type[0], 0u);
  EXPECT_FLOAT_EQ(d.types.length[0], 4.5f);
  EXPECT_FLOAT_EQ(d.types.delta[0], 2.5f);
  EXPECT_FLOAT_EQ(d.types.delta[1], 4.0f);
  EXPECT_EQ(d.types.car_follow_model[0], "IDM");
  EXPECT_EQ(d.types.index.at("unused"), 1u);

  spec.vtypes[0].params["delta"] = "fast";
  EXPECT_NE(error_of(spec, corridor).find("delta 'fast'"), std::string::npos);
}

TEST_F(DemandBuilderTest, CarFollowModelIsTheVTypesElseTheDefault) {
  DemandSpec spec;
  auto named = [](const std::string& id, const std::string& model) {
    VTypeSpec t = vtype(id);
    t.car_follow_model = model;
    t.car_follow_model_given = true;
    return t;
  };
  spec.vtypes = {named("idm", "IDM"), named("krauss", "Krauss"), named("eidm", "EIDM"), vtype("plain")};
  VehicleSpec v = on_edges("v", 0, {"E0"});  // no type: DEFAULT_VEHTYPE, which names no model either
  spec.vehicles = {v};
  for (const std::string default_model : {"Krauss", "IDM", "W99"}) {
    SCOPED_TRACE(default_model);
    DemandOptions opt;
    opt.default_car_follow_model = default_model;
    const Demand d = build_demand(spec, corridor, opt);
    ASSERT_EQ(d.types.size(), 5u);
    const uint8_t default_runs = default_model == "Krauss" ? kCarFollowKrauss : kCarFollowIdm;
    const std::vector<std::string> names{"IDM", "Krauss", "EIDM", default_model, default_model};
    const std::vector<uint8_t> runs{kCarFollowIdm, kCarFollowKrauss, kCarFollowIdm, default_runs,
                                    default_runs};
    EXPECT_EQ(d.types.car_follow_model, names);
    EXPECT_EQ(d.types.model, runs);
  }
  // SUMO's default without options: Krauss.
  EXPECT_EQ(build_demand(spec, corridor, {}).types.model[3], kCarFollowKrauss);
}

// A flow of n vehicles of type/route distribution `dist`.
FlowSpec many(const std::string& id, int64_t n) {
  FlowSpec f;
  f.id = id;
  f.number = n;
  f.period = 1;
  f.loc = at(40);
  return f;
}

TEST_F(DemandBuilderTest, VTypeDistributionDrawsByWeightAndSeed) {
  DemandSpec spec;
  spec.vtypes = {vtype("slow"), vtype("fast")};
  spec.vtype_dists.push_back({"mix", {{"slow", 1.0}, {"fast", 3.0}}, at(3)});
  FlowSpec f = many("f", 4000);
  f.type = "mix";
  f.edges = {"E0"};
  spec.flows = {f};
  Demand a = build_demand(spec, corridor, {});
  ASSERT_EQ(a.size(), 4000u);
  size_t fast = 0;
  for (uint32_t t : a.vehicle_type) fast += t == a.types.index.at("fast");
  EXPECT_NEAR(static_cast<double>(fast) / 4000, 0.75, 0.03);
  EXPECT_EQ(build_demand(spec, corridor, {}).vehicle_type, a.vehicle_type);
  DemandOptions other;
  other.seed = 99;
  EXPECT_NE(build_demand(spec, corridor, other).vehicle_type, a.vehicle_type);
}

TEST_F(DemandBuilderTest, RouteDistributionDrawsByWeightAndSharesStorage) {
  DemandSpec spec;
  spec.routes = {route("short", {"E0"}), route("long", {"E0", "E1", "E2"}), route("never", {"E1"})};
  spec.route_dists.push_back({"rd", {{"short", 0.2}, {"long", 0.8}, {"never", 0.0}}, at(7)});
  FlowSpec f = many("f", 4000);
  f.route = "rd";
  spec.flows = {f};
  Demand a = build_demand(spec, corridor, {});
  ASSERT_EQ(a.size(), 4000u);
  size_t longer = 0;
  for (uint32_t v = 0; v < a.size(); ++v) longer += a.route_length[v] == 3;
  EXPECT_NEAR(static_cast<double>(longer) / 4000, 0.8, 0.03);
  EXPECT_EQ(a.route_edges.size(), 4u);  // each used route stored once; "never" never drawn
  EXPECT_EQ(build_demand(spec, corridor, {}).route_begin, a.route_begin);
  DemandOptions other;
  other.seed = 5;
  EXPECT_NE(build_demand(spec, corridor, other).route_begin, a.route_begin);
}

TEST_F(DemandBuilderTest, SpeedFactorsFollowTheTypeAndTheVehicleId) {
  DemandSpec spec;
  VTypeSpec fixed = vtype("fixed");
  fixed.speed_factor = 1.2;
  fixed.speed_dev = 0;
  VTypeSpec wild = vtype("wild");
  wild.speed_dev = 3;  // most of the normal lies outside [0.2, 2]: redrawn into the bounds
  spec.vtypes = {fixed, wild};
  FlowSpec normal = many("n", 3000), f = many("f", 20), w = many("w", 500);
  normal.edges = f.edges = w.edges = {"E0"};
  f.type = "fixed";
  w.type = "wild";
  spec.flows = {normal, f, w};
  Demand d = build_demand(spec, corridor, {});
  double sum = 0, sum2 = 0;
  int n = 0;
  for (uint32_t v = 0; v < d.size(); ++v) {
    const float sf = d.speed_factor[v];
    EXPECT_GE(sf, 0.2f);
    EXPECT_LE(sf, 2.0f);
    const std::string& type = d.types.id[d.vehicle_type[v]];
    if (type == "fixed") {
      EXPECT_FLOAT_EQ(sf, 1.2f);
    }
    if (type == "DEFAULT_VEHTYPE") {
      sum += sf;
      sum2 += sf * sf;
      ++n;
    }
  }
  ASSERT_EQ(n, 3000);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_NEAR(sd, 0.1, 0.01);

  // Keyed by id, not by position: the same vehicle keeps its factor when others come and go.
  DemandSpec alone;
  FlowSpec later = many("n", 3000);
  later.edges = {"E0"};
  alone.vehicles = {on_edges("x", 0, {"E0"})};
  alone.flows = {later};
  Demand e = build_demand(alone, corridor, {});
  EXPECT_EQ(e.speed_factor[index_of(e, "n.1234")], d.speed_factor[index_of(d, "n.1234")]);
}

// --- depart attributes ---

TEST_F(DemandBuilderTest, DepartAttributesAreCopiedAndNegativePositionsCountFromTheEnd) {
  DemandSpec spec;
  VehicleSpec v = on_edges("v", 0, {"E0", "E1"});
  v.depart_spec.lane = DepartLane::Given;
  v.depart_spec.lane_index = 1;
  v.depart_spec.pos = DepartPos::Given;
  v.depart_spec.pos_value = -10;
  v.depart_spec.speed = DepartSpeed::Given;
  v.depart_spec.speed_value = 7.5;
  v.depart_spec.arrival = ArrivalPos::Given;
  v.depart_spec.arrival_value = -5;
  VehicleSpec w = on_edges("w", 0, {"E2"});
  w.depart_spec.lane = DepartLane::Best;
  w.depart_spec.pos = DepartPos::Free;
  w.depart_spec.speed = DepartSpeed::Max;
  w.depart_spec.arrival = ArrivalPos::Random;
  spec.vehicles = {v, w};
  Demand d = build_demand(spec, corridor, {});
  EXPECT_EQ(d.depart_lane_kind[0], static_cast<uint8_t>(DepartLane::Given));
  EXPECT_EQ(d.depart_lane[0], 1);
  EXPECT_EQ(d.depart_pos_kind[0], static_cast<uint8_t>(DepartPos::Given));
  EXPECT_FLOAT_EQ(d.depart_pos[0], 90.0f);
  EXPECT_EQ(d.depart_speed_kind[0], static_cast<uint8_t>(DepartSpeed::Given));
  EXPECT_FLOAT_EQ(d.depart_speed[0], 7.5f);
  EXPECT_FLOAT_EQ(d.arrival_pos[0], 95.0f);
  EXPECT_EQ(d.depart_lane_kind[1], static_cast<uint8_t>(DepartLane::Best));
  EXPECT_EQ(d.depart_pos_kind[1], static_cast<uint8_t>(DepartPos::Free));
  EXPECT_EQ(d.depart_speed_kind[1], static_cast<uint8_t>(DepartSpeed::Max));
  EXPECT_EQ(d.arrival_pos_kind[1], static_cast<uint8_t>(ArrivalPos::Random));
}

TEST_F(DemandBuilderTest, DepartLaneIsMappedAmongLanesAndCheckedForTheClass) {
  Network cross = build_network(test::make_signal_spec(/*bus_lane=*/true));
  DemandSpec spec;
  VehicleSpec v = on_edges("v", 0, {"WtoC", "CtoE"}, 12);
  v.depart_spec.lane = DepartLane::Given;
  v.depart_spec.lane_index = 1;  // SUMO index of the car lane next to the bus lane
  spec.vehicles = {v};
  Demand d = build_demand(spec, cross, {});
  EXPECT_EQ(d.depart_lane[0], 1);               // the bus lane is kept, at rank 0
  spec.vehicles[0].depart_spec.lane_index = 0;  // the bus lane: not for a passenger car
  const std::string msg = error_of(spec, cross);
  EXPECT_NE(msg.find("test.rou.xml:12"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'v'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("WtoC"), std::string::npos) << msg;
  spec.vehicles[0].depart_spec.lane_index = 2;
  EXPECT_NE(error_of(spec, cross).find("departLane 2"), std::string::npos);
}

// --- ordering ---

TEST_F(DemandBuilderTest, VehiclesAreSortedByDepartStably) {
  DemandSpec spec;
  spec.vehicles = {on_edges("a", 5, {"E0"}), on_edges("b", 1, {"E0"}), on_edges("c", 5, {"E0"}),
                   on_edges("d", 1, {"E0"}), on_edges("e", 2, {"E0"})};
  FlowSpec f = flow("f", {"E1"});
  f.period = 2;
  f.end = 7;
  spec.flows = {f};
  Demand d = build_demand(spec, corridor, {});
  EXPECT_EQ(d.vehicle_id, (std::vector<std::string>{"f.0", "b", "d", "e", "f.1", "f.2", "a", "c", "f.3"}));
  EXPECT_EQ(d.depart, (std::vector<double>{0, 1, 1, 2, 2, 4, 5, 5, 6}));
}

// --- errors ---

TEST_F(DemandBuilderTest, UnknownIdsNameTheVehicleAndTheLine) {
  auto expect_error = [&](const DemandSpec& spec, std::vector<std::string> parts) {
    const std::string msg = error_of(spec, corridor);
    ASSERT_FALSE(msg.empty());
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  };
  DemandSpec type;
  VehicleSpec v = on_edges("v7", 0, {"E0"}, 17);
  v.type = "truck";
  type.vehicles = {v};
  expect_error(type, {"test.rou.xml:17", "'truck'", "'v7'"});

  DemandSpec unknown_route;
  unknown_route.vehicles = {on_route("v8", 0, "nowhere", 18)};
  expect_error(unknown_route, {"test.rou.xml:18", "'nowhere'", "'v8'"});

  DemandSpec unknown_edge;
  unknown_edge.vehicles = {on_edges("v9", 0, {"E0", "E9"}, 19)};
  expect_error(unknown_edge, {"test.rou.xml:19", "'E9'", "'v9'"});

  DemandSpec named_unknown_edge;
  named_unknown_edge.routes = {route("r", {"E0", "X"}, 4)};
  named_unknown_edge.vehicles = {on_route("v10", 0, "r")};
  expect_error(named_unknown_edge, {"test.rou.xml:4", "'X'", "route 'r'", "'v10'"});

  DemandSpec gap;
  gap.vehicles = {on_edges("v11", 0, {"E0", "E2"}, 21)};
  expect_error(gap, {"test.rou.xml:21", "'E0'", "'E2'", "'v11'"});

  DemandSpec no_path;
  no_path.vehicles = {trip("t12", 0, "E3", "E0", 22)};
  expect_error(no_path, {"test.rou.xml:22", "no route from edge 'E3' to edge 'E0' for trip 't12'"});

  DemandSpec bad_junction;
  VehicleSpec j = vehicle("t13", 0, 23);
  j.from_junction = "K0";
  j.to_junction = "Q";
  bad_junction.vehicles = {j};
  expect_error(bad_junction, {"test.rou.xml:23", "'Q'", "'t13'"});

  DemandSpec routeless;
  routeless.vehicles = {vehicle("v14", 0, 24)};
  expect_error(routeless, {"test.rou.xml:24", "'v14'"});

  DemandSpec twice;
  twice.vehicles = {on_edges("v15", 0, {"E0"}, 25), on_edges("v15", 1, {"E1"}, 26)};
  expect_error(twice, {"test.rou.xml:26", "duplicate", "'v15'"});

  DemandSpec clash;  // a flow's generated id taken by a vehicle
  FlowSpec f = flow("f", {"E0"}, 28);
  f.number = 2;
  f.period = 1;
  clash.flows = {f};
  clash.vehicles = {on_edges("f.1", 0, {"E0"})};
  expect_error(clash, {"test.rou.xml:28", "duplicate", "'f.1'"});

  DemandSpec bad_dist;
  bad_dist.vtype_dists.push_back({"d", {{"ghost", 1}}, at(27)});
  expect_error(bad_dist, {"test.rou.xml:27", "'ghost'", "'d'"});
}

TEST_F(DemandBuilderTest, InternalEdgesAreNotDrivable) {
  test::GridOptions o;
  o.with_internal = true;
  Network net = build_network(test::make_grid_spec(2, 2, o));
  std::string internal;
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (net.edge_is_internal[e]) internal = net.edge_id[e];
  ASSERT_FALSE(internal.empty());
  DemandSpec spec;
  spec.vehicles = {on_edges("v", 0, {internal}, 30)};
  const std::string msg = error_of(spec, net);
  EXPECT_NE(msg.find(internal), std::string::npos) << msg;
  EXPECT_NE(msg.find("internal"), std::string::npos) << msg;
}

TEST_F(DemandBuilderTest, IgnoredRouteErrorsSkipAndRecord) {
  DemandSpec spec;
  spec.routes = {route("broken", {"E0", "E2"})};
  FlowSpec f = flow("f", {});
  f.route = "broken";
  f.number = 2;
  f.period = 1;
  spec.flows = {f};
  spec.vehicles = {on_edges("ok", 3, {"E0", "E1"}), trip("lost", 0, "E3", "E0", 40),
                   on_edges("gap", 0, {"E1", "E3"}, 41), on_edges("ghost", 0, {"E7"}, 42)};
  spec.skipped["person"] = 2;
  DemandOptions opt;
  opt.ignore_route_errors = true;
  Demand d = build_demand(spec, corridor, opt);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d.vehicle_id[0], "ok");
  ASSERT_EQ(d.unroutable.size(), 5u);
  std::vector<std::string> ids;
  for (const auto& s : d.unroutable) ids.push_back(s.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"lost", "gap", "ghost", "f.0", "f.1"}));
  EXPECT_NE(d.unroutable[0].reason.find("no route from edge 'E3' to edge 'E0'"), std::string::npos);
  EXPECT_EQ(d.unroutable[0].loc.line, 40);
  EXPECT_NE(d.unroutable[1].reason.find("'E3'"), std::string::npos);
  EXPECT_NE(d.unroutable[2].reason.find("'E7'"), std::string::npos);
  EXPECT_EQ(d.unsupported.at("person"), 2);
}

TEST_F(DemandBuilderTest, LargeFlowsBuildQuickly) {
  DemandSpec spec;
  FlowSpec a = many("a", 150000), b = many("b", 150000);
  a.edges = {"E0", "E1"};
  b.from = "E1";
  b.to = "E3";
  b.begin = 0.5;
  spec.flows = {a, b};
  Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 300000u);
  EXPECT_EQ(d.route_edges.size(), 5u);
  EXPECT_EQ(d.vehicle_id[0], "a.0");
  EXPECT_EQ(d.vehicle_id[1], "b.0");
  EXPECT_EQ(d.vehicle_id.back(), "b.149999");
}

}  // namespace
}  // namespace lpsim

// --- scheduled stops ---

namespace lpsim {
namespace {

StopSpec stop_on(const std::string& lane, double end_pos, double duration, double until = -1, int line = 11) {
  StopSpec s;
  s.lane = lane;
  s.end_pos = end_pos;
  s.duration = duration;
  s.until = until;
  s.loc = at(line);
  return s;
}

StopSpec stop_at_place(const std::string& place, double duration) {
  StopSpec s;
  s.stopping_place = place;
  s.duration = duration;
  s.loc = at(12);
  return s;
}

StoppingPlaceSpec bus_stop(const std::string& id, const std::string& lane, double start, double end) {
  StoppingPlaceSpec p;
  p.id = id;
  p.lane = lane;
  p.start_pos = start;
  p.end_pos = end;
  p.loc = {"s.add.xml", 3};
  return p;
}

TEST_F(DemandBuilderTest, StopsArePlacedAlongTheRouteAsSumoPlacesThem) {
  DemandSpec spec;
  spec.stopping_places = {bus_stop("bs", "E1_0", 20, 40), bus_stop("end", "E3_1", -30, -1)};
  RouteSpec r = route("r", {"E0", "E1", "E2", "E3"});
  r.stops = {stop_on("E0_1", -1, 4)};  // a route's stops come before the vehicle's own
  spec.routes = {r};
  VehicleSpec v = on_route("v", 0, "r");
  v.stops = {stop_at_place("bs", 20), stop_on("E2_0", 50, 0, 300), stop_at_place("end", 5)};
  spec.vehicles = {v};
  const Demand d = build_demand(spec, corridor, {});
  const StopTable& st = d.stops;
  ASSERT_EQ(st.size(), 4u);
  EXPECT_EQ(st.first(0), 0u);
  EXPECT_EQ(st.last(0), 4u);
  EXPECT_EQ(st.route_pos, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(corridor.lane_id[st.lane[0]], "E0_1");
  EXPECT_FLOAT_EQ(st.end_pos[0], 99.0f);  // negative: from the lane's end
  // SUMO's default startPos is 0.2 m before endPos as given, before a negative endPos counts from the
  // lane's end (measured: endPos -10 alone is [0, 90] on a 100 m lane).
  EXPECT_FLOAT_EQ(st.start_pos[0], 0.0f);
  EXPECT_FLOAT_EQ(st.start_pos[1], 20.0f);
  EXPECT_FLOAT_EQ(st.end_pos[1], 40.0f);
  EXPECT_DOUBLE_EQ(st.duration[1], 20);
  EXPECT_DOUBLE_EQ(st.until[1], -1);
  EXPECT_DOUBLE_EQ(st.until[2], 300);
  EXPECT_FLOAT_EQ(st.start_pos[3], 70.0f);
  EXPECT_FLOAT_EQ(st.end_pos[3], 99.0f);
}

TEST_F(DemandBuilderTest, AStopOnAnEdgeVisitedTwiceIsOnTheOccurrenceAfterTheStopBefore) {
  DemandSpec spec;
  const std::string a = test::grid_edge(0, 0, 1, 0), b = test::grid_edge(1, 0, 1, 1),
                    c = test::grid_edge(1, 1, 0, 1), e = test::grid_edge(0, 1, 0, 0);
  VehicleSpec v = on_edges("loop", 0, {a, b, c, e, a, b});
  // Further along the same edge: the same occurrence; back on it: its next one.
  v.stops = {stop_on(test::lane_of(a, 0), 30, 1), stop_on(test::lane_of(a, 0), 60, 1),
             stop_on(test::lane_of(a, 0), 10, 1), stop_on(test::lane_of(b, 0), 50, 1)};
  spec.vehicles = {v};
  const Demand d = build_demand(spec, grid, {});
  EXPECT_EQ(d.stops.route_pos, (std::vector<uint32_t>{0, 0, 4, 5}));
}

TEST_F(DemandBuilderTest, FlowUntilIsLaterForEachVehicleByItsDepartOffset) {
  DemandSpec spec;
  FlowSpec f = flow("f", {"E0", "E1"});
  f.begin = 100;
  f.end = 130;
  f.period = 10;
  f.stops = {stop_on("E1_0", 50, 0, 200)};
  spec.flows = {f};
  const Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.size(), 3u);
  for (uint32_t v = 0; v < 3; ++v) {
    ASSERT_EQ(d.stops.last(v) - d.stops.first(v), 1u);
    EXPECT_DOUBLE_EQ(d.stops.until[d.stops.first(v)], 200 + 10.0 * v) << v;
  }
}

TEST_F(DemandBuilderTest, ATripIsRoutedThroughItsStops) {
  DemandSpec spec;
  const std::string from = test::grid_edge(0, 0, 1, 0);
  const std::string detour = test::grid_edge(1, 1, 2, 1);
  VehicleSpec t = trip("t", 0, from, test::grid_edge(2, 1, 2, 0));
  t.stops = {stop_on(test::lane_of(detour, 0), 50, 5)};
  spec.vehicles = {t};
  const Demand d = build_demand(spec, grid, {});
  const std::vector<std::string> r = route_ids(d, grid, 0);
  ASSERT_EQ(d.stops.size(), 1u);
  EXPECT_EQ(r[d.stops.route_pos[0]], detour);
}

TEST_F(DemandBuilderTest, StopsThatCannotBeMadeAreErrorsNamingTheVehicle) {
  DemandSpec spec;
  VehicleSpec v = on_edges("v", 0, {"E1", "E2"});
  v.stops = {stop_on("E0_0", 50, 5)};
  spec.vehicles = {v};
  EXPECT_EQ(error_of(spec, corridor),
            "test.rou.xml:10: vehicle 'v': stop on lane 'E0_0' is not downstream the current route");
  spec.vehicles[0].stops = {stop_on("E2_0", 50, 5), stop_on("E1_0", 50, 5)};  // out of order
  EXPECT_NE(error_of(spec, corridor).find("not downstream"), std::string::npos);
  spec.vehicles[0].stops = {stop_at_place("nowhere", 5)};
  EXPECT_EQ(error_of(spec, corridor), "test.rou.xml:12: stop: unknown stopping place 'nowhere'");
  spec.vehicles[0].stops = {stop_on("E1_7", 50, 5)};
  EXPECT_NE(error_of(spec, corridor).find("test.rou.xml:11: stop: unknown lane 'E1_7'"), std::string::npos);
  spec.vehicles[0].stops = {};
  spec.stopping_places = {bus_stop("bs", "E1_0", 90, 120)};
  EXPECT_NE(error_of(spec, corridor).find("s.add.xml:3: stopping place 'bs': invalid position"),
            std::string::npos);
  spec.stopping_places[0].friendly_pos = true;  // moved onto the lane instead
  EXPECT_EQ(error_of(spec, corridor), "");
}

TEST_F(DemandBuilderTest, AStopOffItsLaneIsDroppedAndCountedAsSumoDropsIt) {
  // SUMO 1.15 reports "Invalid start or end position for stop on lane" and runs on without the stop; with
  // friendlyPos it moves the stop onto the lane (to its end) instead.
  DemandSpec spec;
  VehicleSpec v = on_edges("v", 0, {"E1", "E2"});
  v.stops = {stop_on("E1_0", 150, 5), stop_on("E2_0", 50, 5)};
  spec.vehicles = {v};
  const Demand d = build_demand(spec, corridor, {});
  ASSERT_EQ(d.stops.size(), 1u);
  EXPECT_EQ(corridor.lane_id[d.stops.lane[0]], "E2_0");
  EXPECT_EQ(d.unsupported.at("stop (position off its lane, dropped as SUMO drops it)"), 1);
  spec.vehicles[0].stops[0].friendly_pos = true;
  const Demand f = build_demand(spec, corridor, {});
  ASSERT_EQ(f.stops.size(), 2u);
  EXPECT_FLOAT_EQ(f.stops.end_pos[0], corridor.lane_length[f.stops.lane[0]]);
  EXPECT_EQ(f.unsupported.count("stop (position off its lane, dropped as SUMO drops it)"), 0u);
}

}  // namespace
}  // namespace lpsim

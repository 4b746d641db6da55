#include "converters/route_reader.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>

#include "temp_dir.hpp"

namespace lpsim {
namespace {

class RouteReaderTest : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& body) const { return tmp_.write(name, body); }
  std::string routes(const std::string& inner, const std::string& name = "r.rou.xml") {
    return write(name, "<routes>\n" + inner + "\n</routes>\n");
  }
  void read(const std::string& path, bool sorted_by_depart = false) {
    read_sumo_routes(path, demand_, additional_, sorted_by_depart);
  }

  // Reads `inner` (placed on line 2) and returns the InputError message; fails the test if none is raised.
  std::string error_of(const std::string& inner) {
    std::string path = routes(inner);
    try {
      read(path);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << inner;
    return "";
  }

  test::TempDir tmp_{"lpsim_routes"};
  DemandSpec demand_;
  AdditionalSpec additional_;
};

// SUMO reads route files ahead by departure time (--route-steps > 0) and ignores a vehicle, trip or flow
// departing before the last one registered; public transport ('line') does not move the mark, nor does an
// empty flow. Add-files and --route-steps 0 load every one.
TEST_F(RouteReaderTest, UnsortedDeparturesAreIgnoredAsSumoIgnoresThem) {
  const std::string path = routes(R"X(<vehicle id="a" depart="10"><route edges="e"/></vehicle>
  <flow id="f" begin="20" end="30" period="5"><route edges="e"/></flow>
  <vehicle id="late" depart="15"><route edges="e"/></vehicle>
  <flow id="pt" begin="100" end="200" period="50" line="7"><route edges="e"/></flow>
  <trip id="t" depart="20" from="e" to="e"/>
  <flow id="none" begin="500" end="600" number="0"><route edges="e"/></flow>
  <flow id="g" begin="5" end="60" period="5"><route edges="e"/></flow>
  <vehicle id="b" depart="20"><route edges="e"/></vehicle>)X");
  read(path, true);
  std::vector<std::string> vehicles, flows;
  for (const auto& v : demand_.vehicles) vehicles.push_back(v.id);
  for (const auto& f : demand_.flows) flows.push_back(f.id);
  EXPECT_EQ(vehicles, (std::vector<std::string>{"a", "t", "b"}));
  EXPECT_EQ(flows, (std::vector<std::string>{"f", "pt", "none"}));
  EXPECT_EQ(demand_.unsorted_ignored, 2);
  EXPECT_EQ(demand_.first_unsorted_ignored, "late");
  EXPECT_EQ(demand_.first_unsorted_loc.line, 4);

  demand_ = DemandSpec{};
  read(path, false);
  EXPECT_EQ(demand_.vehicles.size(), 4u);
  EXPECT_EQ(demand_.flows.size(), 4u);
  EXPECT_EQ(demand_.unsorted_ignored, 0);
}

TEST_F(RouteReaderTest, VTypeAttributesDefaultsAndParams) {
  read(routes(R"X(<vType id="a" length="4.5" minGap="1.5" accel="3" decel="5" emergencyDecel="8" maxSpeed="30"
      speedFactor="normc(1.1,0.2,0.2,2)" tau="1.2" sigma="0.3" vClass="passenger" color="red" lcStrategic="2">
    <param key="k1" value="v1"/>
  </vType>
  <vType id="b"/>
  <vType id="c" speedFactor="1.2"/>
  <vType id="d" speedDev="0.05" speedFactor="norm(0.9,0.3)"/>
  <vType id="bus" vClass="bus" maxSpeed="20"/>
  <vType id="idm"><carFollowing-IDM accel="1.5" delta="3"/></vType>
  <vType id="m" carFollowModel="IDM"/>)X"));
  ASSERT_EQ(demand_.vtypes.size(), 7u);
  const auto& a = demand_.vtypes[0];
  EXPECT_EQ(a.id, "a");
  EXPECT_DOUBLE_EQ(a.length, 4.5);
  EXPECT_DOUBLE_EQ(a.min_gap, 1.5);
  EXPECT_DOUBLE_EQ(a.accel, 3);
  EXPECT_DOUBLE_EQ(a.decel, 5);
  EXPECT_DOUBLE_EQ(a.emergency_decel, 8);
  EXPECT_DOUBLE_EQ(a.max_speed, 30);
  EXPECT_DOUBLE_EQ(a.speed_factor, 1.1);
  EXPECT_DOUBLE_EQ(a.speed_dev, 0.2);
  EXPECT_TRUE(a.speed_dev_given);
  EXPECT_DOUBLE_EQ(a.tau, 1.2);
  EXPECT_DOUBLE_EQ(a.sigma, 0.3);
  EXPECT_EQ(a.params.at("color"), "red");
  EXPECT_EQ(a.params.at("lcStrategic"), "2");
  EXPECT_EQ(a.params.at("k1"), "v1");
  EXPECT_EQ(a.loc.line, 3);  // the line where a multi-line start tag ends, as SUMO reports it

  const auto& b = demand_.vtypes[1];
  EXPECT_DOUBLE_EQ(b.length, 5.0);
  EXPECT_DOUBLE_EQ(b.accel, 2.6);
  EXPECT_DOUBLE_EQ(b.speed_dev, 0.1);
  EXPECT_FALSE(b.speed_dev_given);
  EXPECT_EQ(b.car_follow_model, "Krauss");
  EXPECT_EQ(b.vclass, "passenger");

  // A plain speedFactor keeps the default deviation (SUMO 1.15); speedDev beats the distribution's.
  EXPECT_DOUBLE_EQ(demand_.vtypes[2].speed_factor, 1.2);
  EXPECT_DOUBLE_EQ(demand_.vtypes[2].speed_dev, 0.1);
  EXPECT_FALSE(demand_.vtypes[2].speed_dev_given);
  EXPECT_DOUBLE_EQ(demand_.vtypes[3].speed_factor, 0.9);
  EXPECT_DOUBLE_EQ(demand_.vtypes[3].speed_dev, 0.05);

  const auto& bus = demand_.vtypes[4];
  EXPECT_DOUBLE_EQ(bus.length, 12);
  EXPECT_DOUBLE_EQ(bus.accel, 1.2);
  EXPECT_DOUBLE_EQ(bus.decel, 4.0);
  EXPECT_DOUBLE_EQ(bus.max_speed, 20);
  EXPECT_DOUBLE_EQ(bus.speed_dev, 0.0);

  const auto& idm = demand_.vtypes[5];
  EXPECT_EQ(idm.car_follow_model, "IDM");
  EXPECT_DOUBLE_EQ(idm.accel, 1.5);
  EXPECT_EQ(idm.params.at("delta"), "3");
  EXPECT_EQ(demand_.vtypes[6].car_follow_model, "IDM");
}

TEST_F(RouteReaderTest, ABicyclesDesiredMaxSpeedIsSumosUnlessAMaxSpeedIsGiven) {
  // SUMO 1.15 (traci.vehicle.getAllowedSpeed on a 100 km/h lane): a default bicycle rides at 20 km/h times
  // its speed factor (desiredMaxSpeed) though its maxSpeed is 50 km/h; a maxSpeed given lifts that limit;
  // desiredMaxSpeed given sets it, for any class.
  read(routes(R"X(<vType id="bike" vClass="bicycle"/>
  <vType id="fast" vClass="bicycle" maxSpeed="10"/>
  <vType id="slow" vClass="bicycle" desiredMaxSpeed="4"/>
  <vType id="car" desiredMaxSpeed="10"/>
  <vType id="plain"/>)X"));
  ASSERT_EQ(demand_.vtypes.size(), 5u);
  EXPECT_DOUBLE_EQ(demand_.vtypes[0].max_speed, 50 / 3.6);
  EXPECT_DOUBLE_EQ(demand_.vtypes[0].desired_max_speed, 20 / 3.6);
  EXPECT_DOUBLE_EQ(demand_.vtypes[1].max_speed, 10);
  EXPECT_TRUE(std::isinf(demand_.vtypes[1].desired_max_speed));
  EXPECT_DOUBLE_EQ(demand_.vtypes[2].desired_max_speed, 4);
  EXPECT_DOUBLE_EQ(demand_.vtypes[3].desired_max_speed, 10);
  EXPECT_TRUE(std::isinf(demand_.vtypes[4].desired_max_speed));
}

TEST_F(RouteReaderTest, VTypeDistributions) {
  read(routes(R"X(<vTypeDistribution id="mix">
    <vType id="p1" length="4" probability="0.4"/>
    <vType id="p2" length="6"/>
  </vTypeDistribution>
  <vTypeDistribution id="ref" vTypes="p1 p2" probabilities="0.3 0.7"/>)X"));
  ASSERT_EQ(demand_.vtypes.size(), 2u);
  EXPECT_DOUBLE_EQ(demand_.vtypes[1].length, 6);
  ASSERT_EQ(demand_.vtype_dists.size(), 2u);
  const auto& mix = demand_.vtype_dists[0];
  EXPECT_EQ(mix.id, "mix");
  ASSERT_EQ(mix.members.size(), 2u);
  EXPECT_EQ(mix.members[0].id, "p1");
  EXPECT_DOUBLE_EQ(mix.members[0].probability, 0.4);
  EXPECT_DOUBLE_EQ(mix.members[1].probability, 1.0);
  const auto& ref = demand_.vtype_dists[1];
  ASSERT_EQ(ref.members.size(), 2u);
  EXPECT_EQ(ref.members[1].id, "p2");
  EXPECT_DOUBLE_EQ(ref.members[1].probability, 0.7);
}

TEST_F(RouteReaderTest, RoutesAndRouteDistributions) {
  read(routes(R"X(<route id="r1" edges="a b  c "/>
  <route id="r2" edges="d"/>
  <routeDistribution id="rd" routes="r1 r2" probabilities="1 3"/>
  <routeDistribution id="nested">
    <route edges="x y" probability="0.25"/>
    <route id="named" edges="z" probability="0.75"/>
    <route refId="r1" probability="2"/>
  </routeDistribution>)X"));
  ASSERT_EQ(demand_.routes.size(), 4u);
  EXPECT_EQ(demand_.routes[0].edges, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(demand_.routes[2].id, "nested#0");
  EXPECT_EQ(demand_.routes[2].edges, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(demand_.routes[3].id, "named");
  ASSERT_EQ(demand_.route_dists.size(), 2u);
  EXPECT_DOUBLE_EQ(demand_.route_dists[0].members[1].probability, 3);
  const auto& nested = demand_.route_dists[1];
  ASSERT_EQ(nested.members.size(), 3u);
  EXPECT_EQ(nested.members[0].id, "nested#0");
  EXPECT_DOUBLE_EQ(nested.members[0].probability, 0.25);
  EXPECT_EQ(nested.members[1].id, "named");
  EXPECT_EQ(nested.members[2].id, "r1");
  EXPECT_DOUBLE_EQ(nested.members[2].probability, 2);
}

TEST_F(RouteReaderTest, VehiclesTripsAndInlineRoutes) {
  read(routes(
      R"X(<vehicle id="v1" type="t" depart="1:00:05" route="r1" departLane="2" departPos="12.5" departSpeed="3" arrivalPos="-1"/>
  <vehicle id="v2" depart="7.5" departLane="best" departPos="random_free" departSpeed="max" arrivalPos="random">
    <route edges="e1 e2"/>
    <stop lane="e2_0" duration="10"/>
  </vehicle>
  <trip id="t1" depart="3" from=" e1 " to="e3" via="e2 e5"/>
  <trip id="t2" depart="4" fromJunction="J1" toJunction="J2"/>
  <vehicle id="v3" depart="0"><routeDistribution><route edges="a" probability="1"/><route edges="b"/></routeDistribution></vehicle>)X"));
  ASSERT_EQ(demand_.vehicles.size(), 5u);
  const auto& v1 = demand_.vehicles[0];
  EXPECT_EQ(v1.id, "v1");
  EXPECT_EQ(v1.type, "t");
  EXPECT_DOUBLE_EQ(v1.depart, 3605);
  EXPECT_EQ(v1.route, "r1");
  EXPECT_EQ(v1.source, DemandSource::Vehicle);
  EXPECT_EQ(v1.depart_spec.lane, DepartLane::Given);
  EXPECT_EQ(v1.depart_spec.lane_index, 2);
  EXPECT_EQ(v1.depart_spec.pos, DepartPos::Given);
  EXPECT_DOUBLE_EQ(v1.depart_spec.pos_value, 12.5);
  EXPECT_EQ(v1.depart_spec.speed, DepartSpeed::Given);
  EXPECT_DOUBLE_EQ(v1.depart_spec.speed_value, 3);
  EXPECT_EQ(v1.depart_spec.arrival, ArrivalPos::Given);
  EXPECT_DOUBLE_EQ(v1.depart_spec.arrival_value, -1);
  EXPECT_EQ(v1.loc.line, 2);

  const auto& v2 = demand_.vehicles[1];
  EXPECT_TRUE(v2.route.empty());
  // A vehicle's nested route is interned: its edges are indices into the distinct edge ids.
  EXPECT_TRUE(v2.edges.empty());
  ASSERT_EQ(v2.edge_ref_count, 2u);
  std::vector<std::string> v2_edges;
  for (uint32_t k = 0; k < v2.edge_ref_count; ++k)
    v2_edges.push_back(demand_.edge_names.at(demand_.edge_refs.at(v2.edge_ref_begin + k)));
  EXPECT_EQ(v2_edges, (std::vector<std::string>{"e1", "e2"}));
  EXPECT_EQ(v2.depart_spec.lane, DepartLane::Best);
  EXPECT_EQ(v2.depart_spec.pos, DepartPos::RandomFree);
  EXPECT_EQ(v2.depart_spec.speed, DepartSpeed::Max);
  EXPECT_EQ(v2.depart_spec.arrival, ArrivalPos::Random);
  ASSERT_EQ(v2.stops.size(), 1u);
  EXPECT_EQ(v2.stops[0].lane, "e2_0");
  EXPECT_DOUBLE_EQ(v2.stops[0].duration, 10);
  EXPECT_DOUBLE_EQ(v2.stops[0].until, -1);
  EXPECT_FALSE(v2.stops[0].end_pos.has_value());
  EXPECT_EQ(v2.stops[0].loc.line, 5);
  EXPECT_EQ(demand_.skipped.count("stop"), 0u);

  const auto& t1 = demand_.vehicles[2];
  EXPECT_EQ(t1.source, DemandSource::Trip);
  EXPECT_EQ(t1.from, "e1");
  EXPECT_EQ(t1.to, "e3");
  EXPECT_EQ(t1.via, (std::vector<std::string>{"e2", "e5"}));
  EXPECT_EQ(t1.depart_spec.lane, DepartLane::First);
  EXPECT_EQ(t1.depart_spec.pos, DepartPos::Base);
  EXPECT_EQ(t1.depart_spec.speed, DepartSpeed::Zero);
  EXPECT_EQ(t1.depart_spec.arrival, ArrivalPos::Max);
  EXPECT_EQ(demand_.vehicles[3].from_junction, "J1");
  EXPECT_EQ(demand_.vehicles[3].to_junction, "J2");

  const auto& v3 = demand_.vehicles[4];
  EXPECT_EQ(v3.route, "!v3");
  ASSERT_EQ(demand_.route_dists.size(), 1u);
  EXPECT_EQ(demand_.route_dists[0].members[1].id, "!v3#1");
}

TEST_F(RouteReaderTest, FlowsOfEachKind) {
  read(routes(R"X(<flow id="p" begin="10" end="100" period="5" route="r1" departSpeed="desired"/>
  <flow id="h" begin="0:01:00" end="1:00:00" vehsPerHour="600" from="a" to="b" via="c"/>
  <flow id="ph" end="50" perHour="60" fromJunction="J1" toJunction="J2"/>
  <flow id="pr" begin="0" end="10" probability="0.2"><route edges="a b"/></flow>
  <flow id="n" begin="0" end="60" number="7" type="t" route="r2"/>
  <interval begin="100" end="200"><flow id="in" period="10" route="r1"/></interval>)X"));
  ASSERT_EQ(demand_.flows.size(), 6u);
  const auto& p = demand_.flows[0];
  EXPECT_DOUBLE_EQ(p.begin, 10);
  EXPECT_DOUBLE_EQ(p.end, 100);
  EXPECT_DOUBLE_EQ(p.period, 5);
  EXPECT_EQ(p.route, "r1");
  EXPECT_EQ(p.depart_spec.speed, DepartSpeed::Desired);
  const auto& h = demand_.flows[1];
  EXPECT_DOUBLE_EQ(h.begin, 60);
  EXPECT_DOUBLE_EQ(h.end, 3600);
  EXPECT_DOUBLE_EQ(h.vehs_per_hour, 600);
  EXPECT_EQ(h.from, "a");
  EXPECT_EQ(h.via, (std::vector<std::string>{"c"}));
  EXPECT_DOUBLE_EQ(demand_.flows[2].vehs_per_hour, 60);
  EXPECT_DOUBLE_EQ(demand_.flows[2].begin, 0);
  EXPECT_EQ(demand_.flows[2].from_junction, "J1");
  EXPECT_DOUBLE_EQ(demand_.flows[3].probability, 0.2);
  EXPECT_EQ(demand_.flows[3].edges, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(demand_.flows[4].number, 7);
  EXPECT_EQ(demand_.flows[4].type, "t");
  EXPECT_DOUBLE_EQ(demand_.flows[4].period, -1);
  EXPECT_DOUBLE_EQ(demand_.flows[5].begin, 100);
  EXPECT_DOUBLE_EQ(demand_.flows[5].end, 200);
}

TEST_F(RouteReaderTest, UnsupportedContentIsCounted) {
  read(routes(R"X(<person id="p" depart="0"><walk edges="a b"/></person>
  <personFlow id="pf" begin="0" end="10" number="2"><walk from="a" to="b"/></personFlow>
  <container id="c" depart="0"/>
  <param key="x" value="y"/>
  <busStop id="bs" lane="a_0" startPos="0" endPos="10" friendlyPos="true"/>
  <parkingArea id="pa" lane="a_0" startPos="0" endPos="10"/>
  <vehicle id="trig" depart="triggered" route="r"/>
  <trip id="taz" depart="1" fromTaz="z1" toTaz="z2"/>
  <vehicle id="kept" depart="2" route="r"><stop busStop="bs" duration="5"/><param key="a" value="b"/>
    <stop parkingArea="pa" duration="5"/><stop lane="a_0" parking="true" duration="5"/>
    <stop lane="a_0" triggered="person"/><stop lane="a_0" speed="5" duration="1"/><stop lane="a_0"/></vehicle>)X"));
  EXPECT_EQ(demand_.skipped.at("person"), 1);
  EXPECT_EQ(demand_.skipped.at("personFlow"), 1);
  EXPECT_EQ(demand_.skipped.at("container"), 1);
  EXPECT_EQ(demand_.skipped.at("param"), 2);
  EXPECT_EQ(demand_.skipped.at("parkingArea"), 1);
  // Stops LPSim does not make are counted with why; the busStop stop is kept.
  EXPECT_EQ(demand_.skipped.at("stop (parkingArea)"), 1);
  EXPECT_EQ(demand_.skipped.at("stop (parking)"), 1);
  EXPECT_EQ(demand_.skipped.at("stop (triggered)"), 1);
  EXPECT_EQ(demand_.skipped.at("stop (waypoint)"), 1);
  EXPECT_EQ(demand_.skipped.at("stop (neither duration nor until)"), 1);
  EXPECT_EQ(demand_.skipped.count("stop"), 0u);
  EXPECT_EQ(demand_.skipped.at("vehicle (depart=triggered)"), 1);
  EXPECT_EQ(demand_.skipped.at("trip (fromTaz/toTaz)"), 1);
  EXPECT_EQ(demand_.skipped.count("walk"), 0u);  // children of a skipped element are not counted
  ASSERT_EQ(demand_.vehicles.size(), 1u);
  EXPECT_EQ(demand_.vehicles[0].id, "kept");
  ASSERT_EQ(demand_.vehicles[0].stops.size(), 1u);
  EXPECT_EQ(demand_.vehicles[0].stops[0].stopping_place, "bs");
  ASSERT_EQ(demand_.stopping_places.size(), 1u);
  EXPECT_EQ(demand_.stopping_places[0].lane, "a_0");
  EXPECT_EQ(demand_.stopping_places[0].end_pos, 10.0);
  EXPECT_TRUE(demand_.stopping_places[0].friendly_pos);
}

TEST_F(RouteReaderTest, AddFileSignalsAndMeanData) {
  std::string path = write("x.add.xml", R"X(<additional>
  <tlLogic id="J1" programID="p" offset="3" type="static">
    <phase duration="30" state="Gr"/>
    <phase duration="5" state="yr"/>
  </tlLogic>
  <edgeData id="ed" file="out/edges.xml" period="300" begin="0" end="3600" excludeEmpty="true"/>
  <laneData id="ld" file="/abs/lanes.xml" freq="60" withInternal="1"/>
  <e1Detector id="d" lane="a_0" pos="1" freq="60" file="e1.xml"/>
  <vType id="t" length="7"/>
</additional>)X");
  read(path);
  ASSERT_EQ(additional_.tl_logics.size(), 1u);
  EXPECT_EQ(additional_.tl_logics[0].program_id, "p");
  EXPECT_EQ(additional_.tl_logics[0].phases.size(), 2u);
  ASSERT_EQ(additional_.mean_data.size(), 2u);
  const auto& ed = additional_.mean_data[0];
  EXPECT_EQ(ed.id, "ed");
  EXPECT_FALSE(ed.lane_level);
  EXPECT_EQ(ed.file, (tmp_.path() / "out/edges.xml").string());
  EXPECT_DOUBLE_EQ(ed.period, 300);
  EXPECT_DOUBLE_EQ(ed.end, 3600);
  EXPECT_TRUE(ed.exclude_empty);
  EXPECT_FALSE(ed.with_internal);
  const auto& ld = additional_.mean_data[1];
  EXPECT_TRUE(ld.lane_level);
  EXPECT_EQ(ld.file, "/abs/lanes.xml");
  EXPECT_DOUBLE_EQ(ld.period, 60);
  EXPECT_DOUBLE_EQ(ld.begin, -1);
  EXPECT_TRUE(ld.with_internal);
  EXPECT_EQ(demand_.skipped.at("e1Detector"), 1);
  EXPECT_EQ(demand_.vtypes.size(), 1u);
}

TEST_F(RouteReaderTest, ReadsGzip) {
  std::string path = (tmp_.path() / "g.rou.xml.gz").string();
  gzFile gz = gzopen(path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  std::string body =
      "<routes>\n<trip id=\"a\" depart=\"1\" from=\"x\" to=\"y\"/>\n<trip id=\"b\" depart=\"2\" from=\"x\" "
      "to=\"y\"/>\n</routes>\n";
  gzwrite(gz, body.data(), static_cast<unsigned>(body.size()));
  gzclose(gz);
  read(path);
  ASSERT_EQ(demand_.vehicles.size(), 2u);
  EXPECT_EQ(demand_.vehicles[1].id, "b");
}

TEST_F(RouteReaderTest, AppendsAcrossFilesAndRejectsRepeatedIds) {
  read(routes(R"X(<vType id="t"/><vehicle id="v" depart="0" route="r"/>)X", "a.rou.xml"));
  read(routes(R"X(<vehicle id="w" depart="0" route="r"/>)X", "b.rou.xml"));
  EXPECT_EQ(demand_.vehicles.size(), 2u);
  std::string again =
      routes("<vehicle id=\"x\" depart=\"0\" route=\"r\"/>\n<vehicle id=\"v\" depart=\"1\" route=\"r\"/>",
             "c.rou.xml");
  try {
    read(again);
    FAIL() << "duplicate vehicle id accepted";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("c.rou.xml:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"v\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("a.rou.xml:2"), std::string::npos) << msg;
  }
}

// Each bad input names the file, line 2 (where the element sits), the element id and the offending value.
TEST_F(RouteReaderTest, BadInputNamesFileLineIdAndValue) {
  struct Case {
    std::string xml, expected_id, expected_value;
  };
  const std::vector<Case> cases = {
      {R"X(<vehicle id="v" depart="-3" route="r"/>)X", "v", "-3"},
      {R"X(<vehicle id="v" depart="soon" route="r"/>)X", "v", "soon"},
      {R"X(<vehicle id="v" depart="nan" route="r"/>)X", "v", "nan"},
      {R"X(<vehicle depart="1" route="r"/>)X", "id", "missing or empty attribute 'id'"},
      {R"X(<vehicle id="" depart="1" route="r"/>)X", "id", "missing or empty attribute 'id'"},
      {R"X(<trip id="" depart="1" from="a" to="b"/>)X", "trip", "missing or empty attribute 'id'"},
      {R"X(<route id="" edges="a"/>)X", "route", "missing or empty attribute 'id'"},
      {R"X(<vehicle id="v" route="r"/>)X", "v", "depart"},
      {R"X(<vehicle id="v" depart="1"/>)X", "v", "no route"},
      {R"X(<vehicle id="v" depart="1" route="r" departLane="left"/>)X", "v", "left"},
      {R"X(<vehicle id="v" depart="1" route="r" departPos="middle"/>)X", "v", "middle"},
      {R"X(<vehicle id="v" depart="1" route="r" departSpeed="-2"/>)X", "v", "-2"},
      {R"X(<vehicle id="v" depart="1" route="r" arrivalPos="center"/>)X", "v", "center"},
      {R"X(<trip id="t" depart="1" from="a"/>)X", "t", "to"},
      {R"X(<flow id="f" begin="0" end="10" route="r"/>)X", "f", "period"},
      {R"X(<flow id="f" begin="-1" end="10" period="1" route="r"/>)X", "f", "-1"},
      {R"X(<flow id="f" begin="0" end="10" period="0" route="r"/>)X", "f", "period"},
      {R"X(<flow id="f" begin="0" end="10" probability="1.5" route="r"/>)X", "f", "1.5"},
      {R"X(<flow id="f" begin="0" end="10" vehsPerHour="NaN" route="r"/>)X", "f", "NaN"},
      {R"X(<flow id="f" begin="0" end="10" number="-4" route="r"/>)X", "f", "-4"},
      {R"X(<flow id="f" begin="20" end="10" number="4" route="r"/>)X", "f", "10"},
      {R"X(<flow id="f" begin="0" end="10" period="2" vehsPerHour="5" route="r"/>)X", "f", "only one"},
      {R"X(<flow id="f" begin="0" end="10" number="3"/>)X", "f", "no route"},
      {R"X(<vType id="t" length="-5"/>)X", "t", "-5"},
      {R"X(<vType id="t" speedFactor="uniform(1,2)"/>)X", "t", "uniform(1,2)"},
      {R"X(<vType id="t" sigma="1.5"/>)X", "t", "1.5"},
      {R"X(<route id="r" edges=""/>)X", "r", "edges"},
      {R"X(<vTypeDistribution id="d" vTypes="a b" probabilities="1"/>)X", "d", "probabilities"},
      {R"X(<edgeData id="e" file="x.xml" period="-5"/>)X", "e", "-5"},
      {R"X(<edgeData id="e" file="x.xml" excludeEmpty="maybe"/>)X", "e", "maybe"},
  };
  for (const auto& c : cases) {
    std::string msg = error_of(c.xml);
    EXPECT_NE(msg.find("r.rou.xml:2"), std::string::npos) << c.xml << " -> " << msg;
    EXPECT_NE(msg.find(c.expected_id), std::string::npos) << c.xml << " -> " << msg;
    EXPECT_NE(msg.find(c.expected_value), std::string::npos) << c.xml << " -> " << msg;
    demand_ = DemandSpec{};
  }
}

TEST_F(RouteReaderTest, DuplicateTypeAndRouteIdsAndBadRoot) {
  EXPECT_NE(error_of("<vType id=\"t\"/>\n<vType id=\"t\"/>").find("r.rou.xml:3"), std::string::npos);
  demand_ = DemandSpec{};
  EXPECT_NE(
      error_of("<route id=\"r\" edges=\"a\"/>\n<routeDistribution id=\"r\" routes=\"r\"/>").find("duplicate"),
      std::string::npos);
  demand_ = DemandSpec{};
  std::string net = write("n.net.xml", "<net>\n</net>\n");
  try {
    read(net);
    FAIL() << "a net file read as routes";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("<net>"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lpsim

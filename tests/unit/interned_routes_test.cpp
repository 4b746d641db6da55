// Inline routes interned by the route reader (DemandSpec::edge_names / edge_refs): the interner, and the
// demand builder giving interned routes exactly what it gives the same routes as strings.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "converters/edge_id_interner.hpp"
#include "demand/demand_builder.hpp"
#include "net/network_builder.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

TEST(EdgeIdInternerTest, StoresEachIdOnceAndSplitsOnWhitespace) {
  std::vector<std::string> names = {"known"};
  EdgeIdInterner interner(names);
  std::vector<uint32_t> refs;
  EXPECT_EQ(interner.intern_list("  a b\ta\n known\r\nb  ", refs), 5u);
  EXPECT_EQ(refs, (std::vector<uint32_t>{1, 2, 1, 0, 2}));
  EXPECT_EQ(names, (std::vector<std::string>{"known", "a", "b"}));
  EXPECT_EQ(interner.intern_list(" \t ", refs), 0u);
  EXPECT_EQ(refs.size(), 5u);
  EXPECT_EQ(interner.intern("b"), 2u);
  EXPECT_EQ(interner.intern("bb"), 3u);

  // A second interner over the same names (the next route file) finds them all.
  EdgeIdInterner again(names);
  EXPECT_EQ(again.intern("known"), 0u);
  EXPECT_EQ(again.intern("bb"), 3u);
  EXPECT_EQ(names.size(), 4u);
}

TEST(EdgeIdInternerTest, KeepsIndicesWhileGrowing) {
  std::vector<std::string> names;
  EdgeIdInterner interner(names);
  for (int i = 0; i < 5000; ++i)
    EXPECT_EQ(interner.intern("edge" + std::to_string(i)), static_cast<uint32_t>(i));
  for (int i = 4999; i >= 0; --i)
    EXPECT_EQ(interner.intern("edge" + std::to_string(i)), static_cast<uint32_t>(i));
  EXPECT_EQ(names.size(), 5000u);
  EXPECT_EQ(names[1234], "edge1234");
}

class InternedRoutesTest : public ::testing::Test {
 protected:
  // Corridor K0 -E0-> K1 -E1-> K2 -E2-> K3 -E3-> K4, 100 m edges, 2 lanes.
  Network corridor = build_network(test::make_corridor_spec(4, 100, 2));

  static VehicleSpec vehicle(const std::string& id, double depart, int line) {
    VehicleSpec v;
    v.id = id;
    v.depart = depart;
    v.loc = {"test.rou.xml", line};
    return v;
  }
  // The same vehicles twice: routes as strings, and interned as the route reader does.
  void add(const std::string& id, double depart, const std::vector<std::string>& edges, int line = 10) {
    VehicleSpec plain = vehicle(id, depart, line);
    plain.edges = edges;
    as_strings.vehicles.push_back(plain);
    VehicleSpec v = vehicle(id, depart, line);
    EdgeIdInterner interner(interned.edge_names);
    v.edge_ref_begin = interned.edge_refs.size();
    for (const auto& e : edges) interned.edge_refs.push_back(interner.intern(e));
    v.edge_ref_count = static_cast<uint32_t>(edges.size());
    interned.vehicles.push_back(v);
  }
  std::string error_of(const DemandSpec& spec) const {
    try {
      build_demand(spec, corridor, {});
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  DemandSpec as_strings, interned;
};

TEST_F(InternedRoutesTest, SameDemandAsStringRoutes) {
  add("a", 2, {"E0", "E1", "E2", "E3"});
  add("b", 1, {"E2", "E3"});
  add("c", 1, {"E3"});
  const Demand want = build_demand(as_strings, corridor, {});
  const Demand got = build_demand(interned, corridor, {});
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got.vehicle_id, want.vehicle_id);
  EXPECT_EQ(got.route_begin, want.route_begin);
  EXPECT_EQ(got.route_length, want.route_length);
  EXPECT_EQ(got.route_edges, want.route_edges);
  EXPECT_EQ(got.route_edges.size(), 7u);
  EXPECT_EQ(got.speed_factor, want.speed_factor);
  EXPECT_EQ(got.source[0], DemandSource::Vehicle);
}

TEST_F(InternedRoutesTest, ErrorsAreTheMessagesOfStringRoutes) {
  add("gap", 0, {"E0", "E2"}, 21);
  const std::string gap = error_of(interned);
  EXPECT_EQ(gap, error_of(as_strings));
  EXPECT_NE(gap.find("test.rou.xml:21"), std::string::npos) << gap;
  EXPECT_NE(gap.find("no connection from edge 'E0' to edge 'E2' in the route of vehicle 'gap'"),
            std::string::npos)
      << gap;

  as_strings = {};
  interned = {};
  add("ok", 0, {"E0", "E1"});
  add("ghost", 0, {"E1", "E9"}, 22);
  const std::string ghost = error_of(interned);
  EXPECT_EQ(ghost, error_of(as_strings));
  EXPECT_NE(ghost.find("unknown edge 'E9' in the route of vehicle 'ghost'"), std::string::npos) << ghost;
}

TEST_F(InternedRoutesTest, IgnoredErrorsSkipTheSameVehicles) {
  add("ok", 3, {"E0", "E1"});
  add("gap", 0, {"E1", "E3"}, 41);
  add("ghost", 0, {"E7"}, 42);
  add("ok2", 4, {"E1", "E2", "E3"});
  DemandOptions opt;
  opt.ignore_route_errors = true;
  const Demand want = build_demand(as_strings, corridor, opt);
  const Demand got = build_demand(interned, corridor, opt);
  EXPECT_EQ(got.vehicle_id, (std::vector<std::string>{"ok", "ok2"}));
  EXPECT_EQ(got.route_edges, want.route_edges);
  ASSERT_EQ(got.unroutable.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(got.unroutable[k].id, want.unroutable[k].id);
    EXPECT_EQ(got.unroutable[k].reason, want.unroutable[k].reason);
    EXPECT_EQ(got.unroutable[k].loc.line, want.unroutable[k].loc.line);
  }
}

TEST_F(InternedRoutesTest, RefsOutsideTheListAreRejected) {
  add("v", 0, {"E0"}, 30);
  interned.vehicles[0].edge_ref_count = 2;  // one past the end of edge_refs
  EXPECT_NE(error_of(interned).find("test.rou.xml:30"), std::string::npos);
  interned.vehicles[0].edge_ref_count = 1;
  interned.edge_refs[0] = 7;  // no such name
  EXPECT_NE(error_of(interned).find("'v'"), std::string::npos);
}

}  // namespace
}  // namespace lpsim

#include "net/network_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kernels/lane_map.hpp"
#include "kernels/step_view.hpp"
#include "unit/test_nets.hpp"

namespace lpsim {
namespace {

using test::grid_edge;

// Expects build_network to throw an InputError whose message contains every fragment.
void expect_input_error(const NetSpec& spec, const std::vector<std::string>& fragments,
                        const std::vector<TlLogicSpec>& overrides = {}) {
  try {
    build_network(spec, overrides);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    for (const auto& f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

TEST(NetworkBuilder, GridCountsAndLayout) {
  test::GridOptions o;
  o.lanes = 2;
  o.spacing = 100.5;
  Network net = build_network(test::make_grid_spec(3, 3, o));
  // 3x3 grid: 12 neighbour pairs, two directions each.
  ASSERT_EQ(net.num_edges(), 24u);
  EXPECT_EQ(net.num_lanes(), 48u);
  EXPECT_EQ(net.num_junctions(), 9u);
  EXPECT_EQ(net.num_signals(), 0u);
  // ceil(100.5) = 101 cells per lane, no padding.
  ASSERT_EQ(net.lane_cell_begin.size(), 49u);
  for (uint32_t l = 0; l < net.num_lanes(); ++l)
    EXPECT_EQ(net.lane_cell_begin[l + 1] - net.lane_cell_begin[l], 101u);
  EXPECT_EQ(net.num_cells(), 48u * 101u);
  // Lanes of an edge are contiguous and in index order.
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    EXPECT_EQ(net.edge_num_lanes[e], 2);
    EXPECT_EQ(net.edge_first_lane[e], 2 * e);
    EXPECT_EQ(net.lane_index[2 * e], 0);
    EXPECT_EQ(net.lane_index[2 * e + 1], 1);
    EXPECT_EQ(net.lane_edge[2 * e + 1], e);
    EXPECT_FLOAT_EQ(net.edge_length[e], 100.5f);
    EXPECT_FLOAT_EQ(net.edge_speed[e], 13.89f);
  }
  // Shapes: two points per lane.
  EXPECT_EQ(net.lane_shape_begin.back(), 2 * net.num_lanes());
  EXPECT_EQ(net.shape_x.size(), 2 * net.num_lanes());
  EXPECT_DOUBLE_EQ(net.lane_km(), 48 * 100.5 / 1000.0);
  EXPECT_EQ(net.edge_index.at(grid_edge(1, 1, 2, 1)),
            net.lane_edge[net.lane_index_by_id.at(grid_edge(1, 1, 2, 1) + "_1")]);
}

TEST(NetworkBuilder, ConnectionCsrAndSuccessors) {
  Network net = build_network(test::make_grid_spec(3, 3));
  // Every lane's connections are contiguous and all start at that lane.
  ASSERT_EQ(net.lane_conn_begin.size(), net.num_lanes() + 1);
  EXPECT_EQ(net.lane_conn_begin.back(), net.num_connections());
  for (uint32_t l = 0; l < net.num_lanes(); ++l)
    for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c)
      EXPECT_EQ(net.conn_from_lane[c], l);
  // Centre junction J1_1: 4 incoming edges x 3 turns (no U-turns).
  const uint32_t in = net.edge_index.at(grid_edge(0, 1, 1, 1));
  const uint32_t l = net.edge_first_lane[in];
  EXPECT_EQ(net.lane_conn_begin[l + 1] - net.lane_conn_begin[l], 3u);
  for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c)
    EXPECT_EQ(net.conn_junction[c], static_cast<int32_t>(net.junction_index.at("J1_1")));
  EXPECT_TRUE(net.connected(in, net.edge_index.at(grid_edge(1, 1, 2, 1))));
  EXPECT_TRUE(net.connected(in, net.edge_index.at(grid_edge(1, 1, 1, 2))));
  EXPECT_FALSE(net.connected(in, net.edge_index.at(grid_edge(1, 1, 0, 1))));  // U-turn
  // Successor lists are sorted and unique.
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    for (uint32_t i = net.edge_succ_begin[e] + 1; i < net.edge_succ_begin[e + 1]; ++i)
      EXPECT_LT(net.edge_succ[i - 1], net.edge_succ[i]);
  EXPECT_EQ(net.edge_succ.size(), 4u * 3 + 12u * 2 + 8u * 1);  // centre 4x3, side approaches, corners
}

TEST(NetworkBuilder, CsrIsStableInFileOrder) {
  NetSpec s = test::make_corridor_spec(2, 50, 1);
  // Two more connections from E0_0, written after the original one: order must be kept.
  test::add_edge(s, "E0b", "K1", "K0");
  ConnectionSpec c = s.connections.front();
  c.to = "E0b";
  c.dir = 't';
  s.connections.push_back(c);
  Network net = build_network(s);
  const uint32_t l = net.lane_index_by_id.at("E0_0");
  ASSERT_EQ(net.lane_conn_begin[l + 1] - net.lane_conn_begin[l], 2u);
  EXPECT_EQ(net.conn_to_edge[net.lane_conn_begin[l]], net.edge_index.at("E1"));
  EXPECT_EQ(net.conn_to_edge[net.lane_conn_begin[l] + 1], net.edge_index.at("E0b"));
  EXPECT_EQ(net.conn_dir[net.lane_conn_begin[l] + 1], 't');
}

TEST(NetworkBuilder, InternalLanesAndJunctions) {
  test::GridOptions o;
  o.with_internal = true;
  o.internal_length = 5.2;
  NetSpec s = test::make_grid_spec(2, 2, o);
  Network net = build_network(s);
  // 2x2 grid: 8 normal edges, each junction has 2 incoming x 1 non-U turn = 2 links -> 8 internal edges.
  EXPECT_EQ(net.num_edges(), 16u);
  uint32_t internal = 0;
  for (uint32_t e = 0; e < net.num_edges(); ++e) internal += net.edge_is_internal[e];
  EXPECT_EQ(internal, 8u);
  const uint32_t ie = net.edge_index.at(":J0_0_0");
  EXPECT_EQ(net.edge_from_junction[ie], kNone);
  EXPECT_EQ(net.lane_cell_begin[net.edge_first_lane[ie] + 1] - net.lane_cell_begin[net.edge_first_lane[ie]],
            6u);
  // Connections via internal lanes, and the internal lanes' own connections at the same junction.
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    const uint32_t fe = net.lane_edge[net.conn_from_lane[c]];
    if (net.edge_is_internal[fe]) {
      EXPECT_EQ(net.conn_via_lane[c], kNone);
      EXPECT_EQ(net.conn_junction[c],
                static_cast<int32_t>(net.junction_index.at(net.edge_id[fe].substr(1, 4))));
    } else {
      ASSERT_NE(net.conn_via_lane[c], kNone);
      EXPECT_TRUE(net.edge_is_internal[net.lane_edge[net.conn_via_lane[c]]]);
    }
  }
  // Successors skip internal edges, and internal edges have none.
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e]) {
      EXPECT_EQ(net.edge_succ_begin[e], net.edge_succ_begin[e + 1]);
    }
    for (uint32_t i = net.edge_succ_begin[e]; i < net.edge_succ_begin[e + 1]; ++i)
      EXPECT_FALSE(net.edge_is_internal[net.edge_succ[i]]);
  }
  EXPECT_TRUE(
      net.connected(net.edge_index.at(grid_edge(0, 0, 1, 0)), net.edge_index.at(grid_edge(1, 0, 1, 1))));
  EXPECT_EQ(net.junction_type[net.junction_index.at("J1_1")], JunctionType::Priority);
}

TEST(NetworkBuilder, SuccessorsFollowInternalChains) {
  // A connection that ends on an internal edge (no normal to-edge named) still yields the normal successor.
  NetSpec s = test::make_corridor_spec(2);
  EdgeSpec ie;
  ie.id = ":K1_0";
  ie.function = EdgeFunction::Internal;
  LaneSpec il;
  il.id = ":K1_0_0";
  il.length = 3;
  ie.lanes.push_back(il);
  s.edges.push_back(ie);
  s.connections.clear();
  ConnectionSpec a;
  a.from = "E0";
  a.to = ":K1_0";
  ConnectionSpec b;
  b.from = ":K1_0";
  b.to = "E1";
  s.connections = {a, b};
  Network net = build_network(s);
  EXPECT_TRUE(net.connected(net.edge_index.at("E0"), net.edge_index.at("E1")));
  // No shape given: the internal lane sits at its junction K1 (100, 0).
  const uint32_t l = net.lane_index_by_id.at(":K1_0_0");
  EXPECT_FLOAT_EQ(net.shape_x[net.lane_shape_begin[l]], 100.f);
  EXPECT_EQ(net.conn_junction[net.lane_conn_begin[l]], static_cast<int32_t>(net.junction_index.at("K1")));
}

TEST(NetworkBuilder, InternalJunctionFromIntLanesWhenIdDoesNotTell) {
  NetSpec s = test::make_corridor_spec(2);
  EdgeSpec ie;
  ie.id = ":odd";
  ie.function = EdgeFunction::Internal;
  LaneSpec il;
  il.id = ":odd_lane";
  il.length = 2;
  ie.lanes.push_back(il);
  s.edges.push_back(ie);
  s.junctions[1].int_lanes.push_back(":odd_lane");
  ConnectionSpec c;
  c.from = ":odd";
  c.to = "E1";
  s.connections.push_back(c);
  Network net = build_network(s);
  const uint32_t l = net.lane_index_by_id.at(":odd_lane");
  EXPECT_EQ(net.conn_junction[net.lane_conn_begin[l]], static_cast<int32_t>(net.junction_index.at("K1")));
}

// An edge type's <restriction>s give each lane of its normal edges a speed limit per vehicle class; the
// kernels' lane_speed_for reads them (SUMO's MSLane::getVehicleMaxSpeed), other classes keep the lane's
// speed.
TEST(NetworkBuilder, EdgeTypeRestrictionsGiveLanesSpeedsByClass) {
  NetSpec s = test::make_signal_spec(/*bus_lane=*/true, /*with_internal=*/true);
  EdgeTypeSpec t;
  t.id = "arterial";
  t.restrictions = {{vclass_name_bit("truck"), 8.0}, {kAllVClasses, 6.0}};
  s.edge_types.push_back(t);
  for (auto& e : s.edges)
    if (e.id == "WtoC" || e.id.rfind(":C", 0) == 0) e.type = "arterial";  // internal edges: no restriction
  Network net = build_network(s);
  ASSERT_EQ(net.lane_restriction_begin.size(), net.num_lanes() + 1);
  NetView v{};
  v.lane_speed = net.lane_speed.data();
  v.lane_restriction_begin = net.lane_restriction_begin.data();
  v.restriction_vclass = net.restriction_vclass.data();
  v.restriction_speed = net.restriction_speed.data();
  const uint32_t truck = vclass_name_bit("truck"), car = kVClassPassenger;
  for (uint32_t l = 0; l < net.num_lanes(); ++l) {
    const bool restricted = net.edge_id[net.lane_edge[l]] == "WtoC";
    EXPECT_EQ(net.lane_restriction_begin[l + 1] - net.lane_restriction_begin[l], restricted ? 2u : 0u) << l;
    EXPECT_FLOAT_EQ(lane_speed_for(v, l, truck), restricted ? 8.0f : net.lane_speed[l]) << net.lane_id[l];
    EXPECT_FLOAT_EQ(lane_speed_for(v, l, car), net.lane_speed[l]) << net.lane_id[l];
    EXPECT_FLOAT_EQ(lane_speed_for(v, l, kAllVClasses), restricted ? 6.0f : net.lane_speed[l])
        << net.lane_id[l];
  }
  v.lane_restriction_begin = nullptr;  // a net without restrictions: the view holds no table
  EXPECT_FLOAT_EQ(lane_speed_for(v, net.edge_first_lane[net.edge_index.at("WtoC")], truck),
                  net.lane_speed[net.edge_first_lane[net.edge_index.at("WtoC")]]);
}

TEST(NetworkBuilder, BusLaneIsKeptWithItsPermissions) {
  Network net = build_network(test::make_signal_spec(/*bus_lane=*/true));
  EXPECT_EQ(net.num_edges(), 8u);
  EXPECT_EQ(net.num_lanes(), 9u);  // the bus lane is kept
  EXPECT_EQ(net.skipped_non_car_lanes, 0);
  const uint32_t w = net.edge_index.at("WtoC");
  EXPECT_EQ(net.edge_num_lanes[w], 2);
  const uint32_t bus = net.edge_first_lane[w];
  EXPECT_EQ(net.lane_id[bus], "WtoC_0");
  EXPECT_EQ(net.lane_permissions[bus], vclass_name_bit("bus"));
  EXPECT_EQ(net.lane_permissions[bus + 1], kAllVClasses);
  EXPECT_EQ(net.edge_permissions[w], kAllVClasses);
  // Bus lane has 3 connections (N, E, S); the other lanes 4 x 3 = 12.
  EXPECT_EQ(net.skipped_connections, 0);
  EXPECT_EQ(net.num_connections(), 15u);
  EXPECT_TRUE(net.connected(w, net.edge_index.at("CtoE"), kVClassPassenger));
  EXPECT_TRUE(net.connected(w, net.edge_index.at("CtoE"), vclass_name_bit("bus")));
}

TEST(NetworkBuilder, SignalProgramAndLinks) {
  NetSpec s = test::make_signal_spec(/*bus_lane=*/true);
  s.tl_logics[0].type = "actuated";
  s.tl_logics[0].offset = 7;
  Network net = build_network(s);
  ASSERT_EQ(net.num_signals(), 1u);
  EXPECT_EQ(net.signal_program[0], "0");
  EXPECT_EQ(net.signal_actuated[0], 1);
  EXPECT_FLOAT_EQ(net.signal_offset[0], 7.f);
  ASSERT_EQ(net.signal_phase_begin, (std::vector<uint32_t>{0, 4}));
  // 15 links (12 car + 3 bus); every phase state has all of them.
  ASSERT_EQ(net.phase_state_begin.size(), 5u);
  for (uint32_t p = 0; p < 4; ++p) EXPECT_EQ(net.phase_state_begin[p + 1] - net.phase_state_begin[p], 15u);
  EXPECT_EQ(std::string(net.phase_state.begin(), net.phase_state.begin() + 15),
            s.tl_logics[0].phases[0].state);
  EXPECT_FLOAT_EQ(net.phase_duration[1], 3.f);
  EXPECT_FLOAT_EQ(net.phase_min_dur[0], -1.f);
  EXPECT_EQ(net.junction_type[net.junction_index.at("C")], JunctionType::TrafficLight);
  EXPECT_EQ(net.junction_type[net.junction_index.at("N")], JunctionType::DeadEnd);
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    EXPECT_EQ(net.conn_signal[c], 0);
    EXPECT_GE(net.conn_link_index[c], 0);
    EXPECT_LT(net.conn_link_index[c], 15);
    EXPECT_EQ(net.conn_state[c], 'O');
  }
  // Corridor connections are unsignalled.
  Network plain = build_network(test::make_corridor_spec(2));
  EXPECT_EQ(plain.conn_signal[0], kNone);
  EXPECT_EQ(plain.conn_link_index[0], -1);
}

TEST(NetworkBuilder, AdditionalProgramReplacesNetProgram) {
  NetSpec s = test::make_signal_spec();
  s.tl_logics.push_back(test::make_cross_program(s, "net-second", 20));  // the net's last one would win...
  TlLogicSpec add = test::make_cross_program(s, "from-add-file", 45);    // ...but add-files come later
  Network net = build_network(s, {add});
  ASSERT_EQ(net.num_signals(), 1u);
  EXPECT_EQ(net.signal_program[0], "from-add-file");
  EXPECT_FLOAT_EQ(net.phase_duration[0], 45.f);
  Network without = build_network(s);
  EXPECT_EQ(without.signal_program[0], "net-second");
  EXPECT_FLOAT_EQ(without.phase_duration[0], 20.f);
}

TEST(NetworkBuilder, ErrorsNameTheIds) {
  {
    NetSpec s = test::make_corridor_spec(2);
    s.connections[0].to = "nowhere";
    expect_input_error(s, {"corridor.net.xml:1000", "'nowhere'", "'E0'"});
  }
  {
    NetSpec s = test::make_corridor_spec(2);
    s.connections[0].to_lane = 3;
    expect_input_error(s, {"toLane 3", "edge 'E1'", "1 lanes"});
  }
  {
    NetSpec s = test::make_corridor_spec(2);
    s.connections[0].via = ":K1_7_0";
    expect_input_error(s, {"via lane ':K1_7_0'"});
  }
  {
    NetSpec s = test::make_signal_spec();
    s.tl_logics.clear();
    expect_input_error(s, {"tlLogic 'C'", "no program"});
  }
  {
    NetSpec s = test::make_signal_spec();
    s.connections[2].link_index = 12;
    expect_input_error(s, {"linkIndex 12", "tlLogic 'C'", "12 links"});
  }
  {
    NetSpec s = test::make_signal_spec();
    TlLogicSpec bad = test::make_cross_program(s, "short");
    bad.phases[2].state.pop_back();
    expect_input_error(s, {"tlLogic 'C'", "phase 2"}, {bad});
  }
  {
    NetSpec s = test::make_corridor_spec(2);
    s.junctions[1].type = "roundabout";
    expect_input_error(s, {"junction 'K1'", "'roundabout'", "corridor.net.xml:2"});
  }
  {
    NetSpec s = test::make_corridor_spec(2);
    s.edges[1].to = "K9";
    expect_input_error(s, {"edge 'E1'", "'K9'"});
  }
  {
    NetSpec s = test::make_corridor_spec(2);
    s.edges[1].id = "E0";
    expect_input_error(s, {"duplicate edge id 'E0'"});
  }
  {
    // Lanes within a lane's limit that together exceed the lane map's 32-bit cell offsets.
    NetSpec s = test::make_corridor_spec(6);
    for (auto& e : s.edges)
      for (auto& l : e.lanes) l.length = 9e8;
    expect_input_error(s, {"more than the 4294967295", "lane-map cells"});
  }
  {
    // One lane longer than int32 cell indices allow (with room for look-ahead sums), however absurd.
    NetSpec s = test::make_corridor_spec(2);
    s.edges[1].lanes[0].length = 1.1e9;
    expect_input_error(s, {"lane '" + s.edges[1].lanes[0].id + "'", "1100000000 m", "allows a lane"});
    s.edges[1].lanes[0].length = 1e30;
    expect_input_error(s, {"lane '" + s.edges[1].lanes[0].id + "'", "allows a lane"});
  }
}

TEST(NetworkBuilder, PedestrianEdgesAreSkipped) {
  NetSpec s = test::make_signal_spec();
  EdgeSpec cross;
  cross.id = ":C_c0";
  cross.function = EdgeFunction::Crossing;
  LaneSpec cl;
  cl.id = ":C_c0_0";
  cl.permissions = kVClassPedestrian;
  cross.lanes.push_back(cl);
  s.edges.insert(s.edges.begin(), cross);
  ConnectionSpec c;
  c.from = ":C_c0";
  c.to = "CtoN";
  s.connections.push_back(c);
  Network net = build_network(s);
  EXPECT_EQ(net.edge_index.count(":C_c0"), 0u);
  EXPECT_EQ(net.num_edges(), 8u);
  EXPECT_EQ(net.skipped_connections, 1);
}

TEST(NetworkBuilder, RoundaboutsAndLookups) {
  NetSpec s = test::make_grid_spec(2, 2);
  s.roundabouts.push_back({{"J0_0", "J1_0"}, {grid_edge(0, 0, 1, 0), "unknown", grid_edge(1, 0, 1, 1)}});
  s.net_offset = {10, -20};
  Network net = build_network(s);
  ASSERT_EQ(net.roundabout_edges.size(), 1u);
  EXPECT_EQ(net.roundabout_edges[0], (std::vector<uint32_t>{net.edge_index.at(grid_edge(0, 0, 1, 0)),
                                                            net.edge_index.at(grid_edge(1, 0, 1, 1))}));
  EXPECT_FLOAT_EQ(net.net_offset.y, -20.f);
  EXPECT_EQ(net.junction_index.size(), 4u);
  EXPECT_EQ(net.lane_index_by_id.size(), net.num_lanes());
  EXPECT_FLOAT_EQ(net.junction_x[net.junction_index.at("J1_1")], 100.f);
}

TEST(NetworkBuilder, LargeGridBuildsLinearly) {
  // 120x120 grid: ~57k edges, ~170k connections; must build quickly (no quadratic passes).
  NetSpec s = test::make_grid_spec(120, 120);
  Network net = build_network(s);
  EXPECT_EQ(net.num_edges(), 4u * 120 * 119);
  EXPECT_EQ(net.num_connections(), s.connections.size());
}

}  // namespace
}  // namespace lpsim

#include "partition/part_plan.hpp"

#include <algorithm>

#include "partition/junction_graph.hpp"
#include "partition/partition_layout.hpp"
#include "partition/partition_summary.hpp"

namespace lpsim {

namespace {

// The kernels' look-ahead (kMaxLookahead) and the room rule's (kRoomLookAheadLengths vehicle lengths of
// normal lane, looked along twice over), plus the junctions' insides passed on the way.
constexpr double kLookAhead = 1000.0, kRoomLengths = 5.0, kJunctionInsides = 400.0;

// Internal lane l and the internal lanes after it inside its junction (past an internal junction).
template <class Add>
void add_with_inside(const Network& net, uint32_t l, Add add) {
  for (int hops = 0; hops < 8; ++hops) {
    add(l);
    const uint32_t c = net.lane_conn_begin[l];
    if (c == net.lane_conn_begin[l + 1]) return;
    const int32_t via = net.conn_via_lane[c];
    const uint32_t next = via >= 0 ? static_cast<uint32_t>(via) : net.conn_to_lane[c];
    if (!net.edge_is_internal[net.lane_edge[next]]) return;
    l = next;
  }
}

}  // namespace

double ghost_look_ahead(double longest_vehicle) {
  return kLookAhead + 2.0 * kRoomLengths * longest_vehicle + kJunctionInsides;
}

namespace {

// The plans of the parts `wanted` names (every part's holdings are worked out: a plan lists the holders of
// each lane).
std::vector<PartPlan> plans_of(const Network& net, const std::vector<int32_t>& edge_part, int32_t parts,
                               double longest_vehicle, const std::vector<int32_t>& wanted) {
  const uint32_t nl = net.num_lanes();
  std::vector<int32_t> owner = lane_parts(net, edge_part);
  for (int32_t& p : owner)
    if (p == kNone) p = 0;  // a lane no junction claims (none in a connected network) runs in part 0
  const std::vector<PartLayout> layout =
      partition_layout(net, owner, parts, ghost_look_ahead(longest_vehicle), longest_vehicle);

  // The links that must yield to each connection (the reverse of the junction response).
  const uint32_t nc = net.num_connections();
  std::vector<std::vector<uint32_t>> yielders(nc);
  if (net.conn_foe_begin.size() == nc + 1)
    for (uint32_t c = 0; c < nc; ++c)
      for (uint32_t k = net.conn_foe_begin[c]; k < net.conn_foe_begin[c + 1]; ++k)
        yielders[net.conn_foe[k]].push_back(c);

  std::vector<int32_t> signal_owner(net.num_signals(), -1);
  for (uint32_t c = 0; c < nc; ++c) {
    const int32_t s = net.conn_signal[c];
    if (s < 0 || static_cast<size_t>(s) >= net.signal_actuated.size() || !net.signal_actuated[s]) continue;
    const int32_t p = owner[net.conn_from_lane[c]];
    int32_t& o = signal_owner[static_cast<uint32_t>(s)];
    o = o < 0 ? p : std::min(o, p);
  }

  std::vector<std::vector<uint8_t>> held(static_cast<size_t>(parts));
  for (int32_t p = 0; p < parts; ++p) {
    std::vector<uint8_t>& h = held[static_cast<size_t>(p)];
    h.assign(nl, 0);
    for (uint32_t l : layout[static_cast<size_t>(p)].owned) h[l] = 1;
    for (uint32_t l : layout[static_cast<size_t>(p)].ghosts) h[l] = 1;
    std::vector<uint32_t> extra;
    auto add = [&](uint32_t l) {
      if (!h[l]) extra.push_back(l);
    };
    for (uint32_t l = 0; l < nl; ++l) {
      if (!h[l]) continue;
      for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c) {
        if (net.conn_foe_begin.size() == nc + 1)
          for (uint32_t k = net.conn_foe_begin[c]; k < net.conn_foe_begin[c + 1]; ++k) {
            const uint32_t f = net.conn_foe[k];
            add(net.conn_from_lane[f]);
            if (net.conn_via_lane[f] >= 0)
              add_with_inside(net, static_cast<uint32_t>(net.conn_via_lane[f]), add);
          }
        for (uint32_t y : yielders[c])
          if (net.conn_via_lane[y] >= 0)
            add_with_inside(net, static_cast<uint32_t>(net.conn_via_lane[y]), add);
      }
    }
    if (!net.det_lane.empty())
      for (uint32_t s = 0; s < net.num_signals(); ++s)
        if (signal_owner[s] == p)
          for (uint32_t d = net.signal_det_begin[s]; d < net.signal_det_begin[s + 1]; ++d)
            add(net.det_lane[d]);
    for (uint32_t l : extra) {
      const uint32_t e = net.lane_edge[l];
      for (uint32_t m = net.edge_first_lane[e]; m < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++m)
        h[m] = 1;
    }
  }

  std::vector<uint32_t> holder_begin(nl + 1, 0);
  std::vector<int32_t> holders;
  for (uint32_t l = 0; l < nl; ++l) {
    for (int32_t p = 0; p < parts; ++p)
      if (held[static_cast<size_t>(p)][l]) holders.push_back(p);
    holder_begin[l + 1] = static_cast<uint32_t>(holders.size());
  }
  std::vector<int32_t> edge_owner(net.num_edges(), 0);
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (net.edge_num_lanes[e] > 0) edge_owner[e] = owner[net.edge_first_lane[e]];

  std::vector<PartPlan> plans(wanted.size());
  for (size_t w = 0; w < wanted.size(); ++w) {
    const int32_t p = wanted[w];
    PartPlan& plan = plans[w];
    plan.part = p;
    plan.parts = parts;
    plan.lane_owner = owner;
    plan.edge_owner = edge_owner;
    plan.held = std::move(held[static_cast<size_t>(p)]);
    PartLayout lanes;
    for (uint32_t l = 0; l < nl; ++l)
      if (plan.held[l]) (owner[l] == p ? lanes.owned : lanes.ghosts).push_back(l);
    plan.cells = part_cells(net, lanes);
    plan.holder_begin = holder_begin;
    plan.holders = holders;
    for (uint32_t l = 0; l < nl; ++l)
      if (plan.held[l] && holder_begin[l + 1] - holder_begin[l] > 1) plan.shared_lanes.push_back(l);
    plan.signal_owner = signal_owner;
  }
  return plans;
}

}  // namespace

std::vector<PartPlan> part_plans(const Network& net, const std::vector<int32_t>& edge_part, int32_t parts,
                                 double longest_vehicle) {
  std::vector<int32_t> all(static_cast<size_t>(parts));
  for (int32_t p = 0; p < parts; ++p) all[static_cast<size_t>(p)] = p;
  return plans_of(net, edge_part, parts, longest_vehicle, all);
}

PartPlan part_plan(const Network& net, const std::vector<int32_t>& edge_part, int32_t parts,
                   double longest_vehicle, int32_t part) {
  return std::move(plans_of(net, edge_part, parts, longest_vehicle, {part}).front());
}

}  // namespace lpsim

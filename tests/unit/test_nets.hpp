#pragma once
// Small NetSpecs built in code for unit tests (no files, no /work/shared). Shared by the network builder,
// router and demand builder tests: keep the function signatures and the id scheme stable.
//
// Id scheme
//   grid junction (c, r)         "J<c>_<r>"            at (c * spacing, r * spacing)
//   grid edge (c0,r0)->(c1,r1)   "J<c0>_<r0>toJ<c1>_<r1>"
//   corridor junction k          "K<k>"                at (k * length, 0), k = 0..segments
//   corridor edge k              "E<k>"                K<k> -> K<k+1>
//   signal cross: centre "C", arms "N","E","S","W"; edges "NtoC", "CtoN", ...; tlLogic id "C"
//   lanes                        "<edge>_<index>"
//   internal edges (with_internal) ":<junction>_<n>" with one lane ":<junction>_<n>_0", n counting the
//   junction's links in the order the connections are written.
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/net_spec.hpp"

namespace lpsim::test {

struct GridOptions {
  double spacing = 100;        // m between neighbouring junctions (= lane length)
  int lanes = 1;               // car lanes per edge
  double speed = 13.89;        // m/s
  bool with_internal = false;  // connections go via internal junction lanes, as in a SUMO net
  double internal_length = 5;  // m, length of every internal lane
  bool allow_uturn = false;    // add turnaround connections (dir 't')
};

inline std::string grid_junction(int c, int r) { return "J" + std::to_string(c) + "_" + std::to_string(r); }
inline std::string grid_edge(int c0, int r0, int c1, int r1) {
  return grid_junction(c0, r0) + "to" + grid_junction(c1, r1);
}
inline std::string lane_of(const std::string& edge, int index) { return edge + "_" + std::to_string(index); }

namespace detail {

inline LaneSpec make_lane(const std::string& edge, int index, double length, double speed, Point a, Point b) {
  LaneSpec l;
  l.id = lane_of(edge, index);
  l.index = index;
  l.length = length;
  l.speed = speed;
  // Lanes lie to the right of the edge's centre line, 3.2 m apart.
  double dx = b.x - a.x, dy = b.y - a.y, n = std::hypot(dx, dy);
  double off = (index + 0.5) * 3.2;
  double ox = n > 0 ? dy / n * off : 0, oy = n > 0 ? -dx / n * off : 0;
  l.shape = {{a.x + ox, a.y + oy}, {b.x + ox, b.y + oy}};
  return l;
}

inline const JunctionSpec* find_junction(const NetSpec& s, const std::string& id) {
  for (const auto& j : s.junctions)
    if (j.id == id) return &j;
  return nullptr;
}

// Turn direction from the heading of the incoming and outgoing edge (y up): s, l, r or t.
inline char turn_dir(Point a0, Point a1, Point b0, Point b1) {
  double ax = a1.x - a0.x, ay = a1.y - a0.y, bx = b1.x - b0.x, by = b1.y - b0.y;
  double cross = ax * by - ay * bx, dot = ax * bx + ay * by;
  if (std::abs(cross) < 1e-9) return dot > 0 ? 's' : 't';
  return cross > 0 ? 'l' : 'r';
}

}  // namespace detail

/// Adds a normal edge from junction `a` to `b` with `lanes` car lanes of the junction distance.
inline EdgeSpec& add_edge(NetSpec& s, const std::string& id, const JunctionSpec& a, const JunctionSpec& b,
                          int lanes = 1, double speed = 13.89) {
  Point pa{a.x, a.y}, pb{b.x, b.y};
  EdgeSpec e;
  e.id = id;
  e.from = a.id;
  e.to = b.id;
  e.priority = 1;
  e.loc = {s.source, static_cast<int>(s.edges.size()) + 1};
  double len = std::hypot(pb.x - pa.x, pb.y - pa.y);
  for (int i = 0; i < lanes; ++i) e.lanes.push_back(detail::make_lane(id, i, len, speed, pa, pb));
  s.edges.push_back(std::move(e));
  return s.edges.back();
}

/// Same, naming existing junctions by id (linear lookup: for small specs).
inline EdgeSpec& add_edge(NetSpec& s, const std::string& id, const std::string& from, const std::string& to,
                          int lanes = 1, double speed = 13.89) {
  JunctionSpec a = *detail::find_junction(s, from), b = *detail::find_junction(s, to);
  return add_edge(s, id, a, b, lanes, speed);
}

/// Adds the connections of every incoming to every outgoing edge at each junction (lane i -> lane
/// min(i, lanes-1)), optionally via one internal edge per link as SUMO writes them. Existing connections
/// are kept. Junctions listed in `signalled` get tl = junction id and consecutive link indices.
inline void connect_all(NetSpec& s, bool with_internal, double internal_length, bool allow_uturn,
                        const std::vector<std::string>& signalled = {}) {
  std::vector<EdgeSpec> internal;
  std::vector<ConnectionSpec> conns;
  // Incoming and outgoing normal edges per junction, in edge order (keeps this linear for big grids).
  std::unordered_map<std::string, size_t> junction;
  for (size_t k = 0; k < s.junctions.size(); ++k) junction.emplace(s.junctions[k].id, k);
  std::vector<std::vector<size_t>> ins(s.junctions.size()), outs(s.junctions.size());
  for (size_t k = 0; k < s.edges.size(); ++k) {
    if (s.edges[k].function != EdgeFunction::Normal) continue;
    outs[junction.at(s.edges[k].from)].push_back(k);
    ins[junction.at(s.edges[k].to)].push_back(k);
  }
  for (size_t jk = 0; jk < s.junctions.size(); ++jk) {
    JunctionSpec& j = s.junctions[jk];
    bool tl = std::find(signalled.begin(), signalled.end(), j.id) != signalled.end();
    int link = 0;
    for (size_t ik : ins[jk]) {
      const EdgeSpec& in = s.edges[ik];
      for (const auto& inl : in.lanes) j.inc_lanes.push_back(inl.id);
      for (size_t ok : outs[jk]) {
        const EdgeSpec& out = s.edges[ok];
        const JunctionSpec* a = &s.junctions[junction.at(in.from)];
        const JunctionSpec* b = &s.junctions[junction.at(out.to)];
        char dir = detail::turn_dir({a->x, a->y}, {j.x, j.y}, {j.x, j.y}, {b->x, b->y});
        if (in.from == out.to) dir = 't';
        if (dir == 't' && !allow_uturn) continue;
        for (const auto& inl : in.lanes) {
          int to_lane = std::min<int>(inl.index, static_cast<int>(out.lanes.size()) - 1);
          ConnectionSpec c;
          c.from = in.id;
          c.to = out.id;
          c.from_lane = inl.index;
          c.to_lane = to_lane;
          c.dir = dir;
          c.state = tl ? 'O' : 'M';
          if (tl) {
            c.tl = j.id;
            c.link_index = link;
          }
          if (with_internal) {
            EdgeSpec ie;
            ie.id = ":" + j.id + "_" + std::to_string(link);
            ie.function = EdgeFunction::Internal;
            LaneSpec il = detail::make_lane(ie.id, 0, internal_length, inl.speed, {j.x, j.y}, {j.x, j.y});
            il.shape = {inl.shape.back(), out.lanes[to_lane].shape.front()};
            ie.lanes.push_back(il);
            j.int_lanes.push_back(il.id);
            c.via = il.id;
            ConnectionSpec ic;
            ic.from = ie.id;
            ic.to = out.id;
            ic.from_lane = 0;
            ic.to_lane = to_lane;
            ic.dir = dir;
            ic.state = 'M';
            internal.push_back(std::move(ie));
            conns.push_back(c);
            conns.push_back(ic);
          } else {
            conns.push_back(c);
          }
          ++link;
        }
      }
    }
  }
  // SUMO writes internal edges before the normal ones; keep that order.
  internal.insert(internal.end(), s.edges.begin(), s.edges.end());
  s.edges = std::move(internal);
  int line = 1000;
  for (auto& c : conns) c.loc = {s.source, line++};
  s.connections.insert(s.connections.end(), conns.begin(), conns.end());
}

/// A cols x rows grid of priority junctions with two-way edges between neighbours.
inline NetSpec make_grid_spec(int cols, int rows, const GridOptions& o = {}) {
  NetSpec s;
  s.source = "grid.net.xml";
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      JunctionSpec j;
      j.id = grid_junction(c, r);
      j.type = "priority";
      j.x = c * o.spacing;
      j.y = r * o.spacing;
      j.loc = {s.source, 1 + r * cols + c};
      s.junctions.push_back(j);
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int dc[] = {1, -1, 0, 0}, dr[] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        int c1 = c + dc[k], r1 = r + dr[k];
        if (c1 < 0 || r1 < 0 || c1 >= cols || r1 >= rows) continue;
        add_edge(s, grid_edge(c, r, c1, r1), s.junctions[r * cols + c], s.junctions[r1 * cols + c1], o.lanes,
                 o.speed);
      }
    }
  connect_all(s, o.with_internal, o.internal_length, o.allow_uturn);
  return s;
}

/// A one-way chain K0 -E0-> K1 -E1-> ... of `segments` edges, each `length` m, lane i -> lane i.
inline NetSpec make_corridor_spec(int segments, double length = 100, int lanes = 1, double speed = 13.89) {
  NetSpec s;
  s.source = "corridor.net.xml";
  for (int k = 0; k <= segments; ++k) {
    JunctionSpec j;
    j.id = "K" + std::to_string(k);
    j.type = (k == 0 || k == segments) ? "dead_end" : "priority";
    j.x = k * length;
    j.loc = {s.source, k + 1};
    s.junctions.push_back(j);
  }
  for (int k = 0; k < segments; ++k)
    add_edge(s, "E" + std::to_string(k), s.junctions[k], s.junctions[k + 1], lanes, speed);
  connect_all(s, false, 0, false);
  return s;
}

/// Two-phase static program for the signal cross: phase 0 green for links whose from-edge is in
/// `green_first` (N/S approaches by default), phase 1 for the others; each green followed by 3 s yellow.
inline TlLogicSpec make_cross_program(const NetSpec& s, const std::string& program_id, double green = 30) {
  TlLogicSpec t;
  t.id = "C";
  t.program_id = program_id;
  t.loc = {s.source, 900};
  int links = 0;
  std::vector<bool> ns;
  for (const auto& c : s.connections)
    if (c.tl == "C") {
      links = std::max(links, c.link_index + 1);
      ns.resize(links);
      ns[c.link_index] = c.from == "NtoC" || c.from == "StoC";
    }
  auto state = [&](bool for_ns, char on) {
    std::string st(links, 'r');
    for (int i = 0; i < links; ++i)
      if (ns[i] == for_ns) st[i] = on;
    return st;
  };
  auto phase = [](double duration, std::string st) {
    PhaseSpec p;
    p.duration = duration;
    p.state = std::move(st);
    return p;
  };
  t.phases = {phase(green, state(true, 'G')), phase(3, state(true, 'y')), phase(green, state(false, 'G')),
              phase(3, state(false, 'y'))};
  return t;
}

/// One signalled four-arm intersection "C" with arms N, E, S, W 100 m away; two-way edges, 1 car lane
/// each. With `bus_lane`, the approach "WtoC" gets a bus-only lane at index 0 (the car lane becomes
/// index 1), which also has a connection to "CtoE" lane 0 with its own link index.
inline NetSpec make_signal_spec(bool bus_lane = false, bool with_internal = false) {
  NetSpec s;
  s.source = "cross.net.xml";
  auto junction = [&](const std::string& id, const std::string& type, double x, double y) {
    JunctionSpec j;
    j.id = id;
    j.type = type;
    j.x = x;
    j.y = y;
    j.loc = {s.source, static_cast<int>(s.junctions.size()) + 1};
    s.junctions.push_back(j);
  };
  junction("C", "traffic_light", 0, 0);
  junction("N", "dead_end", 0, 100);
  junction("E", "dead_end", 100, 0);
  junction("S", "dead_end", 0, -100);
  junction("W", "dead_end", -100, 0);
  for (const char* arm : {"N", "E", "S", "W"}) {
    add_edge(s, std::string(arm) + "toC", arm, "C");
    add_edge(s, std::string("Cto") + arm, "C", arm);
  }
  if (bus_lane) {
    for (auto& e : s.edges)
      if (e.id == "WtoC") {
        LaneSpec bus = e.lanes[0];
        bus.allow = "bus";
        bus.permissions = vclass_list_mask("bus");
        e.lanes[0].index = 1;
        e.lanes[0].id = lane_of(e.id, 1);
        e.lanes.insert(e.lanes.begin(), bus);
      }
  }
  connect_all(s, with_internal, 6, false, {"C"});
  s.tl_logics.push_back(make_cross_program(s, "0"));
  return s;
}

/// Removes every connection from `from_edge` to `to_edge` (and the internal continuation, if any):
/// a forbidden turn.
inline void remove_connection(NetSpec& s, const std::string& from_edge, const std::string& to_edge) {
  std::vector<std::string> vias;
  for (const auto& c : s.connections)
    if (c.from == from_edge && c.to == to_edge && !c.via.empty())
      vias.push_back(c.via.substr(0, c.via.rfind('_')));
  std::erase_if(s.connections, [&](const ConnectionSpec& c) {
    return (c.from == from_edge && c.to == to_edge) ||
           std::find(vias.begin(), vias.end(), c.from) != vias.end();
  });
}

}  // namespace lpsim::test

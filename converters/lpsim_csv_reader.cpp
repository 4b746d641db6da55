// Reader for the original LPSim CSV inputs (nodes.csv, edges.csv, OD demand). The CSV has no lane-level
// topology, so connections and signal programs are derived here by fixed, documented rules:
//
// Coordinates: nodes.csv x/y are WGS84 longitude/latitude when every x is within [-180,180], every y within
//   [-90,90] and the edge lengths agree better with the degree reading than with the raw numbers (median of
//   |log(length / straight distance)| over edges between distinct positions; with no such edge the range test
//   alone decides). Degrees are projected equirectangularly: x = R cos(mean lat) (lon - min lon),
//   y = R (lat - min lat), R = 6371008.8 m, so the network's south-west corner is (0,0). Otherwise x/y are
//   taken as metres unchanged.
// Edges: id = uniqueid; endpoints osmid_u/osmid_v when the header has them, else u/v (osmids). lanes: rounded
//   to a whole number; 0, empty or a missing column -> 1. speed m/s = speed_mph * 0.44704; 0, empty or a
//   missing column -> 13.89 m/s (50 km/h). Every lane's length is `length` (not the straight distance); its
//   shape is the straight line between the two node positions. Lane ids are "<edge id>_<index>".
// Junctions: one per node, in nodes.csv order (OD indices rely on this). Type: dead_end when the node lacks
//   incoming or outgoing edges, traffic_light when `highway` is exactly "traffic_signals" and the node has
//   approaches in both heading groups (below), priority otherwise.
// Connections (no internal lanes): at each node every incoming edge connects to every outgoing edge except
//   the U-turn back to its own source node, which is kept only when the node offers that edge no other exit.
//   Incoming lane i goes to outgoing lane min(i, outgoing lanes - 1), so every lane has a way on.
//   dir: 't' for the U-turn; otherwise from the turn angle between the two edges' headings: within 30 degrees
//   's', to the left 'l', to the right 'r' (zero-length geometry counts as straight).
//   Heading groups: the reference approach is the incoming edge with the largest speed*lanes (first in file
//   order on ties); approaches whose axis is within 45 degrees of its axis form group A, the rest group B.
//   state: an approach is major when it is in group A and its speed*lanes is at least half the reference's;
//   its straight and right links get 'M', its left and U-turn links 'm', every link of a minor approach 'm'.
//   At traffic lights the same rule gives SUMO's signal-off states 'O' / 'o'.
// Signals (tlLogic id = node osmid, programID "0", static, offset 0): links are the node's connections in
//   order (linkIndex = position). Phases: group A green 30 s ('G', left and U-turns 'g'), A yellow 3 s, group
//   B green 30 s, B yellow 3 s; links not in the active group are red.
// OD CSV: vehicle id "od<row>" (row = 0-based data row, whatever an index column says); depart = dep_time;
//   origin/destination are indices into the junctions (nodes.csv row order).
#include "converters/lpsim_csv_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

#include "converters/csv_table.hpp"

namespace lpsim {

namespace {

constexpr double kMphToMetresPerSecond = 0.44704;
constexpr double kDefaultSpeed = 13.89;     // m/s, SUMO's default edge speed
constexpr double kEarthRadius = 6371008.8;  // m, mean radius
constexpr int kMaxLanes = 32;
constexpr double kGreenSeconds = 30, kYellowSeconds = 3;
constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kStraightTolerance = 30 * kDegToRad;
constexpr double kSameAxisTolerance = 45 * kDegToRad;
constexpr double kMajorScoreShare = 0.5;

struct RawNodes {
  std::vector<std::string> id;
  std::vector<double> x, y;  // as written in the file
  std::vector<uint8_t> signal;
  std::vector<SourceLoc> loc;
  std::unordered_map<std::string, uint32_t> index;
};

struct RawEdge {
  std::string id;
  uint32_t u = 0, v = 0;  // node indices
  double length = 0, speed = kDefaultSpeed;
  int lanes = 1;
  SourceLoc loc;
};

RawNodes read_nodes(const std::string& path) {
  const CsvTable t = CsvTable::read_file(path);
  const size_t c_id = t.column("osmid"), c_x = t.column("x"), c_y = t.column("y");
  const auto c_highway = t.find_column("highway");
  RawNodes n;
  const size_t rows = t.num_rows();
  n.id.reserve(rows);
  n.x.reserve(rows);
  n.y.reserve(rows);
  n.signal.reserve(rows);
  n.loc.reserve(rows);
  n.index.reserve(rows);
  for (size_t r = 0; r < rows; ++r) {
    std::string id(t.id(r, c_id));
    if (id.empty()) t.fail(r, c_id, "empty node id");
    if (!n.index.emplace(id, static_cast<uint32_t>(n.id.size())).second) t.fail(r, c_id, "duplicate node id");
    n.id.push_back(std::move(id));
    n.x.push_back(t.number(r, c_x));
    n.y.push_back(t.number(r, c_y));
    n.signal.push_back(c_highway && t.trimmed(r, *c_highway) == "traffic_signals");
    n.loc.push_back(t.loc(r));
  }
  return n;
}

std::vector<RawEdge> read_edges(const std::string& path, const RawNodes& nodes) {
  const CsvTable t = CsvTable::read_file(path);
  const size_t c_id = t.column("uniqueid"), c_length = t.column("length");
  // The full-network header carries dense indices in u/v and osmids in osmid_u/osmid_v.
  const bool osmid_columns = t.find_column("osmid_u").has_value();
  const size_t c_u = t.column(osmid_columns ? "osmid_u" : "u");
  const size_t c_v = t.column(osmid_columns ? "osmid_v" : "v");
  const auto c_lanes = t.find_column("lanes");
  const auto c_speed = t.find_column("speed_mph");

  std::vector<RawEdge> edges(t.num_rows());
  std::unordered_set<std::string> seen;
  seen.reserve(edges.size());
  auto node_of = [&](size_t r, size_t c) {
    auto it = nodes.index.find(std::string(t.trimmed(r, c)));
    if (it == nodes.index.end()) t.fail(r, c, "unknown node (not in the nodes file)");
    return it->second;
  };
  for (size_t r = 0; r < edges.size(); ++r) {
    RawEdge& e = edges[r];
    e.id = std::string(t.id(r, c_id));
    if (e.id.empty()) t.fail(r, c_id, "empty edge id");
    if (!seen.insert(e.id).second) t.fail(r, c_id, "duplicate edge id");
    e.u = node_of(r, c_u);
    e.v = node_of(r, c_v);
    e.length = t.number(r, c_length);
    if (e.length < 0) t.fail(r, c_length, "negative length");
    if (c_lanes) {
      const double lanes = t.optional_number(r, *c_lanes).value_or(0);
      if (lanes < 0) t.fail(r, *c_lanes, "negative lane count");
      if (lanes > kMaxLanes) t.fail(r, *c_lanes, "more than " + std::to_string(kMaxLanes) + " lanes");
      e.lanes = std::max(1, static_cast<int>(std::lround(lanes)));
    }
    if (c_speed) {
      const double mph = t.optional_number(r, *c_speed).value_or(0);
      if (mph < 0) t.fail(r, *c_speed, "negative speed");
      if (mph > 0) e.speed = mph * kMphToMetresPerSecond;
    }
    e.loc = t.loc(r);
  }
  return edges;
}

double median(std::vector<double>& v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

struct Projection {
  bool degrees = false;
  double lon0 = 0, lat0 = 0, cos_lat = 1;

  Point apply(double x, double y) const {
    if (!degrees) return {x, y};
    return {kEarthRadius * cos_lat * (x - lon0) * kDegToRad, kEarthRadius * (y - lat0) * kDegToRad};
  }
};

Projection choose_projection(const RawNodes& nodes, const std::vector<RawEdge>& edges) {
  Projection p;
  if (nodes.id.empty()) return p;
  double lat_sum = 0;
  p.lon0 = nodes.x[0];
  p.lat0 = nodes.y[0];
  for (size_t i = 0; i < nodes.id.size(); ++i) {
    if (std::fabs(nodes.x[i]) > 180 || std::fabs(nodes.y[i]) > 90) return p;  // cannot be degrees
    lat_sum += nodes.y[i];
    p.lon0 = std::min(p.lon0, nodes.x[i]);
    p.lat0 = std::min(p.lat0, nodes.y[i]);
  }
  p.cos_lat = std::cos(lat_sum / static_cast<double>(nodes.id.size()) * kDegToRad);
  p.degrees = true;

  // Numbers that fit both readings: trust whichever reading the edge lengths agree with.
  std::vector<double> as_degrees, as_metres;
  for (const RawEdge& e : edges) {
    const double dx = nodes.x[e.v] - nodes.x[e.u], dy = nodes.y[e.v] - nodes.y[e.u];
    const double metres = std::hypot(dx, dy);
    if (metres <= 0 || e.length <= 0) continue;
    const double projected = kEarthRadius * kDegToRad * std::hypot(dx * p.cos_lat, dy);
    as_degrees.push_back(std::fabs(std::log(e.length / projected)));
    as_metres.push_back(std::fabs(std::log(e.length / metres)));
  }
  if (!as_degrees.empty()) p.degrees = median(as_degrees) <= median(as_metres);
  return p;
}

// Adjacency in compressed form: items of node n are list[begin[n] .. begin[n+1]), in edge file order.
struct Adjacency {
  std::vector<uint32_t> begin, list;
};

Adjacency build_adjacency(size_t num_nodes, const std::vector<RawEdge>& edges, bool incoming) {
  Adjacency a;
  a.begin.assign(num_nodes + 1, 0);
  for (const RawEdge& e : edges) ++a.begin[(incoming ? e.v : e.u) + 1];
  for (size_t n = 0; n < num_nodes; ++n) a.begin[n + 1] += a.begin[n];
  a.list.resize(edges.size());
  std::vector<uint32_t> fill(a.begin.begin(), a.begin.end() - 1);
  for (uint32_t i = 0; i < edges.size(); ++i) a.list[fill[incoming ? edges[i].v : edges[i].u]++] = i;
  return a;
}

double normalize_angle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

// Angle in [0, pi/2] between the lines (not the directions) of two headings.
double axis_difference(double a, double b) {
  const double d = std::fabs(normalize_angle(a - b));
  return std::min(d, kPi - d);
}

struct EdgeGeometry {
  double heading = 0;  // radians, counter-clockwise from +x
  bool has_heading = false;
};

char turn_direction(const EdgeGeometry& in, const EdgeGeometry& out) {
  if (!in.has_heading || !out.has_heading) return 's';
  const double turn = normalize_angle(out.heading - in.heading);  // positive = to the left
  if (std::fabs(turn) <= kStraightTolerance) return 's';
  return turn > 0 ? 'l' : 'r';
}

// Derives a node's connections (appended to net.connections) and, for signalised nodes, its tlLogic.
class NodeWiring {
 public:
  NodeWiring(const RawNodes& nodes, const std::vector<RawEdge>& edges, const std::vector<EdgeGeometry>& geom,
             NetSpec& net)
      : nodes_(nodes), edges_(edges), geom_(geom), net_(net) {}

  // Returns the junction type.
  std::string wire(uint32_t node, const uint32_t* in_begin, const uint32_t* in_end, const uint32_t* out_begin,
                   const uint32_t* out_end) {
    if (in_begin == in_end || out_begin == out_end) return "dead_end";
    const uint32_t reference = *std::max_element(in_begin, in_end, [&](uint32_t a, uint32_t b) {
      return score(a) < score(b);  // max_element keeps the first of equals
    });
    in_group_a_.clear();
    bool any_group_b = false;
    for (const uint32_t* e = in_begin; e != in_end; ++e) {
      const bool a = !geom_[*e].has_heading || !geom_[reference].has_heading ||
                     axis_difference(geom_[*e].heading, geom_[reference].heading) < kSameAxisTolerance;
      in_group_a_.push_back(a);
      any_group_b |= !a;
    }
    const bool signalised = nodes_.signal[node] && any_group_b;
    const double major_score = kMajorScoreShare * score(reference);

    const size_t first = net_.connections.size();
    link_group_a_.clear();
    for (const uint32_t* e = in_begin; e != in_end; ++e) {
      const RawEdge& in = edges_[*e];
      const bool group_a = in_group_a_[static_cast<size_t>(e - in_begin)];
      const bool major = group_a && score(*e) >= major_score;
      const bool other_exit =
          std::any_of(out_begin, out_end, [&](uint32_t o) { return edges_[o].v != in.u; });
      for (const uint32_t* o = out_begin; o != out_end; ++o) {
        const RawEdge& out = edges_[*o];
        const bool u_turn = out.v == in.u;
        if (u_turn && other_exit) continue;
        const char dir = u_turn ? 't' : turn_direction(geom_[*e], geom_[*o]);
        const bool yields = !major || dir == 'l' || dir == 't';
        const char state = signalised ? (yields ? 'o' : 'O') : (yields ? 'm' : 'M');
        for (int lane = 0; lane < in.lanes; ++lane) {
          ConnectionSpec c;
          c.from = in.id;
          c.to = out.id;
          c.from_lane = lane;
          c.to_lane = std::min(lane, out.lanes - 1);
          c.dir = dir;
          c.state = state;
          c.loc = in.loc;
          if (signalised) {
            c.tl = nodes_.id[node];
            c.link_index = static_cast<int>(net_.connections.size() - first);
          }
          net_.connections.push_back(std::move(c));
          link_group_a_.push_back(group_a);
        }
      }
    }
    if (!signalised) return "priority";
    net_.tl_logics.push_back(signal_program(node, first));
    return "traffic_light";
  }

 private:
  double score(uint32_t e) const { return edges_[e].speed * edges_[e].lanes; }

  TlLogicSpec signal_program(uint32_t node, size_t first) const {
    TlLogicSpec tl;
    tl.id = nodes_.id[node];
    tl.program_id = "0";
    tl.type = "static";
    tl.loc = nodes_.loc[node];
    for (const bool group_a : {true, false}) {
      PhaseSpec green, yellow;
      green.duration = kGreenSeconds;
      yellow.duration = kYellowSeconds;
      for (size_t k = 0; k < link_group_a_.size(); ++k) {
        const bool active = link_group_a_[k] == group_a;
        const char dir = net_.connections[first + k].dir;
        green.state.push_back(!active ? 'r' : (dir == 'l' || dir == 't') ? 'g' : 'G');
        yellow.state.push_back(active ? 'y' : 'r');
      }
      tl.phases.push_back(std::move(green));
      tl.phases.push_back(std::move(yellow));
    }
    return tl;
  }

  const RawNodes& nodes_;
  const std::vector<RawEdge>& edges_;
  const std::vector<EdgeGeometry>& geom_;
  NetSpec& net_;
  std::vector<bool> in_group_a_, link_group_a_;
};

}  // namespace

NetSpec read_lpsim_csv_net(const std::string& nodes_csv, const std::string& edges_csv) {
  const RawNodes nodes = read_nodes(nodes_csv);
  const std::vector<RawEdge> raw_edges = read_edges(edges_csv, nodes);
  const Projection proj = choose_projection(nodes, raw_edges);

  NetSpec net;
  net.source = nodes_csv + "," + edges_csv;
  const size_t num_nodes = nodes.id.size();
  std::vector<Point> pos(num_nodes);
  for (size_t i = 0; i < num_nodes; ++i) pos[i] = proj.apply(nodes.x[i], nodes.y[i]);

  std::vector<EdgeGeometry> geom(raw_edges.size());
  net.edges.reserve(raw_edges.size());
  for (size_t i = 0; i < raw_edges.size(); ++i) {
    const RawEdge& r = raw_edges[i];
    const Point a = pos[r.u], b = pos[r.v];
    if (a.x != b.x || a.y != b.y) geom[i] = {std::atan2(b.y - a.y, b.x - a.x), true};
    EdgeSpec e;
    e.id = r.id;
    e.from = nodes.id[r.u];
    e.to = nodes.id[r.v];
    e.loc = r.loc;
    e.lanes.resize(static_cast<size_t>(r.lanes));
    for (int l = 0; l < r.lanes; ++l) {
      LaneSpec& lane = e.lanes[static_cast<size_t>(l)];
      lane.id = r.id + "_" + std::to_string(l);
      lane.index = l;
      lane.speed = r.speed;
      lane.length = r.length;
      lane.shape = {a, b};
      lane.loc = r.loc;
    }
    net.edges.push_back(std::move(e));
  }

  const Adjacency in = build_adjacency(num_nodes, raw_edges, true);
  const Adjacency out = build_adjacency(num_nodes, raw_edges, false);
  NodeWiring wiring(nodes, raw_edges, geom, net);
  net.junctions.reserve(num_nodes);
  for (uint32_t n = 0; n < num_nodes; ++n) {
    JunctionSpec j;
    j.id = nodes.id[n];
    j.x = pos[n].x;
    j.y = pos[n].y;
    j.loc = nodes.loc[n];
    const uint32_t* in_b = in.list.data() + in.begin[n];
    const uint32_t* in_e = in.list.data() + in.begin[n + 1];
    size_t inc = 0;
    for (const uint32_t* e = in_b; e != in_e; ++e) inc += net.edges[*e].lanes.size();
    j.inc_lanes.reserve(inc);
    for (const uint32_t* e = in_b; e != in_e; ++e)
      for (const LaneSpec& lane : net.edges[*e].lanes) j.inc_lanes.push_back(lane.id);
    j.type = wiring.wire(n, in_b, in_e, out.list.data() + out.begin[n], out.list.data() + out.begin[n + 1]);
    net.junctions.push_back(std::move(j));
  }
  return net;
}

void read_lpsim_od_csv(const std::string& path, const NetSpec& net, DemandSpec& demand) {
  const CsvTable t = CsvTable::read_file(path);
  const size_t c_dep = t.column("dep_time"), c_origin = t.column("origin"), c_dest = t.column("destination");
  const int64_t num_nodes = static_cast<int64_t>(net.junctions.size());
  auto node_at = [&](size_t r, size_t c) -> const std::string& {
    const int64_t i = t.integer(r, c);
    if (i < 0 || i >= num_nodes)
      t.fail(r, c,
             "not a node index (the network has " + std::to_string(num_nodes) + " nodes, 0.." +
                 std::to_string(num_nodes - 1) + ")");
    return net.junctions[static_cast<size_t>(i)].id;
  };
  demand.vehicles.reserve(demand.vehicles.size() + t.num_rows());
  for (size_t r = 0; r < t.num_rows(); ++r) {
    VehicleSpec v;
    v.id = "od" + std::to_string(r);
    v.source = DemandSource::OdCsv;
    v.depart = t.number(r, c_dep);
    if (v.depart < 0) t.fail(r, c_dep, "negative departure time");
    v.from_junction = node_at(r, c_origin);
    v.to_junction = node_at(r, c_dest);
    v.loc = t.loc(r);
    demand.vehicles.push_back(std::move(v));
  }
}

}  // namespace lpsim

#include "converters/net_reader.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include "converters/cli_options.hpp"       // parse_sumo_bool
#include "converters/route_attributes.hpp"  // split_ids
#include "converters/tl_logic_reader.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Long shapes would make one-line error messages unreadable; the start of the value is enough to find it.
std::string excerpt(const std::string& value) {
  return value.size() <= 60 ? value : value.substr(0, 57) + "...";
}

// The values of a fixed set of attributes of the current element, captured in one pass over its attributes
// (XmlStream::for_each_attr) into buffers reused from element to element: no per-attribute lookup or string
// allocation for elements read by the hundred thousand. value(k) is null when key k is absent.
template <size_t N>
class AttrCapture {
 public:
  explicit AttrCapture(const std::array<std::string_view, N>& keys) : keys_(keys) {}

  void read(const XmlStream& xs) {
    present_.fill(false);
    xs.for_each_attr([this](std::string_view name, std::string_view value) {
      for (size_t k = 0; k < N; ++k)
        if (name == keys_[k]) {
          values_[k].assign(value.data(), value.size());
          present_[k] = true;
          return;
        }
    });
  }
  const std::string* value(size_t k) const { return present_[k] ? &values_[k] : nullptr; }
  std::string text(size_t k) const { return present_[k] ? values_[k] : std::string(); }

 private:
  std::array<std::string_view, N> keys_;
  std::array<std::string, N> values_;
  std::array<bool, N> present_{};
};

// from_chars on one coordinate; SUMO writes plain decimals, no leading '+'.
bool parse_coord(const char*& p, const char* end, double& out) {
  auto [ptr, ec] = std::from_chars(p, end, out);
  if (ec != std::errc() || !std::isfinite(out)) return false;
  p = ptr;
  return true;
}

// "x,y x,y ..." (a third ",z" per point is allowed and dropped). Empty: no points.
std::vector<Point> parse_shape(const XmlStream& xs, const char* key, const std::string& text) {
  size_t points = 0;
  for (size_t i = 0; i < text.size(); ++i)
    if (!is_space(text[i]) && (i == 0 || is_space(text[i - 1]))) ++points;
  std::vector<Point> shape;
  shape.reserve(points);
  const char* p = text.data();
  const char* end = p + text.size();
  auto bad = [&]() {
    xs.fail(std::string("attribute '") + key + "' is not a list of x,y points: '" + excerpt(text) + "'");
  };
  for (;;) {
    while (p < end && is_space(*p)) ++p;
    if (p == end) break;
    Point pt;
    if (!parse_coord(p, end, pt.x) || p == end || *p != ',') bad();
    ++p;
    if (!parse_coord(p, end, pt.y)) bad();
    if (p < end && *p == ',') {
      ++p;
      double z = 0;
      if (!parse_coord(p, end, z)) bad();
    }
    if (p < end && !is_space(*p)) bad();
    shape.push_back(pt);
  }
  return shape;
}

double required_non_negative(const XmlStream& xs, const char* key, const std::string* v) {
  if (!v) xs.fail(std::string("missing attribute '") + key + "'");
  auto d = parse_double(*v);
  if (!d) xs.fail(std::string("attribute '") + key + "' is not a finite number: '" + *v + "'");
  if (*d < 0) xs.fail(std::string("attribute '") + key + "' must not be negative: '" + *v + "'");
  if (*d > std::numeric_limits<float>::max())  // lane lengths and speeds are stored as floats
    xs.fail(std::string("attribute '") + key + "' is beyond a 32-bit float's range: '" + *v + "'");
  return *d;
}

int required_index(const XmlStream& xs, const char* key, const std::string* v) {
  if (!v) xs.fail(std::string("missing attribute '") + key + "'");
  auto i = parse_integer(*v);
  if (!i || *i < 0 || *i > 1'000'000)
    xs.fail(std::string("attribute '") + key + "' is not a lane index (integer >= 0): '" + *v + "'");
  return static_cast<int>(*i);
}

const std::string& required(const XmlStream& xs, const char* key, const std::string* v) {
  if (!v) xs.fail(std::string("missing attribute '") + key + "'");
  return *v;
}

// As XmlStream::number.
double number(const XmlStream& xs, const char* key, const std::string* v, double fallback) {
  if (!v) return fallback;
  auto d = parse_double(*v);
  if (!d) xs.fail(std::string("attribute '") + key + "' is not a finite number: '" + *v + "'");
  return *d;
}

// As XmlStream::integer.
long long integer(const XmlStream& xs, const char* key, const std::string* v, long long fallback) {
  if (!v) return fallback;
  auto i = parse_integer(*v);
  if (!i) xs.fail(std::string("attribute '") + key + "' is not an integer: '" + *v + "'");
  return *i;
}

// A SUMO boolean attribute (parse_sumo_bool's spellings).
bool flag(const XmlStream& xs, const char* key, const std::string* v, bool fallback) {
  if (!v) return fallback;
  const std::optional<bool> b = parse_sumo_bool(*v);
  if (!b) xs.fail(std::string("attribute '") + key + "' is not a boolean: '" + *v + "'");
  return *b;
}

EdgeFunction parse_function(const XmlStream& xs, const std::string* f) {
  if (!f || *f == "normal") return EdgeFunction::Normal;
  if (*f == "internal") return EdgeFunction::Internal;
  if (*f == "connector") return EdgeFunction::Connector;
  if (*f == "crossing") return EdgeFunction::Crossing;
  if (*f == "walkingarea") return EdgeFunction::WalkingArea;
  xs.fail("unknown edge function '" + *f + "'");
}

// SUMO writes link directions as one letter, except "invalid" for links without a direction; that one is
// stored as 'T' as net_spec.hpp documents (note SUMO also uses 'T' for a left-hand-traffic turnaround).
char parse_dir(const XmlStream& xs, const std::string* d) {
  if (!d) return 's';
  if (*d == "invalid") return 'T';
  if (d->size() != 1 || std::string_view("stTlrLR").find((*d)[0]) == std::string_view::npos)
    xs.fail("unknown link direction dir='" + *d + "'");
  return (*d)[0];
}

char parse_state(const XmlStream& xs, const std::string* s) {
  if (!s) return 'M';
  if (s->size() != 1) xs.fail("link state must be one character: state='" + *s + "'");
  return (*s)[0];
}

Point parse_offset(const XmlStream& xs) {
  auto v = xs.attr("netOffset");
  if (!v) return {};
  std::vector<Point> pts = parse_shape(xs, "netOffset", *v);
  if (pts.size() != 1) xs.fail("attribute 'netOffset' is not one x,y point: '" + excerpt(*v) + "'");
  return pts[0];
}

class NetParser {
 public:
  explicit NetParser(const std::string& path) : xs_(path) {
    net_.source = path;
    reserve_for(path);
  }

  NetSpec run() {
    bool root_seen = false;
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof) break;
      if (ev != XmlStream::Event::Start) continue;
      if (!root_seen) {
        if (xs_.name() != "net")
          throw InputError(xs_.loc(),
                           "root element is <" + xs_.name() + ">, expected <net> of a SUMO network");
        root_seen = true;
        continue;
      }
      if (xs_.depth() == 2 && xs_.name() == "request" && in_junction_) {
        read_request();
        continue;
      }
      if (xs_.depth() != 1) continue;
      const std::string& name = xs_.name();
      in_junction_ = name == "junction";
      if (name == "edge") {
        read_edge();
      } else if (name == "junction") {
        read_junction();
      } else if (name == "connection") {
        read_connection();
      } else if (name == "tlLogic") {
        net_.tl_logics.push_back(read_tl_logic(xs_));
      } else if (name == "roundabout") {
        RoundaboutSpec r;
        r.nodes = split_ids(xs_.get("nodes", ""));
        r.edges = split_ids(xs_.get("edges", ""));
        net_.roundabouts.push_back(std::move(r));
      } else if (name == "location") {
        net_.net_offset = parse_offset(xs_);
      } else if (name == "type") {
        read_edge_type();
      }
    }
    if (net_.edges.empty()) throw InputError(SourceLoc{xs_.path(), 0}, "network has no <edge> elements");
    return std::move(net_);
  }

 private:
  // Growing vectors of 100k+ specs re-touches every page several times. Bytes per element in netconvert
  // output are at least ~300 (edge with its lane), ~200 (connection), ~600 (junction), so these bounds
  // rarely fall short; the unused tail of an over-reservation is never touched and so costs no memory.
  // Compressed files give no useful size: they grow as needed.
  void reserve_for(const std::string& path) {
    if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".gz") == 0) return;
    std::error_code ec;
    auto bytes = std::filesystem::file_size(path, ec);
    if (ec) return;
    net_.edges.reserve(bytes / 300);
    net_.connections.reserve(bytes / 200);
    net_.junctions.reserve(bytes / 600);
  }

  // Checks run in the order of the attributes below, so the first problem reported is always the same one.
  enum EdgeAttr { kEdgeId, kEdgeFunction, kEdgeFrom, kEdgeTo, kEdgePriority, kEdgeType, kEdgeBidi };
  AttrCapture<7> edge_attrs_{{"id", "function", "from", "to", "priority", "type", "bidi"}};

  void read_edge() {
    const auto& a = edge_attrs_;
    edge_attrs_.read(xs_);
    EdgeSpec e;
    e.loc = xs_.loc();
    e.id = required(xs_, "id", a.value(kEdgeId));
    e.function = parse_function(xs_, a.value(kEdgeFunction));
    if (e.function == EdgeFunction::Normal) {
      e.from = required(xs_, "from", a.value(kEdgeFrom));
      e.to = required(xs_, "to", a.value(kEdgeTo));
    } else {
      e.from = a.text(kEdgeFrom);
      e.to = a.text(kEdgeTo);
    }
    e.priority = static_cast<int>(integer(xs_, "priority", a.value(kEdgePriority), -1));
    e.type = a.text(kEdgeType);
    e.bidi = a.text(kEdgeBidi);
    const int depth = xs_.depth();
    e.lanes.reserve(4);
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof)
        throw InputError(e.loc, "<edge id=\"" + e.id + "\">: unexpected end of file");
      if (ev == XmlStream::Event::End && xs_.depth() == depth) break;
      if (ev == XmlStream::Event::Start && xs_.depth() == depth + 1 && xs_.name() == "lane")
        e.lanes.push_back(read_lane(e.function));
    }
    check_lane_indices(e);
    net_.edges.push_back(std::move(e));
  }

  // SUMO gives a restriction's class its limit on every lane of the type's edges. A class name this version
  // does not know is left out (no vehicle LPSim runs can have it), as unknown names in allow/disallow are.
  void read_edge_type() {
    EdgeTypeSpec t;
    t.loc = xs_.loc();
    t.id = xs_.get("id", "");
    if (t.id.empty()) xs_.fail("<type> without an id");
    const int depth = xs_.depth();
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof)
        throw InputError(t.loc, "<type id=\"" + t.id + "\">: unexpected end of file");
      if (ev == XmlStream::Event::End && xs_.depth() == depth) break;
      if (ev != XmlStream::Event::Start || xs_.depth() != depth + 1 || xs_.name() != "restriction") continue;
      const std::string vclass = xs_.get("vClass", "");
      const std::string speed = xs_.get("speed", "");
      if (vclass.empty()) xs_.fail("<restriction> of type '" + t.id + "' without a vClass");
      const double limit = required_non_negative(xs_, "speed", speed.empty() ? nullptr : &speed);
      if (vclass == "ignoring" || vclass_name_bit(vclass) != 0)
        t.restrictions.push_back({vehicle_vclass_mask(vclass), limit});
    }
    if (!t.restrictions.empty()) net_.edge_types.push_back(std::move(t));
  }

  enum LaneAttr { kLaneId, kLaneIndex, kLaneSpeed, kLaneLength, kLaneAllow, kLaneDisallow, kLaneShape };
  AttrCapture<7> lane_attrs_{{"id", "index", "speed", "length", "allow", "disallow", "shape"}};

  LaneSpec read_lane(EdgeFunction function) {
    const auto& a = lane_attrs_;
    lane_attrs_.read(xs_);
    LaneSpec l;
    l.loc = xs_.loc();
    l.id = required(xs_, "id", a.value(kLaneId));
    l.index = required_index(xs_, "index", a.value(kLaneIndex));
    l.speed = required_non_negative(xs_, "speed", a.value(kLaneSpeed));
    l.length = required_non_negative(xs_, "length", a.value(kLaneLength));
    l.allow = a.text(kLaneAllow);
    l.disallow = a.text(kLaneDisallow);
    // Crossings and walking areas belong to pedestrians whatever their lists say.
    const bool pedestrian_area = function == EdgeFunction::Crossing || function == EdgeFunction::WalkingArea;
    l.permissions = pedestrian_area ? kVClassPedestrian : lane_permissions(l.allow, l.disallow);
    if (!vehicle_lane(l.permissions)) ++net_.skipped_non_car_lanes;
    if (auto shape = a.value(kLaneShape)) l.shape = parse_shape(xs_, "shape", *shape);
    return l;
  }

  // SUMO places a lane by its order inside <edge>, and connections count fromLane/toLane in that order; the
  // index attribute is not authoritative (netconvert 1.22 wrote index="0" twice on an internal edge of
  // bologna_acosta). So the index kept is the position, whatever the attribute said.
  static void check_lane_indices(EdgeSpec& e) {
    if (e.lanes.empty()) throw InputError(e.loc, "<edge id=\"" + e.id + "\">: edge has no <lane>");
    for (size_t i = 0; i < e.lanes.size(); ++i) e.lanes[i].index = static_cast<int>(i);
  }

  bool in_junction_ = false;

  enum JunctionAttr { kJunctionId, kJunctionType, kJunctionX, kJunctionY, kJunctionInc, kJunctionInt };
  AttrCapture<6> junction_attrs_{{"id", "type", "x", "y", "incLanes", "intLanes"}};

  void read_junction() {
    const auto& a = junction_attrs_;
    junction_attrs_.read(xs_);
    JunctionSpec j;
    j.loc = xs_.loc();
    j.id = required(xs_, "id", a.value(kJunctionId));
    j.type = a.text(kJunctionType);
    j.x = number(xs_, "x", a.value(kJunctionX), 0);
    j.y = number(xs_, "y", a.value(kJunctionY), 0);
    if (auto inc = a.value(kJunctionInc)) j.inc_lanes = split_ids(*inc);
    if (auto in = a.value(kJunctionInt)) j.int_lanes = split_ids(*in);
    net_.junctions.push_back(std::move(j));
  }

  // <request index response foes>: which links of the junction this link yields to / conflicts with.
  // SUMO writes the bit of link j at character (n-1-j).
  enum RequestAttr { kRequestIndex, kRequestResponse, kRequestFoes };
  AttrCapture<3> request_attrs_{{"index", "response", "foes"}};

  void read_request() {
    const auto& a = request_attrs_;
    request_attrs_.read(xs_);
    JunctionSpec& j = net_.junctions.back();
    long long index = integer(xs_, "index", a.value(kRequestIndex), -1);
    if (index < 0 || index > 4096) xs_.fail("request index out of range: " + a.text(kRequestIndex));
    std::string response = required(xs_, "response", a.value(kRequestResponse)), foes = a.text(kRequestFoes);
    auto bits = [](const std::string& s) { return s.find_first_not_of("01") == std::string::npos; };
    if (!bits(response) || !bits(foes)) xs_.fail("request bits must be 0 or 1: '" + response + "'");
    const auto i = static_cast<size_t>(index);
    if (j.response.size() <= i) {
      j.response.resize(i + 1);
      j.foes.resize(i + 1);
    }
    j.response[i] = std::move(response);
    j.foes[i] = std::move(foes);
  }

  enum ConnectionAttr {
    kConnFrom,
    kConnTo,
    kConnFromLane,
    kConnToLane,
    kConnVia,
    kConnTl,
    kConnLink,
    kConnDir,
    kConnState,
    kConnKeepClear
  };
  AttrCapture<10> connection_attrs_{
      {"from", "to", "fromLane", "toLane", "via", "tl", "linkIndex", "dir", "state", "keepClear"}};

  void read_connection() {
    const auto& a = connection_attrs_;
    connection_attrs_.read(xs_);
    ConnectionSpec c;
    c.loc = xs_.loc();
    c.from = required(xs_, "from", a.value(kConnFrom));
    c.to = required(xs_, "to", a.value(kConnTo));
    c.from_lane = required_index(xs_, "fromLane", a.value(kConnFromLane));
    c.to_lane = required_index(xs_, "toLane", a.value(kConnToLane));
    c.via = a.text(kConnVia);
    c.tl = a.text(kConnTl);
    long long link = integer(xs_, "linkIndex", a.value(kConnLink), -1);
    if (link < -1 || link > 1'000'000)
      xs_.fail("attribute 'linkIndex' out of range: '" + a.text(kConnLink) + "'");
    c.link_index = static_cast<int>(link);
    c.dir = parse_dir(xs_, a.value(kConnDir));
    c.state = parse_state(xs_, a.value(kConnState));
    c.keep_clear = flag(xs_, "keepClear", a.value(kConnKeepClear), true);
    net_.connections.push_back(std::move(c));
  }

  XmlStream xs_;
  NetSpec net_;
};

}  // namespace

NetSpec read_sumo_net(const std::string& path) { return NetParser(path).run(); }

}  // namespace lpsim

#include "converters/net_reader.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>

#include "converters/route_attributes.hpp"  // split_ids
#include "converters/tl_logic_reader.hpp"
#include "converters/vclass.hpp"
#include "converters/xml_stream.hpp"

namespace lpsim {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }


// Long shapes would make one-line error messages unreadable; the start of the value is enough to find it.
std::string excerpt(const std::string& value) {
  return value.size() <= 60 ? value : value.substr(0, 57) + "...";
}

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

double required_non_negative(const XmlStream& xs, const char* key) {
  auto v = xs.attr(key);
  if (!v) xs.fail(std::string("missing attribute '") + key + "'");
  auto d = parse_double(*v);
  if (!d) xs.fail(std::string("attribute '") + key + "' is not a finite number: '" + *v + "'");
  if (*d < 0) xs.fail(std::string("attribute '") + key + "' must not be negative: '" + *v + "'");
  return *d;
}

int required_index(const XmlStream& xs, const char* key) {
  auto v = xs.attr(key);
  if (!v) xs.fail(std::string("missing attribute '") + key + "'");
  auto i = parse_integer(*v);
  if (!i || *i < 0 || *i > 1'000'000)
    xs.fail(std::string("attribute '") + key + "' is not a lane index (integer >= 0): '" + *v + "'");
  return static_cast<int>(*i);
}

EdgeFunction parse_function(const XmlStream& xs) {
  auto f = xs.attr("function");
  if (!f || *f == "normal") return EdgeFunction::Normal;
  if (*f == "internal") return EdgeFunction::Internal;
  if (*f == "connector") return EdgeFunction::Connector;
  if (*f == "crossing") return EdgeFunction::Crossing;
  if (*f == "walkingarea") return EdgeFunction::WalkingArea;
  xs.fail("unknown edge function '" + *f + "'");
}

// SUMO writes link directions as one letter, except "invalid" for links without a direction; that one is
// stored as 'T' as net_spec.hpp documents (note SUMO also uses 'T' for a left-hand-traffic turnaround).
char parse_dir(const XmlStream& xs) {
  auto d = xs.attr("dir");
  if (!d) return 's';
  if (*d == "invalid") return 'T';
  if (d->size() != 1 || std::string_view("stTlrLR").find((*d)[0]) == std::string_view::npos)
    xs.fail("unknown link direction dir='" + *d + "'");
  return (*d)[0];
}

char parse_state(const XmlStream& xs) {
  auto s = xs.attr("state");
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
          throw InputError(xs_.loc(), "root element is <" + xs_.name() + ">, expected <net> of a SUMO network");
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

  void read_edge() {
    EdgeSpec e;
    e.loc = xs_.loc();
    e.id = xs_.required("id");
    e.function = parse_function(xs_);
    if (e.function == EdgeFunction::Normal) {
      e.from = xs_.required("from");
      e.to = xs_.required("to");
    } else {
      e.from = xs_.get("from", "");
      e.to = xs_.get("to", "");
    }
    e.priority = static_cast<int>(xs_.integer("priority", -1));
    e.type = xs_.get("type", "");
    const int depth = xs_.depth();
    e.lanes.reserve(4);
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof) throw InputError(e.loc, "<edge id=\"" + e.id + "\">: unexpected end of file");
      if (ev == XmlStream::Event::End && xs_.depth() == depth) break;
      if (ev == XmlStream::Event::Start && xs_.depth() == depth + 1 && xs_.name() == "lane")
        e.lanes.push_back(read_lane(e.function));
    }
    check_lane_indices(e);
    net_.edges.push_back(std::move(e));
  }

  LaneSpec read_lane(EdgeFunction function) {
    LaneSpec l;
    l.loc = xs_.loc();
    l.id = xs_.required("id");
    l.index = required_index(xs_, "index");
    l.speed = required_non_negative(xs_, "speed");
    l.length = required_non_negative(xs_, "length");
    l.allow = xs_.get("allow", "");
    l.disallow = xs_.get("disallow", "");
    // Crossings and walking areas belong to pedestrians whatever their lists say.
    l.passenger_allowed = function != EdgeFunction::Crossing && function != EdgeFunction::WalkingArea &&
                          passenger_allowed(l.allow, l.disallow);
    if (!l.passenger_allowed) ++net_.skipped_non_car_lanes;
    if (auto shape = xs_.attr("shape")) l.shape = parse_shape(xs_, "shape", *shape);
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

  void read_junction() {
    JunctionSpec j;
    j.loc = xs_.loc();
    j.id = xs_.required("id");
    j.type = xs_.get("type", "");
    j.x = xs_.number("x", 0);
    j.y = xs_.number("y", 0);
    if (auto inc = xs_.attr("incLanes")) j.inc_lanes = split_ids(*inc);
    if (auto in = xs_.attr("intLanes")) j.int_lanes = split_ids(*in);
    net_.junctions.push_back(std::move(j));
  }

  // <request index response foes>: which links of the junction this link yields to / conflicts with.
  // SUMO writes the bit of link j at character (n-1-j).
  void read_request() {
    JunctionSpec& j = net_.junctions.back();
    long long index = xs_.integer("index", -1);
    if (index < 0 || index > 4096) xs_.fail("request index out of range: " + xs_.get("index", ""));
    std::string response = xs_.required("response"), foes = xs_.get("foes", "");
    for (char c : response + foes)
      if (c != '0' && c != '1') xs_.fail("request bits must be 0 or 1: '" + response + "'");
    const auto i = static_cast<size_t>(index);
    if (j.response.size() <= i) {
      j.response.resize(i + 1);
      j.foes.resize(i + 1);
    }
    j.response[i] = std::move(response);
    j.foes[i] = std::move(foes);
  }

  void read_connection() {
    ConnectionSpec c;
    c.loc = xs_.loc();
    c.from = xs_.required("from");
    c.to = xs_.required("to");
    c.from_lane = required_index(xs_, "fromLane");
    c.to_lane = required_index(xs_, "toLane");
    c.via = xs_.get("via", "");
    c.tl = xs_.get("tl", "");
    long long link = xs_.integer("linkIndex", -1);
    if (link < -1 || link > 1'000'000) xs_.fail("attribute 'linkIndex' out of range: '" + xs_.required("linkIndex") + "'");
    c.link_index = static_cast<int>(link);
    c.dir = parse_dir(xs_);
    c.state = parse_state(xs_);
    net_.connections.push_back(std::move(c));
  }

  XmlStream xs_;
  NetSpec net_;
};

}  // namespace

NetSpec read_sumo_net(const std::string& path) { return NetParser(path).run(); }

}  // namespace lpsim

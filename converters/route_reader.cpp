#include "converters/route_reader.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <string_view>
#include <unordered_set>

#include "converters/edge_id_interner.hpp"
#include "converters/route_attributes.hpp"
#include "converters/route_vtype.hpp"
#include "converters/tl_logic_reader.hpp"
#include "converters/xml_stream.hpp"
#include "core/time_range.hpp"

namespace lpsim {

namespace {

// A time attribute's value in seconds, or why it is not one: unparsable, negative, or beyond what the
// engine can represent (core/time_range.hpp).
struct TimeValue {
  double seconds = 0;
  std::string problem;  // empty when the value is usable
};

TimeValue parse_time_value(std::string_view key, const std::string& text) {
  TimeValue out;
  auto t = parse_sumo_time(text);
  const std::string quoted = "attribute '" + std::string(key) + "'";
  if (!t)
    out.problem = quoted + " is not a time: '" + text + "'";
  else if (*t < 0)
    out.problem = quoted + " is negative: '" + text + "'";
  else if (!time_in_range(*t))
    out.problem = quoted + " is beyond the largest time LPSim accepts (1e12 s): '" + text + "'";
  else
    out.seconds = *t;
  return out;
}

// Attributes of vehicle, trip and flow elements. They are copied once per element into buffers reused
// across elements, so a million vehicles cost one attribute pass and no allocations here.
enum Key : uint8_t {
  kId,
  kType,
  kDepart,
  kRoute,
  kDepartLane,
  kDepartPos,
  kDepartSpeed,
  kArrivalPos,
  kFrom,
  kTo,
  kVia,
  kFromJunction,
  kToJunction,
  kFromTaz,
  kToTaz,
  kBegin,
  kEnd,
  kPeriod,
  kVehsPerHour,
  kPerHour,
  kProbability,
  kNumber,
  kLine,
  kKeyCount
};
constexpr std::array<std::string_view, kKeyCount> kKeyNames = {
    "id",   "type",   "depart",      "route",        "departLane",  "departPos", "departSpeed", "arrivalPos",
    "from", "to",     "via",         "fromJunction", "toJunction",  "fromTaz",   "toTaz",       "begin",
    "end",  "period", "vehsPerHour", "perHour",      "probability", "number",    "line"};

struct TravellerAttrs {
  std::array<std::string, kKeyCount> value;
  std::array<bool, kKeyCount> present{};

  void read(const XmlStream& xs) {
    present.fill(false);
    xs.for_each_attr([this](std::string_view key, std::string_view v) {
      for (size_t i = 0; i < kKeyCount; ++i)
        if (key == kKeyNames[i]) {
          value[i].assign(v);
          present[i] = true;
          return;
        }
    });
  }
  const std::string* get(Key k) const { return present[k] ? &value[k] : nullptr; }
  // Edge and junction ids with the stray spaces real files carry removed.
  std::string id_value(Key k) const { return present[k] ? std::string(trim(value[k])) : std::string(); }
};

std::string_view element_name(const VehicleSpec& v) {
  return v.source == DemandSource::Trip ? "trip" : "vehicle";
}
std::string_view element_name(const FlowSpec&) { return "flow"; }

// Raises InputError for an id that appears twice among `items`, where at least one of the two comes from
// `first_new` on. Sorting (hash, index) pairs once per file costs far less than a node-based hash set
// filled vehicle by vehicle.
template <class Spec>
void check_unique_ids(const std::vector<Spec>& items, size_t first_new) {
  if (first_new == items.size()) return;
  std::vector<std::pair<size_t, size_t>> keyed(items.size());
  for (size_t i = 0; i < items.size(); ++i) keyed[i] = {std::hash<std::string>{}(items[i].id), i};
  std::sort(keyed.begin(), keyed.end());
  for (size_t a = 0; a < keyed.size();) {
    size_t b = a + 1;
    while (b < keyed.size() && keyed[b].first == keyed[a].first) ++b;
    for (size_t i = a; i < b; ++i)
      for (size_t j = i + 1; j < b; ++j) {
        const Spec& first = items[keyed[i].second];
        const Spec& second = items[keyed[j].second];
        if (keyed[j].second >= first_new && first.id == second.id)
          throw InputError(second.loc, "<" + std::string(element_name(second)) + " id=\"" + second.id +
                                           "\">: duplicate id, first used at " + first.loc.str());
      }
    a = b;
  }
}

// Fewer bytes than a vehicle with its route usually takes in a route file (Bologna's: 200).
constexpr uintmax_t kMinBytesPerVehicle = 128;

// A vehicle's or vType's parameter asking for SUMO's rerouting device.
constexpr std::string_view kReroutingParam = "has.rerouting.device";

constexpr std::string_view kUnsupportedDeparts[] = {"triggered", "containerTriggered", "begin", "split"};

class RouteFileReader {
 public:
  RouteFileReader(const std::string& path, DemandSpec& demand, AdditionalSpec& additional,
                  bool sorted_by_depart)
      : xs_(path),
        demand_(demand),
        additional_(additional),
        folder_(std::filesystem::path(path).parent_path()),
        first_new_vehicle_(demand.vehicles.size()),
        first_new_flow_(demand.flows.size()),
        edge_ids_(demand.edge_names),
        sorted_by_depart_(sorted_by_depart) {
    // Room for the vehicles a file of this size may hold, so the 380-byte specs are not moved (and their
    // pages touched twice) while the vector grows. Untouched capacity costs no memory.
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    if (!ec) demand.vehicles.reserve(demand.vehicles.size() + bytes / kMinBytesPerVehicle);
    for (const auto& t : demand.vtypes) type_ids_.insert(t.id);
    for (const auto& d : demand.vtype_dists) type_ids_.insert(d.id);
    for (const auto& r : demand.routes) route_ids_.insert(r.id);
    for (const auto& d : demand.route_dists) route_ids_.insert(d.id);
  }

  void read() {
    if (xs_.next() != XmlStream::Event::Start) throw InputError(xs_.loc(), "no root element");
    const std::string root = xs_.name();
    // SUMO ignores the root's name; refusing others catches a net or output file given by mistake.
    if (root != "routes" && root != "additional" && root != "add" && root != "tlLogics")
      throw InputError(xs_.loc(), "root element <" + root + "> is not <routes>, <additional> or <tlLogics>");
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof) break;
      if (ev == XmlStream::Event::Start) read_element();
    }
    check_unique_ids(demand_.vehicles, first_new_vehicle_);
    check_unique_ids(demand_.flows, first_new_flow_);
  }

 private:
  [[noreturn]] static void fail(const SourceLoc& loc, std::string_view element, std::string_view id,
                                const std::string& message) {
    throw InputError(loc, "<" + std::string(element) + " id=\"" + std::string(id) + "\">: " + message);
  }

  // At the Start event of a child of the root (or of an <interval>); leaves the stream at its End event.
  void read_element() {
    const std::string& name = xs_.name();
    if (name == "vehicle")
      read_vehicle(DemandSource::Vehicle);
    else if (name == "trip")
      read_vehicle(DemandSource::Trip);
    else if (name == "flow")
      read_flow();
    else if (name == "route")
      read_route();
    else if (name == "vType")
      read_vtype_element();
    else if (name == "routeDistribution")
      read_route_distribution("");
    else if (name == "vTypeDistribution")
      read_vtype_distribution();
    else if (name == "tlLogic")
      additional_.tl_logics.push_back(read_tl_logic(xs_));
    else if (name == "edgeData")
      read_mean_data(false);
    else if (name == "laneData")
      read_mean_data(true);
    else if (name == "interval")
      read_interval();
    else if (name == "busStop" || name == "trainStop" || name == "containerStop" || name == "chargingStation")
      read_stopping_place();
    else
      skip_counted();
  }

  // Counts the current element as unsupported and passes over it and its children.
  void skip_counted() {
    ++demand_.skipped[xs_.name()];
    skip_subtree();
  }

  void skip_subtree() {
    const int depth = xs_.depth();
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof) xs_.fail("unexpected end of file");
      if (ev == XmlStream::Event::End && xs_.depth() == depth) return;
    }
  }

  // Visits the children of the current element (depth + 1 only); `child` reads or skips each one.
  template <class Child>
  void for_each_child(const SourceLoc& loc, std::string_view element, std::string_view id, Child&& child) {
    const int depth = xs_.depth();
    for (;;) {
      auto ev = xs_.next();
      if (ev == XmlStream::Event::Eof) fail(loc, element, id, "unexpected end of file inside the element");
      if (ev == XmlStream::Event::End && xs_.depth() == depth) return;
      if (ev == XmlStream::Event::Start) child();
    }
  }

  void register_type_id(const SourceLoc& loc, std::string_view element, const std::string& id) {
    if (!type_ids_.insert(id).second)
      fail(loc, element, id, "duplicate id: another vType or vTypeDistribution has it");
  }
  void register_route_id(const SourceLoc& loc, std::string_view element, const std::string& id) {
    if (!route_ids_.insert(id).second)
      fail(loc, element, id, "duplicate id: another route or routeDistribution has it");
  }

  double time_attr(Key key, const SourceLoc& loc, std::string_view element, std::string_view id,
                   double fallback) const {
    const std::string* v = attrs_.get(key);
    if (!v) return fallback;
    const TimeValue t = parse_time_value(kKeyNames[key], *v);
    if (!t.problem.empty()) fail(loc, element, id, t.problem);
    return t.seconds;
  }

  // A time attribute of the current element (by name), or nullopt when absent; InputError when not a time.
  std::optional<double> named_time_attr(const char* key, const SourceLoc& loc, std::string_view element,
                                        std::string_view id) const {
    auto text = xs_.attr(key);
    if (!text) return std::nullopt;
    const TimeValue t = parse_time_value(key, *text);
    if (!t.problem.empty()) fail(loc, element, id, t.problem);
    return t.seconds;
  }

  double positive_attr(Key key, const SourceLoc& loc, std::string_view element, std::string_view id) const {
    const std::string& v = attrs_.value[key];
    auto d = parse_double(v);
    if (!d || *d <= 0)
      fail(loc, element, id,
           "attribute '" + std::string(kKeyNames[key]) + "' must be a positive number: '" + v + "'");
    return *d;
  }

  // type, route, from/to (edges or junctions) and via: the same attributes on a vehicle, trip or flow.
  template <class Spec>
  void read_type_and_path(Spec& spec) const {
    if (attrs_.present[kType]) spec.type = attrs_.value[kType];
    if (attrs_.present[kRoute]) spec.route = attrs_.id_value(kRoute);
    spec.from = attrs_.id_value(kFrom);
    spec.to = attrs_.id_value(kTo);
    spec.from_junction = attrs_.id_value(kFromJunction);
    spec.to_junction = attrs_.id_value(kToJunction);
    if (attrs_.present[kVia]) spec.via = split_ids(attrs_.value[kVia]);
  }

  void read_depart_spec(const SourceLoc& loc, std::string_view element, std::string_view id,
                        DepartSpec& d) const {
    if (auto* v = attrs_.get(kDepartLane); v && !parse_depart_lane(*v, d))
      fail(loc, element, id,
           "unknown departLane '" + *v + "' (first, random, free, allowed, best or a lane index)");
    if (auto* v = attrs_.get(kDepartPos); v && !parse_depart_pos(*v, d))
      fail(loc, element, id,
           "unknown departPos '" + *v + "' (base, random, free, random_free, last, stop or a position)");
    if (auto* v = attrs_.get(kDepartSpeed); v && !parse_depart_speed(*v, d))
      fail(loc, element, id,
           "unknown departSpeed '" + *v +
               "' (random, max, desired, speedLimit, last, avg or a non-negative speed)");
    if (auto* v = attrs_.get(kArrivalPos); v && !parse_arrival_pos(*v, d))
      fail(loc, element, id, "unknown arrivalPos '" + *v + "' (max, random or a position)");
  }

  // Trips and flows between traffic assignment zones need TAZ definitions LPSim does not load.
  bool skip_if_taz(std::string_view element) {
    if (!attrs_.present[kFromTaz] && !attrs_.present[kToTaz]) return false;
    ++demand_.skipped[std::string(element) + " (fromTaz/toTaz)"];
    skip_subtree();
    return true;
  }

  // Reads the children of a vehicle, trip or flow: a nested <route> or <routeDistribution> gives the path,
  // <stop>s (its own or its nested route's) go to `stops`; anything else (params, ...) is counted as
  // unsupported. With `interned` (vehicles and trips, read
  // by the million) a nested route's edges are interned into it instead of filling `edges`.
  void read_path_children(const SourceLoc& loc, std::string_view element, const std::string& id,
                          std::string& route, std::vector<std::string>& edges, std::vector<StopSpec>& stops,
                          int8_t& rerouting_param, VehicleSpec* interned = nullptr) {
    for_each_child(loc, element, id, [&] {
      const bool has_path = !route.empty() || !edges.empty() || (interned && interned->edge_ref_count > 0);
      if (xs_.name() == "route") {
        if (has_path)
          fail(xs_.loc(), element, id, "more than one route (attribute 'route' or nested routes)");
        bool given = false;
        size_t count = 0;
        xs_.for_each_attr([&](std::string_view key, std::string_view value) {
          if (key != "edges") return;
          given = true;
          if (!interned) {
            edges = split_ids(value);
            count = edges.size();
            return;
          }
          interned->edge_ref_begin = demand_.edge_refs.size();
          count = edge_ids_.intern_list(value, demand_.edge_refs);
          if (count > UINT32_MAX)
            fail(xs_.loc(), element, id, "nested <route> with more than 2^32 - 1 edges");
          interned->edge_ref_count = static_cast<uint32_t>(count);
        });
        if (!given) fail(xs_.loc(), element, id, "nested <route> without 'edges'");
        if (count == 0) fail(xs_.loc(), element, id, "nested <route> with empty 'edges'");
        read_route_children(stops);
      } else if (xs_.name() == "routeDistribution") {
        if (has_path)
          fail(xs_.loc(), element, id, "more than one route (attribute 'route' or nested routes)");
        route = read_route_distribution("!" + id);
      } else if (xs_.name() == "stop") {
        read_stop(stops);
      } else if (xs_.name() == "param" && xs_.get("key", "") == kReroutingParam) {
        // Equips it with the rerouting device, or keeps it from one (demand_builder), whatever the options.
        rerouting_param = parse_sumo_bool(trim(xs_.get("value", ""))).value_or(false) ? 1 : 0;
        skip_subtree();
      } else {
        skip_counted();
      }
    });
  }

  // Reads a route's <stop> children into `stops`, counts the others as unsupported, and leaves the stream
  // at the route's End.
  void read_route_children(std::vector<StopSpec>& stops) {
    const std::string element = xs_.name();
    for_each_child(xs_.loc(), element, xs_.get("id", ""), [&] {
      if (xs_.name() == "stop")
        read_stop(stops);
      else
        skip_counted();
    });
  }

  // Counts the children of the current element as unsupported and leaves it at its End.
  void skip_children_counted() {
    const std::string element = xs_.name();
    for_each_child(xs_.loc(), element, xs_.get("id", ""), [&] { skip_counted(); });
  }

  // A boolean attribute of the current element (SUMO's spellings), false when absent; InputError otherwise.
  bool bool_attr(const char* key, std::string_view element, std::string_view id) const {
    auto text = xs_.attr(key);
    if (!text) return false;
    auto b = parse_sumo_bool(trim(*text));
    if (!b)
      fail(xs_.loc(), element, id, std::string("attribute '") + key + "' is not a boolean: '" + *text + "'");
    return *b;
  }

  // A number attribute of the current element, or `fallback` when absent; InputError when not a number.
  double number_attr(const char* key, std::string_view element, double fallback) const {
    auto text = xs_.attr(key);
    if (!text) return fallback;
    auto d = parse_double(*text);
    if (!d)
      fail(xs_.loc(), element, xs_.get("id", ""),
           std::string("attribute '") + key + "' is not a number: '" + *text + "'");
    return *d;
  }

  // A <stop>: kept in `stops` when LPSim makes it (on the road, for a duration or until a time); counted
  // as unsupported, with why, when it is one LPSim does not model (parking off the road, waiting for
  // persons or containers, a waypoint passed at speed, a parking area).
  void read_stop(std::vector<StopSpec>& stops) {
    const std::string_view element = "stop";
    StopSpec st;
    st.loc = xs_.loc();
    auto skip_as = [&](const std::string& why) {
      ++demand_.skipped["stop (" + why + ")"];
      skip_subtree();
    };
    if (xs_.has("parkingArea")) return skip_as("parkingArea");
    for (const char* key : {"busStop", "trainStop", "containerStop", "chargingStation"})
      if (auto v = xs_.attr(key)) st.stopping_place = std::string(trim(*v));
    if (auto v = xs_.attr("lane")) st.lane = std::string(trim(*v));
    if (auto v = xs_.attr("edge")) st.edge = std::string(trim(*v));
    if (st.stopping_place.empty() && st.lane.empty() && st.edge.empty())
      fail(st.loc, element, "", "needs a lane, an edge or a stopping place (busStop, trainStop, ...)");
    if (auto v = xs_.attr("parking"); v && trim(*v) != "false" && trim(*v) != "0") {
      auto b = parse_sumo_bool(*v);
      if (!b || *b) return skip_as("parking");
    }
    for (const char* key : {"triggered", "containerTriggered"})
      if (auto v = xs_.attr(key); v && trim(*v) != "false" && trim(*v) != "0") return skip_as("triggered");
    if (number_attr("speed", element, 0) > 0) return skip_as("waypoint");
    if (xs_.has("startPos")) st.start_pos = number_attr("startPos", element, 0);
    if (xs_.has("endPos")) st.end_pos = number_attr("endPos", element, 0);
    st.friendly_pos = bool_attr("friendlyPos", element, "");
    st.duration = named_time_attr("duration", st.loc, element, "").value_or(-1);
    st.until = named_time_attr("until", st.loc, element, "").value_or(-1);
    // SUMO waits for a person or container there, which never comes in a scenario without them.
    if (st.duration < 0 && st.until < 0) return skip_as("neither duration nor until");
    stops.push_back(std::move(st));
    skip_children_counted();
  }

  // <busStop>, <trainStop>, <containerStop>, <chargingStation>: where stops that name them are made.
  void read_stopping_place() {
    const std::string element = xs_.name();
    StoppingPlaceSpec p;
    p.loc = xs_.loc();
    p.id = xs_.get("id", "");
    if (p.id.empty()) fail(p.loc, element, "", "missing or empty attribute 'id'");
    auto lane = xs_.attr("lane");
    if (!lane || trim(*lane).empty()) fail(p.loc, element, p.id, "missing attribute 'lane'");
    p.lane = std::string(trim(*lane));
    p.start_pos = number_attr("startPos", element, 0);
    if (xs_.has("endPos")) p.end_pos = number_attr("endPos", element, 0);
    p.friendly_pos = bool_attr("friendlyPos", element, p.id);
    for (const auto& other : demand_.stopping_places)
      if (other.id == p.id) fail(p.loc, element, p.id, "duplicate id, first used at " + other.loc.str());
    demand_.stopping_places.push_back(std::move(p));
    skip_children_counted();
  }

  // SUMO's SUMORouteHandler::checkLastDepart: in a route file read ahead by departure time, a vehicle,
  // trip or flow departing before the last one registered is ignored with a warning.
  bool ignored_as_unsorted(double depart, const std::string& id, const SourceLoc& loc) {
    if (!sorted_by_depart_ || depart >= last_depart_) return false;
    if (demand_.unsorted_ignored++ == 0) {
      demand_.first_unsorted_ignored = id;
      demand_.first_unsorted_loc = loc;
    }
    return true;
  }
  // SUMO's registerLastDepart: public transport (a 'line') does not move the mark, so that lines may be
  // listed ahead of the traffic.
  void register_depart(double depart, bool line) {
    if (!line) last_depart_ = depart;
  }
  bool public_transport() const { return attrs_.present[kLine] && !attrs_.value[kLine].empty(); }

  static bool has_endpoints(const std::string& from, const std::string& from_junction, const std::string& to,
                            const std::string& to_junction) {
    return (!from.empty() || !from_junction.empty()) && (!to.empty() || !to_junction.empty());
  }

  void read_vehicle(DemandSource source) {
    const std::string_view element = source == DemandSource::Trip ? "trip" : "vehicle";
    VehicleSpec v;
    v.loc = xs_.loc();
    const SourceLoc& loc = v.loc;
    attrs_.read(xs_);
    if (!attrs_.present[kId] || attrs_.value[kId].empty())
      fail(loc, element, "", "missing or empty attribute 'id'");
    const std::string& id = attrs_.value[kId];
    const std::string* depart = attrs_.get(kDepart);
    if (!depart) fail(loc, element, id, "missing attribute 'depart'");
    for (auto word : kUnsupportedDeparts)
      if (trim(*depart) == word) {
        ++demand_.skipped[std::string(element) + " (depart=" + std::string(word) + ")"];
        skip_subtree();
        return;
      }
    if (skip_if_taz(element)) return;

    v.id = id;
    v.source = source;
    v.depart = time_attr(kDepart, loc, element, id, 0);
    if (ignored_as_unsorted(v.depart, id, loc)) return skip_subtree();
    const bool line = public_transport();
    read_type_and_path(v);
    read_depart_spec(loc, element, id, v.depart_spec);
    read_path_children(loc, element, v.id, v.route, v.edges, v.stops, v.rerouting_param, &v);

    const bool endpoints = has_endpoints(v.from, v.from_junction, v.to, v.to_junction);
    // SUMO starts a trip without 'from' at its first stop and ends one without 'to' at its last.
    if (source == DemandSource::Trip && !endpoints && v.stops.empty())
      fail(loc, element, v.id, "needs 'from' (or 'fromJunction') and 'to' (or 'toJunction'), or stops");
    if (source == DemandSource::Vehicle && v.route.empty() && v.edges.empty() && v.edge_ref_count == 0 &&
        !endpoints)
      fail(loc, element, v.id, "no route: give 'route', a nested <route>, or from/to");
    register_depart(v.depart, line);
    demand_.vehicles.push_back(std::move(v));
  }

  void read_flow() {
    const std::string_view element = "flow";
    FlowSpec f;
    f.loc = xs_.loc();
    const SourceLoc& loc = f.loc;
    attrs_.read(xs_);
    if (!attrs_.present[kId] || attrs_.value[kId].empty())
      fail(loc, element, "", "missing or empty attribute 'id'");
    if (skip_if_taz(element)) return;
    f.id = attrs_.value[kId];
    const std::string& id = f.id;
    f.begin = time_attr(kBegin, loc, element, id, interval_begin_.value_or(0));
    f.end = time_attr(kEnd, loc, element, id, interval_end_.value_or(-1));
    if (f.end >= 0 && f.end < f.begin)
      fail(loc, element, id, "end " + attrs_.value[kEnd] + " lies before begin " + std::to_string(f.begin));
    // SUMO closes a flow of no vehicles before it looks at the order.
    const bool empty = attrs_.present[kNumber] && trim(attrs_.value[kNumber]) == "0";
    if (!empty && ignored_as_unsorted(f.begin, id, loc)) return skip_subtree();
    const bool line = public_transport();

    int rates = 0;
    if (attrs_.present[kPeriod]) {
      f.period = time_attr(kPeriod, loc, element, id, -1);
      if (f.period <= 0)
        fail(loc, element, id, "attribute 'period' must be positive: '" + attrs_.value[kPeriod] + "'");
      ++rates;
    }
    for (Key k : {kVehsPerHour, kPerHour})
      if (attrs_.present[k]) {
        f.vehs_per_hour = positive_attr(k, loc, element, id);
        // Its period, 3600 / rate, is a time the engine must hold like any other.
        if (!time_in_range(3600.0 / f.vehs_per_hour))
          fail(loc, element, id,
               "attribute '" + std::string(kKeyNames[k]) + "' is so small that its period (3600 s / " +
                   "rate) lies beyond the largest time LPSim represents: '" + attrs_.value[k] + "'");
        ++rates;
      }
    if (attrs_.present[kProbability]) {
      auto p = parse_double(attrs_.value[kProbability]);
      if (!p || *p <= 0 || *p > 1)
        fail(loc, element, id,
             "attribute 'probability' must lie in (0, 1]: '" + attrs_.value[kProbability] + "'");
      f.probability = *p;
      ++rates;
    }
    if (attrs_.present[kNumber]) {
      auto n = parse_integer(attrs_.value[kNumber]);
      if (!n || *n < 0)
        fail(loc, element, id,
             "attribute 'number' must be a non-negative integer: '" + attrs_.value[kNumber] + "'");
      f.number = *n;
    }
    if (rates > 1)
      fail(loc, element, id, "give only one of 'period', 'vehsPerHour' (or 'perHour'), 'probability'");
    if (rates == 0 && f.number < 0)
      fail(loc, element, id, "needs one of 'period', 'vehsPerHour', 'perHour', 'probability' or 'number'");

    read_type_and_path(f);
    read_depart_spec(loc, element, id, f.depart_spec);
    read_path_children(loc, element, f.id, f.route, f.edges, f.stops, f.rerouting_param);
    if (f.route.empty() && f.edges.empty() && !has_endpoints(f.from, f.from_junction, f.to, f.to_junction))
      fail(loc, element, f.id,
           "no route: give 'route', a nested <route>, from/to or fromJunction/toJunction");
    if (!empty) register_depart(f.begin, line);
    demand_.flows.push_back(std::move(f));
  }

  void read_route() {
    const SourceLoc loc = xs_.loc();
    RouteSpec r;
    r.loc = loc;
    r.id = xs_.get("id", "");
    if (r.id.empty()) fail(loc, "route", "", "missing or empty attribute 'id'");
    auto edges = xs_.attr("edges");
    if (!edges) fail(loc, "route", r.id, "missing attribute 'edges'");
    r.edges = split_ids(*edges);
    if (r.edges.empty()) fail(loc, "route", r.id, "empty 'edges'");
    register_route_id(loc, "route", r.id);
    read_route_children(r.stops);
    demand_.routes.push_back(std::move(r));
  }

  // Members given as `ids="a b"` with optional `probabilities="0.3 0.7"` (default 1 each).
  static std::vector<WeightedId> listed_members(const XmlStream& xs, const char* ids_key,
                                                std::string_view element, const std::string& id) {
    std::vector<WeightedId> members;
    auto ids = xs.attr(ids_key);
    if (!ids) return members;
    for (auto& member : split_ids(*ids)) members.push_back(WeightedId{std::move(member), 1.0});
    if (auto probs = xs.attr("probabilities")) {
      auto values = split_ids(*probs);
      if (values.size() != members.size())
        fail(xs.loc(), element, id,
             "'probabilities' has " + std::to_string(values.size()) + " values for " +
                 std::to_string(members.size()) + " members: '" + *probs + "'");
      for (size_t i = 0; i < values.size(); ++i) {
        auto p = parse_double(values[i]);
        if (!p || *p < 0)
          fail(xs.loc(), element, id, "bad probability '" + values[i] + "' in 'probabilities'");
        members[i].probability = *p;
      }
    }
    return members;
  }

  double probability_attr(std::string_view element, const std::string& id) const {
    auto text = xs_.attr("probability");
    if (!text) return 1.0;
    auto p = parse_double(*text);
    if (!p || *p < 0)
      fail(xs_.loc(), element, id, "attribute 'probability' must be non-negative: '" + *text + "'");
    return *p;
  }

  // `fallback_id` names a distribution nested in a vehicle or flow ("!<vehicle id>", as SUMO does);
  // empty at the top level, where the id is required. Returns the distribution's id.
  std::string read_route_distribution(const std::string& fallback_id) {
    const std::string_view element = "routeDistribution";
    RouteDistSpec dist;
    dist.loc = xs_.loc();
    dist.id = xs_.get("id", fallback_id);
    if (dist.id.empty()) fail(dist.loc, element, "", "missing or empty attribute 'id'");
    register_route_id(dist.loc, element, dist.id);
    dist.members = listed_members(xs_, "routes", element, dist.id);
    int nested = 0;
    for_each_child(dist.loc, element, dist.id, [&] {
      if (xs_.name() != "route") return skip_counted();
      const SourceLoc loc = xs_.loc();
      const double probability = probability_attr("route", xs_.get("id", ""));
      auto edges = xs_.attr("edges");
      if (!edges) {
        // A member that refers to a route defined elsewhere.
        auto ref = xs_.attr("refId");
        if (!ref)
          fail(loc, "route", xs_.get("id", ""),
               "route in routeDistribution '" + dist.id + "' has neither 'edges' nor 'refId'");
        dist.members.push_back(WeightedId{std::string(trim(*ref)), probability});
        skip_children_counted();
        return;
      }
      RouteSpec r;
      r.loc = loc;
      r.id = xs_.get("id", dist.id + "#" + std::to_string(nested));
      ++nested;
      r.edges = split_ids(*edges);
      if (r.edges.empty()) fail(loc, "route", r.id, "empty 'edges'");
      register_route_id(loc, "route", r.id);
      dist.members.push_back(WeightedId{r.id, probability});
      read_route_children(r.stops);
      demand_.routes.push_back(std::move(r));
    });
    if (dist.members.empty()) fail(dist.loc, element, dist.id, "no routes");
    std::string id = dist.id;
    demand_.route_dists.push_back(std::move(dist));
    return id;
  }

  void read_vtype_element() {
    double unused_probability = 1.0;
    VTypeSpec t = read_vtype(xs_, demand_.skipped, unused_probability);
    register_type_id(t.loc, "vType", t.id);
    demand_.vtypes.push_back(std::move(t));
  }

  void read_vtype_distribution() {
    const std::string_view element = "vTypeDistribution";
    VTypeDistSpec dist;
    dist.loc = xs_.loc();
    dist.id = xs_.get("id", "");
    if (dist.id.empty()) fail(dist.loc, element, "", "missing or empty attribute 'id'");
    register_type_id(dist.loc, element, dist.id);
    dist.members = listed_members(xs_, "vTypes", element, dist.id);
    for_each_child(dist.loc, element, dist.id, [&] {
      if (xs_.name() != "vType") return skip_counted();
      double probability = 1.0;
      VTypeSpec t = read_vtype(xs_, demand_.skipped, probability);
      register_type_id(t.loc, "vType", t.id);
      dist.members.push_back(WeightedId{t.id, probability});
      demand_.vtypes.push_back(std::move(t));
    });
    if (dist.members.empty()) fail(dist.loc, element, dist.id, "no vTypes");
    demand_.vtype_dists.push_back(std::move(dist));
  }

  // SUMO's meandata types: traffic measures ("", "traffic", "performance") and exhaust emissions
  // ("emissions", and "hbefa", the name SUMO 1.15 still takes for it with a warning) are written; SUMO's
  // noise and amitran types are not; anything else SUMO refuses as well.
  static MeanDataType mean_data_type(const SourceLoc& loc, std::string_view element, const std::string& id,
                                     const std::string& value) {
    const std::string_view type = trim(value);
    if (type.empty() || type == "traffic" || type == "performance") return MeanDataType::Traffic;
    if (type == "emissions" || type == "hbefa") return MeanDataType::Emissions;
    if (type == "harmonoise" || type == "amitran")
      fail(loc, element, id,
           "type '" + value +
               "' is not supported: LPSim writes traffic measures (no type, or 'traffic') and emissions "
               "('emissions'), not SUMO's noise (harmonoise) or amitran measures");
    fail(loc, element, id,
         "unknown type '" + value +
             "' (traffic, performance, emissions; hbefa, harmonoise and amitran are SUMO's, of which "
             "harmonoise and amitran are not supported)");
  }

  void read_mean_data(bool lane_level) {
    const std::string_view element = lane_level ? "laneData" : "edgeData";
    MeanDataSpec m;
    m.loc = xs_.loc();
    m.lane_level = lane_level;
    m.id = xs_.get("id", "");
    if (m.id.empty()) fail(m.loc, element, "", "missing or empty attribute 'id'");
    if (auto type = xs_.attr("type")) {
      m.type = mean_data_type(m.loc, element, m.id, *type);
      m.hbefa_name = trim(*type) == "hbefa";
    }
    auto file = xs_.attr("file");
    if (!file || trim(*file).empty()) fail(m.loc, element, m.id, "missing attribute 'file'");
    std::filesystem::path out(std::string(trim(*file)));
    m.file = out.is_absolute() || folder_.empty() ? out.string() : (folder_ / out).string();
    auto time = [&](const char* key) { return named_time_attr(key, m.loc, element, m.id).value_or(-1); };
    m.period = time(xs_.has("period") ? "period" : "freq");
    if (m.period == 0) fail(m.loc, element, m.id, "period must be positive");
    m.begin = time("begin");
    m.end = time("end");
    if (m.begin >= 0 && m.end >= 0 && m.end < m.begin) fail(m.loc, element, m.id, "end lies before begin");
    auto flag = [&](const char* key) {
      auto text = xs_.attr(key);
      if (!text) return false;
      // excludeEmpty="defaults" writes empty edges with default values: they are not excluded.
      if (std::string_view(key) == "excludeEmpty" && trim(*text) == "defaults") {
        m.empty_defaults = m.type == MeanDataType::Emissions;
        return false;
      }
      auto b = parse_sumo_bool(*text);
      if (!b)
        fail(m.loc, element, m.id, std::string("attribute '") + key + "' is not a boolean: '" + *text + "'");
      return *b;
    };
    m.exclude_empty = flag("excludeEmpty");
    m.with_internal = flag("withInternal");
    additional_.mean_data.push_back(std::move(m));
    skip_children_counted();
  }

  // <interval begin end> wraps flows (and other demand) and gives them its begin and end as defaults.
  void read_interval() {
    const SourceLoc loc = xs_.loc();
    const std::string id = xs_.get("id", "");
    auto bound = [&](const char* key) { return named_time_attr(key, loc, "interval", id); };
    auto saved_begin = interval_begin_, saved_end = interval_end_;
    interval_begin_ = bound("begin");
    interval_end_ = bound("end");
    for_each_child(loc, "interval", "", [&] { read_element(); });
    interval_begin_ = saved_begin;
    interval_end_ = saved_end;
  }

  XmlStream xs_;
  DemandSpec& demand_;
  AdditionalSpec& additional_;
  std::filesystem::path folder_;
  size_t first_new_vehicle_, first_new_flow_;
  EdgeIdInterner edge_ids_;
  std::unordered_set<std::string> type_ids_, route_ids_;
  std::optional<double> interval_begin_, interval_end_;
  TravellerAttrs attrs_;
  const bool sorted_by_depart_;
  double last_depart_ = -1;  // s: the departure of the last vehicle or flow registered (SUMO's myLastDepart)
};

}  // namespace

void read_sumo_routes(const std::string& path, DemandSpec& demand, AdditionalSpec& additional,
                      bool sorted_by_depart) {
  RouteFileReader(path, demand, additional, sorted_by_depart).read();
}

}  // namespace lpsim

#include "net/network_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "kernels/lane_map.hpp"
#include "net/actuated_detectors.hpp"
#include "net/junction_foes.hpp"
#include "net/junction_type.hpp"

namespace lpsim {
namespace {

// Builds the Network in passes over the spec: junctions, edges and lanes, lane map layout, signals,
// connections (CSR), edge successors, roundabouts. Every pass is linear (hash lookups, counting sort), so
// 100k-edge / 1M-lane nets build in well under a second per pass.
class Builder {
 public:
  Builder(const NetSpec& spec, const std::vector<TlLogicSpec>& overrides, const NetworkLimits& limits)
      : spec_(spec), overrides_(overrides), limits_(limits) {}

  Network build() {
    add_junctions();
    add_edges_and_lanes();
    lay_out_lanes();
    add_signals();
    add_connections();
    add_edge_successors();
    add_roundabouts();
    build_junction_foes(spec_, net_);
    place_actuated_detectors(net_);
    net_.skipped_non_car_lanes = spec_.skipped_non_car_lanes;
    net_.net_offset = spec_.net_offset;
    return std::move(net_);
  }

  // A rail crossing or rail signal junction of that id (its tl attribute needs no program for cars).
  bool is_rail_controlled(const std::string& id) const {
    for (const auto& j : spec_.junctions)
      if (j.id == id) return j.type == "rail_crossing" || j.type == "rail_signal";
    return false;
  }

 private:
  const NetSpec& spec_;
  const std::vector<TlLogicSpec>& overrides_;
  const NetworkLimits& limits_;
  Network net_;

  std::vector<uint32_t>
      spec_lane_offset_;  // per spec edge: first slot in spec_lane_car_ (and the total last)
  std::vector<uint8_t> spec_lanes_by_position_;       // per spec edge: 1 when lane k has index k for every k
  std::vector<int32_t> spec_lane_car_;                // per spec lane: its lane index or kNone if dropped
  std::vector<uint32_t> edge_spec_;                   // per network edge: index of its EdgeSpec
  std::vector<const LaneSpec*> lane_spec_;            // per car lane: its LaneSpec
  std::vector<int32_t> internal_junction_;            // per network edge: junction an internal edge lies in
  std::unordered_set<std::string> pedestrian_edges_;  // crossings and walking areas, dropped entirely
  std::unordered_set<std::string> non_car_lanes_;     // lane ids dropped (pedestrian only; for via checks)

  void add_junctions() {
    const auto n = spec_.junctions.size();
    net_.junction_id.reserve(n);
    net_.junction_type.reserve(n);
    net_.junction_x.reserve(n);
    net_.junction_y.reserve(n);
    net_.junction_index.reserve(n);
    for (const auto& j : spec_.junctions) {
      const auto idx = static_cast<uint32_t>(net_.junction_id.size());
      if (!net_.junction_index.emplace(j.id, idx).second)
        throw InputError(j.loc, "duplicate junction id '" + j.id + "'");
      net_.junction_id.push_back(j.id);
      net_.junction_type.push_back(parse_junction_type(j.type, j.loc, j.id));
      net_.junction_x.push_back(static_cast<float>(j.x));
      net_.junction_y.push_back(static_cast<float>(j.y));
    }
  }

  int32_t junction_of(const EdgeSpec& e, const std::string& id, const char* role) {
    // Edges are mostly listed by their from-junction: reuse the previous lookup of the same from-id.
    const bool from = role[0] == 'f';
    if (from && last_junction_ != kNone && id == last_junction_id_) return last_junction_;
    auto it = net_.junction_index.find(id);
    if (it != net_.junction_index.end()) {
      if (from) {
        last_junction_id_ = id;
        last_junction_ = static_cast<int32_t>(it->second);
      }
      return static_cast<int32_t>(it->second);
    }
    // Connector edges may end in districts that are not junctions; a normal edge must have both ends.
    if (e.function == EdgeFunction::Connector) return kNone;
    throw InputError(e.loc, "edge '" + e.id + "' names unknown " + role + " junction '" + id + "'");
  }

  // ":<junction>_<n>" -> junction index; falls back to the junctions' intLanes lists.
  int32_t junction_of_internal(const EdgeSpec& e) {
    auto us = e.id.rfind('_');
    if (!e.id.empty() && e.id[0] == ':' && us != std::string::npos && us > 1) {
      // A junction's internal edges come one after another: reuse the previous edge's lookup.
      const std::string_view name(e.id.data() + 1, us - 1);
      if (last_internal_junction_ != kNone && name == last_internal_name_) return last_internal_junction_;
      auto it = net_.junction_index.find(std::string(name));
      if (it != net_.junction_index.end()) {
        last_internal_name_.assign(name);
        last_internal_junction_ = static_cast<int32_t>(it->second);
        return last_internal_junction_;
      }
    }
    if (!int_lane_junction_built_) {  // only nets with unusual internal ids pay for this map
      for (uint32_t j = 0; j < spec_.junctions.size(); ++j)
        for (const auto& l : spec_.junctions[j].int_lanes)
          int_lane_junction_.emplace(l, static_cast<int32_t>(j));
      int_lane_junction_built_ = true;
    }
    for (const auto& l : e.lanes) {
      auto it = int_lane_junction_.find(l.id);
      if (it != int_lane_junction_.end()) return it->second;
    }
    return kNone;
  }
  std::unordered_map<std::string, int32_t> int_lane_junction_;
  bool int_lane_junction_built_ = false;
  std::string last_junction_id_;  // id of the last from-junction found by junction_of
  int32_t last_junction_ = kNone;
  std::string last_internal_name_;  // junction id of the previous internal edge resolved by its name
  int32_t last_internal_junction_ = kNone;

  void add_edges_and_lanes() {
    const auto& edges = spec_.edges;
    size_t spec_lanes = 0;
    for (const auto& e : edges) spec_lanes += e.lanes.size();
    spec_lane_offset_.resize(edges.size() + 1);
    spec_lanes_by_position_.resize(edges.size());
    spec_lane_car_.assign(spec_lanes, kNone);
    net_.edge_index.reserve(edges.size());
    // Edge columns grow to at most one entry per spec edge: reserving avoids regrowing (and re-faulting)
    // multi-megabyte arrays on large nets.
    net_.edge_id.reserve(edges.size());
    net_.edge_is_internal.reserve(edges.size());
    net_.edge_from_junction.reserve(edges.size());
    net_.edge_to_junction.reserve(edges.size());
    internal_junction_.reserve(edges.size());
    net_.edge_priority.reserve(edges.size());
    edge_spec_.reserve(edges.size());
    net_.edge_first_lane.reserve(edges.size());
    net_.edge_num_lanes.reserve(edges.size());
    net_.edge_length.reserve(edges.size());
    net_.edge_speed.reserve(edges.size());
    net_.edge_permissions.reserve(edges.size());
    net_.lane_index_by_id.reserve(spec_lanes);
    net_.lane_id.reserve(spec_lanes);
    lane_spec_.reserve(spec_lanes);
    net_.lane_edge.reserve(spec_lanes);
    net_.lane_index.reserve(spec_lanes);
    net_.lane_length.reserve(spec_lanes);
    net_.lane_speed.reserve(spec_lanes);
    net_.lane_permissions.reserve(spec_lanes);

    std::unordered_map<std::string_view, const EdgeTypeSpec*> types;
    for (const EdgeTypeSpec& t : spec_.edge_types) types.emplace(t.id, &t);
    net_.lane_restriction_begin.reserve(spec_lanes + 1);
    net_.lane_restriction_begin.push_back(0);

    uint32_t offset = 0;
    std::vector<uint32_t> order;
    for (uint32_t se = 0; se < edges.size(); ++se) {
      const EdgeSpec& e = edges[se];
      spec_lane_offset_[se] = offset;
      offset += static_cast<uint32_t>(e.lanes.size());
      spec_lane_offset_[se + 1] = offset;
      bool by_position = true;
      for (uint32_t k = 0; k < e.lanes.size(); ++k)
        by_position = by_position && e.lanes[k].index == static_cast<int>(k);
      spec_lanes_by_position_[se] = by_position ? 1 : 0;
      if (e.function == EdgeFunction::Crossing || e.function == EdgeFunction::WalkingArea) {
        pedestrian_edges_.insert(e.id);
        for (const auto& l : e.lanes) non_car_lanes_.insert(l.id);
        continue;
      }
      const auto ei = static_cast<uint32_t>(net_.edge_id.size());
      if (!net_.edge_index.emplace(e.id, ei).second)
        throw InputError(e.loc, "duplicate edge id '" + e.id + "'");
      const bool internal = e.function == EdgeFunction::Internal;
      net_.edge_id.push_back(e.id);
      net_.edge_is_internal.push_back(internal ? 1 : 0);
      net_.edge_from_junction.push_back(internal ? kNone : junction_of(e, e.from, "from"));
      net_.edge_to_junction.push_back(internal ? kNone : junction_of(e, e.to, "to"));
      internal_junction_.push_back(internal ? junction_of_internal(e) : kNone);
      net_.edge_priority.push_back(e.priority);
      edge_spec_.push_back(se);

      order.clear();
      uint32_t other_lanes = 0;
      float other_speeds = 0;
      for (uint32_t k = 0; k < e.lanes.size(); ++k) {
        if (vehicle_lane(e.lanes[k].permissions)) {
          order.push_back(k);
          continue;
        }
        ++other_lanes;
        other_speeds += static_cast<float>(e.lanes[k].speed);
        if (non_car_lanes_.insert(e.lanes[k].id).second && !internal)
          net_.left_out_lane_edge.emplace(e.lanes[k].id, ei);
      }
      net_.edge_other_lanes.push_back(static_cast<uint8_t>(std::min<uint32_t>(other_lanes, 255)));
      net_.edge_other_lane_speeds.push_back(other_speeds);
      std::stable_sort(order.begin(), order.end(),
                       [&](uint32_t a, uint32_t b) { return e.lanes[a].index < e.lanes[b].index; });
      if (order.size() > std::numeric_limits<uint8_t>::max())
        throw InputError(e.loc,
                         "edge '" + e.id + "' has " + std::to_string(order.size()) + " lanes (max 255)");
      net_.edge_first_lane.push_back(static_cast<uint32_t>(net_.lane_id.size()));
      net_.edge_num_lanes.push_back(static_cast<uint8_t>(order.size()));
      float speed = 0;
      uint32_t edge_classes = 0;
      // Internal edges have no type: SUMO restricts the lanes of normal edges only.
      const auto type = internal || e.type.empty() ? types.end() : types.find(e.type);
      for (uint32_t k : order) {
        const LaneSpec& l = e.lanes[k];
        if (l.index < 0 || l.index > std::numeric_limits<uint8_t>::max())
          throw InputError(l.loc,
                           "lane '" + l.id + "' of edge '" + e.id + "' has index " + std::to_string(l.index));
        const auto li = static_cast<uint32_t>(net_.lane_id.size());
        if (!net_.lane_index_by_id.emplace(l.id, li).second)
          throw InputError(l.loc, "duplicate lane id '" + l.id + "' in edge '" + e.id + "'");
        spec_lane_car_[spec_lane_offset_[se] + k] = static_cast<int32_t>(li);
        net_.lane_id.push_back(l.id);
        lane_spec_.push_back(&l);
        net_.lane_edge.push_back(ei);
        net_.lane_index.push_back(static_cast<uint8_t>(l.index));
        net_.lane_length.push_back(static_cast<float>(l.length));
        net_.lane_speed.push_back(static_cast<float>(l.speed));
        net_.lane_permissions.push_back(l.permissions);
        if (type != types.end())
          for (const SpeedRestrictionSpec& r : type->second->restrictions) {
            net_.restriction_vclass.push_back(r.vclass);
            net_.restriction_speed.push_back(static_cast<float>(r.speed));
          }
        net_.lane_restriction_begin.push_back(static_cast<uint32_t>(net_.restriction_vclass.size()));
        edge_classes |= l.permissions;
        speed = std::max(speed, static_cast<float>(l.speed));
      }
      net_.edge_length.push_back(order.empty() ? 0.f : static_cast<float>(e.lanes[order.front()].length));
      net_.edge_speed.push_back(speed);
      net_.edge_permissions.push_back(edge_classes);
    }
  }

  // The backends hold the lane map twice (the buffer read and the one written each step), a byte per cell.
  void check_lane_map_budget(double cells, uint32_t longest) const {
    if (limits_.max_lane_map_gib <= 0) return;
    constexpr double kGib = 1024.0 * 1024.0 * 1024.0;
    const double gib = 2 * cells / kGib;
    if (gib <= limits_.max_lane_map_gib) return;
    char what[256];
    std::snprintf(
        what, sizeof what,
        "the lanes need %.2f GiB of lane map (%.0f cells, one per metre, in two buffers), more than "
        "%s %g allows; the longest lane, '",
        gib, cells, limits_.max_lane_map_option.c_str(), limits_.max_lane_map_gib);
    char lane_len[64];
    std::snprintf(lane_len, sizeof lane_len, "%.0f m", static_cast<double>(net_.lane_length[longest]));
    throw InputError(lane_spec_[longest]->loc, what + net_.lane_id[longest] + "', is " + lane_len);
  }

  // Cells: one per started metre, at least one per lane. Shapes: as given, else the edge's end junctions.
  void lay_out_lanes() {
    const uint32_t lanes = net_.num_lanes();
    net_.lane_cell_begin.resize(lanes + 1);
    net_.lane_shape_begin.resize(lanes + 1);
    // The engine addresses cells with 32-bit offsets (half the state per vehicle of 64-bit ones) and a lane's
    // cells with int32 (kMaxLaneCells leaves room for look-ahead sums). Checked in doubles, so that no absurd
    // length overflows an integer conversion.
    double total = 0;
    uint32_t longest = 0;
    for (uint32_t l = 0; l < lanes; ++l) {
      total += std::max(1.0, std::ceil(static_cast<double>(net_.lane_length[l])));
      if (net_.lane_length[l] > net_.lane_length[longest]) longest = l;
    }
    if (lanes > 0 && std::ceil(static_cast<double>(net_.lane_length[longest])) > kMaxLaneCells) {
      char len[64];
      std::snprintf(len, sizeof len, "%.0f m", static_cast<double>(net_.lane_length[longest]));
      throw InputError(lane_spec_[longest]->loc, "lane '" + net_.lane_id[longest] + "' is " + len +
                                                     " long, more than the " + std::to_string(kMaxLaneCells) +
                                                     " m (one lane-map cell per metre) LPSim allows a lane");
    }
    if (total >= 4294967296.0) {
      char what[160];
      std::snprintf(what, sizeof what, "the lanes need %.0f lane-map cells (one per metre)", total);
      char lane_len[64];
      std::snprintf(lane_len, sizeof lane_len, "%.0f m", static_cast<double>(net_.lane_length[longest]));
      throw InputError(lane_spec_[longest]->loc, std::string(what) +
                                                     ", more than the 4294967295 LPSim can address; the "
                                                     "longest lane, '" +
                                                     net_.lane_id[longest] + "', is " + lane_len);
    }
    check_lane_map_budget(total, longest);
    uint64_t cells = 0;
    for (uint32_t l = 0; l < lanes; ++l) {
      net_.lane_cell_begin[l] = cells;
      cells +=
          std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(static_cast<double>(net_.lane_length[l]))));
    }
    net_.lane_cell_begin[lanes] = cells;

    size_t points = 0;
    for (const LaneSpec* ls : lane_spec_) points += std::max<size_t>(2, ls->shape.size());
    net_.shape_x.reserve(points);
    net_.shape_y.reserve(points);
    for (uint32_t l = 0; l < lanes; ++l) {
      net_.lane_shape_begin[l] = static_cast<uint32_t>(net_.shape_x.size());
      const auto& shape = lane_spec_[l]->shape;
      if (!shape.empty()) {
        for (const auto& p : shape) push_point(p.x, p.y);
      } else {
        const uint32_t e = net_.lane_edge[l];
        int32_t a = net_.edge_from_junction[e], b = net_.edge_to_junction[e];
        if (net_.edge_is_internal[e]) a = b = internal_junction_[e];
        push_junction_point(a);
        push_junction_point(b);
      }
    }
    net_.lane_shape_begin[lanes] = static_cast<uint32_t>(net_.shape_x.size());
  }
  void push_point(double x, double y) {
    net_.shape_x.push_back(static_cast<float>(x));
    net_.shape_y.push_back(static_cast<float>(y));
  }
  void push_junction_point(int32_t j) {
    if (j == kNone)
      push_point(0, 0);
    else
      push_point(net_.junction_x[j], net_.junction_y[j]);
  }

  // One program per tlLogic id: the last one loaded wins, add-file programs after the net's.
  void add_signals() {
    std::unordered_map<std::string, const TlLogicSpec*> chosen;
    std::vector<std::string> order;
    auto take = [&](const TlLogicSpec& t) {
      auto [it, fresh] = chosen.try_emplace(t.id, &t);
      if (fresh)
        order.push_back(t.id);
      else
        it->second = &t;
    };
    for (const auto& t : spec_.tl_logics) take(t);
    for (const auto& t : overrides_) {
      // As SUMO: an add-file program replaces one of the network's, it cannot add a traffic light.
      if (!chosen.count(t.id))
        throw InputError(t.loc, "tlLogic '" + t.id + "' program '" + t.program_id +
                                    "' names no traffic light of the network " + spec_.source);
      take(t);
    }
    const std::unordered_map<std::string, size_t> links_used = links_used_by_connections();
    std::unordered_set<const TlLogicSpec*> from_add_file;
    for (const auto& t : overrides_) from_add_file.insert(&t);

    net_.signal_phase_begin.push_back(0);
    net_.phase_state_begin.push_back(0);
    for (const auto& id : order) {
      const TlLogicSpec& t = *chosen[id];
      if (t.phases.empty())
        throw InputError(t.loc, "tlLogic '" + t.id + "' program '" + t.program_id + "' has no phases");
      check_phase_sizes(t, links_used.count(t.id) ? links_used.at(t.id) : 0, from_add_file.count(&t) != 0);
      const size_t links = t.phases.front().state.size();
      if (links > static_cast<size_t>(std::numeric_limits<int16_t>::max()))
        throw InputError(t.loc,
                         "tlLogic '" + t.id + "' controls " + std::to_string(links) + " links (max 32767)");
      net_.signal_index.emplace(t.id, net_.num_signals());
      net_.signal_id.push_back(t.id);
      net_.signal_program.push_back(t.program_id);
      net_.signal_actuated.push_back(t.type == "actuated" ? 1 : 0);
      add_actuated_params(t);
      net_.signal_offset.push_back(static_cast<float>(t.offset));
      for (size_t p = 0; p < t.phases.size(); ++p) {
        const PhaseSpec& ph = t.phases[p];
        net_.phase_duration.push_back(static_cast<float>(ph.duration));
        net_.phase_min_dur.push_back(static_cast<float>(ph.min_dur));
        net_.phase_max_dur.push_back(static_cast<float>(ph.max_dur));
        net_.phase_state.insert(net_.phase_state.end(), ph.state.begin(), ph.state.end());
        net_.phase_state_begin.push_back(static_cast<uint32_t>(net_.phase_state.size()));
      }
      net_.signal_phase_begin.push_back(static_cast<uint32_t>(net_.phase_duration.size()));
    }
  }

  // SUMO 1.15's defaults for the parameters of an actuated program's gap control, unless it sets them.
  void add_actuated_params(const TlLogicSpec& t) {
    double max_gap = 3.0, detector_gap = 2.0, passing_time = 1.9;
    for (const auto& [key, value] : t.params) {
      double* target = key == "max-gap"        ? &max_gap
                       : key == "detector-gap" ? &detector_gap
                       : key == "passing-time" ? &passing_time
                                               : nullptr;
      if (target == nullptr) continue;  // named in a load warning (app/load_warnings)
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(v) || v < 0 || (target == &passing_time && v == 0))
        throw InputError(t.loc, "tlLogic '" + t.id + "' param '" + key + "': '" + value + "' is not a " +
                                    (target == &passing_time ? "positive" : "non-negative") +
                                    " number of seconds");
      *target = v;
    }
    net_.signal_max_gap.push_back(static_cast<float>(max_gap));
    net_.signal_detector_gap.push_back(static_cast<float>(detector_gap));
    net_.signal_passing_time.push_back(static_cast<float>(passing_time));
  }

  // Per traffic light id: the links its connections use (the highest linkIndex + 1).
  std::unordered_map<std::string, size_t> links_used_by_connections() const {
    std::unordered_map<std::string, size_t> used;
    for (const ConnectionSpec& c : spec_.connections)
      if (!c.tl.empty() && c.link_index >= 0) {
        size_t& n = used[c.tl];
        n = std::max(n, static_cast<size_t>(c.link_index) + 1);
      }
    return used;
  }

  // Every phase state has one signal per link: the size most phases have (on a tie the larger) is taken as
  // meant, and the first phase of another size is blamed on its own line. An add-file program must also
  // cover the links of the network's connections; were it short, the connection would be blamed instead, in
  // the network file the user did not change.
  static void check_phase_sizes(const TlLogicSpec& t, size_t links_used, bool from_add_file) {
    std::unordered_map<size_t, size_t> phases_of_size;
    size_t links = 0;
    for (const PhaseSpec& ph : t.phases) {
      const size_t n = ++phases_of_size[ph.state.size()];
      const size_t best = phases_of_size[links];
      if (n > best || (n == best && ph.state.size() > links)) links = ph.state.size();
    }
    const std::string program = "tlLogic '" + t.id + "' program '" + t.program_id + "' phase ";
    for (size_t p = 0; p < t.phases.size(); ++p) {
      const PhaseSpec& ph = t.phases[p];
      const std::string what = program + std::to_string(p) + ": state '" + ph.state + "' has " +
                               std::to_string(ph.state.size()) + " links";
      if (ph.state.size() != links)
        throw InputError(ph.loc, what + ", the program's other phases " + std::to_string(links));
      if (from_add_file && links < links_used)
        throw InputError(ph.loc, what + ", but the network's connections use " + std::to_string(links_used) +
                                     " (linkIndex up to " + std::to_string(links_used - 1) + ")");
    }
  }

  uint32_t signal_links(uint32_t s) const {
    const uint32_t p = net_.signal_phase_begin[s];
    return net_.phase_state_begin[p + 1] - net_.phase_state_begin[p];
  }

  // Car lane index of lane `index` of edge `ei`, kNone if that lane is not a car lane; InputError if the
  // edge has no lane with that index.
  int32_t car_lane(const ConnectionSpec& c, uint32_t ei, int index, const char* role) const {
    const uint32_t se = edge_spec_[ei];
    // Lanes listed in index order (as the net reader stores them): the index is the slot.
    const uint32_t first = spec_lane_offset_[se], count = spec_lane_offset_[se + 1] - first;
    if (spec_lanes_by_position_[se] && index >= 0 && static_cast<uint32_t>(index) < count)
      return spec_lane_car_[first + static_cast<uint32_t>(index)];
    const auto& lanes = spec_.edges[se].lanes;
    for (uint32_t k = 0; k < lanes.size(); ++k)
      if (lanes[k].index == index) return spec_lane_car_[spec_lane_offset_[se] + k];
    throw InputError(c.loc, "connection from '" + c.from + "' to '" + c.to + "' names " + role + " " +
                                std::to_string(index) + " but edge '" + net_.edge_id[ei] + "' has " +
                                std::to_string(lanes.size()) + " lanes");
  }

  // Consecutive connections mostly share their from-edge and signal: the last lookup of each is kept.
  struct LastLookup {
    std::string id;
    uint32_t index = 0;
    bool valid = false;
  };
  LastLookup last_from_, last_tl_;
  // A from-edge's lanes lead to the same few edges: the last kRecentTo to-edge lookups are kept.
  static constexpr size_t kRecentTo = 4;
  std::array<LastLookup, kRecentTo> recent_to_;
  size_t recent_to_next_ = 0;

  uint32_t to_edge_of(const ConnectionSpec& c) {
    for (const auto& r : recent_to_)
      if (r.valid && r.id == c.to) return r.index;
    LastLookup& slot = recent_to_[recent_to_next_];
    recent_to_next_ = (recent_to_next_ + 1) % kRecentTo;
    return cached_edge_of(c, c.to, "to", slot);
  }

  uint32_t cached_edge_of(const ConnectionSpec& c, const std::string& id, const char* role,
                          LastLookup& last) const {
    if (last.valid && last.id == id) return last.index;
    last.index = edge_of(c, id, role);
    last.id = id;
    last.valid = true;
    return last.index;
  }

  uint32_t edge_of(const ConnectionSpec& c, const std::string& id, const char* role) const {
    auto it = net_.edge_index.find(id);
    if (it == net_.edge_index.end())
      throw InputError(c.loc, "connection from '" + c.from + "' to '" + c.to + "' names unknown " + role +
                                  " edge '" + id + "'");
    return it->second;
  }

  struct Conn {
    uint32_t from_lane, to_lane, to_edge;
    int32_t via, signal, junction;
    int16_t link;
    char state, dir;
    bool keep_clear;
  };

  void add_connections() {
    std::vector<Conn> kept;
    kept.reserve(spec_.connections.size());
    for (const auto& c : spec_.connections) {
      if (!pedestrian_edges_.empty() && (pedestrian_edges_.count(c.from) || pedestrian_edges_.count(c.to))) {
        ++net_.skipped_connections;
        continue;
      }
      const uint32_t fe = cached_edge_of(c, c.from, "from", last_from_), te = to_edge_of(c);
      const int32_t fl = car_lane(c, fe, c.from_lane, "fromLane");
      const int32_t tl = car_lane(c, te, c.to_lane, "toLane");
      int32_t via = kNone;
      bool via_ok = true;
      if (!c.via.empty()) {
        auto it = net_.lane_index_by_id.find(c.via);
        if (it != net_.lane_index_by_id.end())
          via = static_cast<int32_t>(it->second);
        else if (!non_car_lanes_.empty() && non_car_lanes_.count(c.via))
          via_ok = false;
        else
          throw InputError(c.loc, "connection from '" + c.from + "' to '" + c.to +
                                      "' names unknown via lane '" + c.via + "'");
      }
      if (fl == kNone || tl == kNone || !via_ok) {
        ++net_.skipped_connections;
        continue;
      }
      Conn k{static_cast<uint32_t>(fl),
             static_cast<uint32_t>(tl),
             te,
             via,
             kNone,
             kNone,
             -1,
             c.state,
             c.dir,
             c.keep_clear};
      k.junction = net_.edge_is_internal[fe] ? internal_junction_[fe] : net_.edge_to_junction[fe];
      if (!c.tl.empty()) {
        if (!last_tl_.valid || last_tl_.id != c.tl) {
          auto it = net_.signal_index.find(c.tl);
          // Rail crossings name their junction as tl without a program: SUMO closes them for trains only,
          // and no trains run here, so road links there are open (unsignalised).
          if (it == net_.signal_index.end() && is_rail_controlled(c.tl)) {
            kept.push_back(k);
            continue;
          }
          if (it == net_.signal_index.end())
            throw InputError(c.loc, "connection from '" + c.from + "' to '" + c.to + "' names tlLogic '" +
                                        c.tl + "' which has no program");
          last_tl_ = {c.tl, it->second, true};
        }
        const uint32_t signal = last_tl_.index;
        const uint32_t links = signal_links(signal);
        if (c.link_index < 0 || static_cast<uint32_t>(c.link_index) >= links)
          throw InputError(c.loc, "connection from '" + c.from + "' to '" + c.to + "' has linkIndex " +
                                      std::to_string(c.link_index) + " but tlLogic '" + c.tl + "' controls " +
                                      std::to_string(links) + " links");
        k.signal = static_cast<int32_t>(signal);
        k.link = static_cast<int16_t>(c.link_index);
      }
      kept.push_back(k);
    }

    // Counting sort by from-lane keeps file order within a lane.
    const uint32_t lanes = net_.num_lanes();
    auto& begin = net_.lane_conn_begin;
    begin.assign(lanes + 1, 0);
    for (const auto& k : kept) ++begin[k.from_lane + 1];
    for (uint32_t l = 0; l < lanes; ++l) begin[l + 1] += begin[l];
    std::vector<uint32_t> slot(begin.begin(), begin.end() - 1);
    const size_t n = kept.size();
    net_.conn_from_lane.resize(n);
    net_.conn_to_lane.resize(n);
    net_.conn_via_lane.resize(n);
    net_.conn_to_edge.resize(n);
    net_.conn_signal.resize(n);
    net_.conn_link_index.resize(n);
    net_.conn_state.resize(n);
    net_.conn_dir.resize(n);
    net_.conn_junction.resize(n);
    net_.conn_keep_clear.resize(n);
    for (const auto& k : kept) {
      const uint32_t i = slot[k.from_lane]++;
      net_.conn_from_lane[i] = k.from_lane;
      net_.conn_to_lane[i] = k.to_lane;
      net_.conn_via_lane[i] = k.via;
      net_.conn_to_edge[i] = k.to_edge;
      net_.conn_signal[i] = k.signal;
      net_.conn_link_index[i] = k.link;
      net_.conn_state[i] = k.state;
      net_.conn_dir[i] = k.dir;
      net_.conn_junction[i] = k.junction;
      net_.conn_keep_clear[i] = k.keep_clear ? 1 : 0;
    }
  }

  // Normal edges reachable from each normal edge by one connection, following chains of internal lanes
  // when a connection leads onto an internal edge instead of naming the normal edge beyond it; with each,
  // the vClasses allowed along some such path (on its from-lane, via lanes and to-lane).
  void add_edge_successors() {
    const uint32_t edges = net_.num_edges();
    const auto& perm = net_.lane_permissions;
    net_.edge_succ_begin.assign(edges + 1, 0);
    std::vector<std::pair<uint32_t, uint32_t>> found, stack;  // (edge, classes), (lane, classes)
    std::vector<uint32_t> lane_mark(net_.num_lanes(), 0), lane_reach(net_.num_lanes(), 0);
    uint32_t mark = 0;
    for (uint32_t e = 0; e < edges; ++e) {
      net_.edge_succ_begin[e] = static_cast<uint32_t>(net_.edge_succ.size());
      if (net_.edge_is_internal[e]) continue;
      found.clear();
      ++mark;
      // Start from the edge's own lanes (normal lanes are never reached again: connections from internal
      // lanes that lead to a normal edge end the walk).
      const uint32_t l0 = net_.edge_first_lane[e], l1 = l0 + net_.edge_num_lanes[e];
      for (uint32_t l = l0; l < l1; ++l) stack.emplace_back(l, perm[l]);
      while (!stack.empty()) {
        const auto [l, classes] = stack.back();
        stack.pop_back();
        for (uint32_t c = net_.lane_conn_begin[l]; c < net_.lane_conn_begin[l + 1]; ++c) {
          const uint32_t t = net_.conn_to_edge[c], tl = net_.conn_to_lane[c];
          const int32_t via = net_.conn_via_lane[c];
          const uint32_t along = classes & perm[tl] & (via == kNone ? kAllVClasses : perm[via]);
          if (along == 0) continue;
          if (!net_.edge_is_internal[t]) {
            found.emplace_back(t, along);
          } else {
            if (lane_mark[tl] != mark) lane_mark[tl] = mark, lane_reach[tl] = 0;
            if ((along & ~lane_reach[tl]) == 0) continue;  // nothing new to carry on
            lane_reach[tl] |= along;
            stack.emplace_back(tl, along);
          }
        }
      }
      std::sort(found.begin(), found.end());
      for (size_t i = 0; i < found.size(); ++i) {
        if (i > 0 && found[i].first == found[i - 1].first) {
          net_.edge_succ_permissions.back() |= found[i].second;
          continue;
        }
        net_.edge_succ.push_back(found[i].first);
        net_.edge_succ_permissions.push_back(found[i].second);
      }
    }
    net_.edge_succ_begin[edges] = static_cast<uint32_t>(net_.edge_succ.size());
  }

  void add_roundabouts() {
    for (const auto& r : spec_.roundabouts) {
      std::vector<uint32_t> edges;
      for (const auto& id : r.edges) {
        auto it = net_.edge_index.find(id);
        if (it != net_.edge_index.end()) edges.push_back(it->second);
      }
      net_.roundabout_edges.push_back(std::move(edges));
    }
    // SUMO drives on into a roundabout's junctions without checking the room behind them (its
    // junction-blocking rule skips vehicles on roundabout edges).
    for (const auto& edges : net_.roundabout_edges)
      for (uint32_t e : edges)
        for (uint32_t l = net_.edge_first_lane[e]; l < net_.edge_first_lane[e] + net_.edge_num_lanes[e]; ++l)
          for (uint32_t c = net_.lane_conn_begin[l]; c < net_.lane_conn_begin[l + 1]; ++c)
            net_.conn_keep_clear[c] = 0;
  }
};

}  // namespace

Network build_network(const NetSpec& spec, const std::vector<TlLogicSpec>& tl_overrides,
                      const NetworkLimits& limits) {
  return Builder(spec, tl_overrides, limits).build();
}

}  // namespace lpsim

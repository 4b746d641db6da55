#include "net/actuated_detectors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "core/vclass.hpp"

namespace lpsim {

namespace {

// SUMO's DEFAULT_LENGTH_WITH_GAP: a passenger car and its gap, the unit in which a loop's distance from the
// line is bounded by what minDur lets pass.
constexpr double kLengthWithGap = 7.5;

// What one actuated signal's rules need about its links: the approach lanes each link leaves from.
struct SignalLinks {
  std::vector<std::vector<uint32_t>> lanes;  // per link index: from-lanes, ascending, unique
  std::vector<bool> turnaround;              // every connection of the link turns around
  std::vector<bool> one_lane;                // some approach of the link is an edge with one lane
};

// Connections from normal lanes into each lane: how many, and the from-lane of the last one (the only one
// when there is one).
struct Incoming {
  std::vector<uint32_t> count;
  std::vector<uint32_t> from;
};

// Lanes of an edge that some class other than pedestrians and bicycles may use (SUMO's "motorized" lanes).
uint32_t motorized_lanes(const Network& net, uint32_t edge) {
  const uint32_t first = net.edge_first_lane[edge];
  const uint32_t not_motorized = vclass_name_bit("pedestrian") | vclass_name_bit("bicycle");
  uint32_t n = 0;
  for (uint32_t l = first; l < first + net.edge_num_lanes[edge]; ++l)
    if (l >= net.lane_permissions.size() || (net.lane_permissions[l] & ~not_motorized) != 0) ++n;
  return n;
}

SignalLinks links_of(const Network& net, const std::vector<uint32_t>& conns, size_t num_links) {
  SignalLinks l{std::vector<std::vector<uint32_t>>(num_links), std::vector<bool>(num_links, true),
                std::vector<bool>(num_links, false)};
  for (uint32_t c : conns) {
    if (net.conn_link_index[c] < 0) continue;
    const auto i = static_cast<size_t>(net.conn_link_index[c]);
    if (i >= num_links) continue;
    const uint32_t from = net.conn_from_lane[c];
    if (std::find(l.lanes[i].begin(), l.lanes[i].end(), from) == l.lanes[i].end()) l.lanes[i].push_back(from);
    if (net.conn_dir[c] != 't') l.turnaround[i] = false;
    if (motorized_lanes(net, net.lane_edge[from]) == 1) l.one_lane[i] = true;
  }
  for (auto& v : l.lanes) std::sort(v.begin(), v.end());
  return l;
}

bool shares_lane(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
  for (uint32_t x : a)
    if (std::binary_search(b.begin(), b.end(), x)) return true;
  return false;
}

class SignalDetectors {
 public:
  SignalDetectors(Network& net, uint32_t s, const std::vector<uint32_t>& conns, const Incoming& incoming)
      : net_(net), s_(s), incoming_(incoming) {
    p0_ = net.signal_phase_begin[s];
    p1_ = net.signal_phase_begin[s + 1];
    num_links_ = net.phase_state_begin[p0_ + 1] - net.phase_state_begin[p0_];
    links_ = links_of(net, conns, num_links_);
  }

  // Loops appended to det_lane/det_pos (from first_det on), and per phase the loops that may extend it.
  std::vector<std::vector<uint32_t>> place(uint32_t first_det) {
    std::map<uint32_t, uint32_t> loop_of_lane;  // approach lane -> loop index
    for (size_t i = 0; i < num_links_; ++i)
      for (uint32_t lane : links_.lanes[i]) {
        if (loop_of_lane.count(lane)) continue;
        const double min_dur = minimum_min_duration(lane);
        if (min_dur == std::numeric_limits<double>::infinity()) continue;  // no actuated phase serves it
        loop_of_lane[lane] = first_det + static_cast<uint32_t>(add_loop(lane, min_dur));
      }
    std::vector<std::vector<uint32_t>> per_phase(p1_ - p0_);
    for (uint32_t p = p0_; p < p1_; ++p)
      if (actuated(p)) per_phase[p - p0_] = loops_for_phase(p, loop_of_lane);
    return per_phase;
  }

 private:
  double min_of(uint32_t p) const {
    return net_.phase_min_dur[p] >= 0 ? net_.phase_min_dur[p] : net_.phase_duration[p];
  }
  double max_of(uint32_t p) const {
    return net_.phase_max_dur[p] >= 0 ? net_.phase_max_dur[p] : net_.phase_duration[p];
  }
  bool actuated(uint32_t p) const { return min_of(p) != max_of(p); }
  char state(uint32_t p, size_t i) const { return net_.phase_state[net_.phase_state_begin[p] + i]; }

  // The shortest minDur of the actuated phases that show green to some link from `lane` (infinity: none).
  double minimum_min_duration(uint32_t lane) const {
    double result = std::numeric_limits<double>::infinity();
    for (uint32_t p = p0_; p < p1_; ++p)
      for (size_t i = 0; i < num_links_; ++i)
        if ((state(p, i) == 'G' || state(p, i) == 'g') && actuated(p) &&
            std::binary_search(links_.lanes[i].begin(), links_.lanes[i].end(), lane))
          result = std::min(result, min_of(p));
    return result;
  }

  // A loop detector-gap seconds of driving before the line, but no farther than the queue minDur lets pass
  // (vehicles standing between loop and line would otherwise not hold the green); on an approach shorter
  // than that, upstream along single predecessors, else at the approach's start.
  size_t add_loop(uint32_t lane, double min_dur) {
    const double distance =
        std::min(static_cast<double>(net_.signal_detector_gap[s_]) * net_.lane_speed[lane],
                 (min_dur / net_.signal_passing_time[s_] + 0.5) * kLengthWithGap);
    double pos = net_.lane_length[lane] - distance;
    uint32_t on = lane;
    // Bounded: a loop of single predecessors would add its length every round.
    for (uint32_t round = 0; pos < 0 && incoming_.count[on] == 1 && round < net_.num_lanes(); ++round) {
      on = incoming_.from[on];
      pos += net_.lane_length[on];
    }
    net_.det_lane.push_back(on);
    net_.det_pos.push_back(static_cast<float>(std::max(0.0, pos)));
    return loops_added_++;
  }

  // SUMO's choice of the loops that may extend phase p: a loop counts if every link from its approach is
  // green in p (green minor links only where they cannot hold the phase on their own: minor in every phase
  // or a turnaround, beside a major link from the same approach; or the approach's edge has one lane), and
  // no approach it leads into directly has a loop whose links are not green (joined signals).
  std::vector<uint32_t> loops_for_phase(uint32_t p, const std::map<uint32_t, uint32_t>& loop_of_lane) const {
    std::vector<bool> never_major(num_links_, true);
    for (uint32_t q = p0_; q < p1_; ++q)
      for (size_t i = 0; i < num_links_; ++i)
        if (state(q, i) == 'G') never_major[i] = false;
    std::set<size_t> green;
    for (size_t i = 0; i < num_links_; ++i) {
      const char st = state(p, i);
      if (st == 'G' || (st == 'g' && (((never_major[i] || links_.turnaround[i]) && has_major(p, i)) ||
                                      links_.one_lane[i])))
        green.insert(i);
    }
    std::map<uint32_t, std::vector<size_t>> links_of_loop;
    for (size_t i = 0; i < num_links_; ++i)
      for (uint32_t lane : links_.lanes[i]) {
        auto it = loop_of_lane.find(lane);
        if (it != loop_of_lane.end()) links_of_loop[it->second].push_back(i);
      }
    auto all_green = [&](uint32_t loop) {
      auto it = links_of_loop.find(loop);
      if (it == links_of_loop.end()) return true;
      for (size_t i : it->second)
        if (!green.count(i)) return false;
      return true;
    };
    std::vector<uint32_t> loops;
    for (const auto& [lane, loop] : loop_of_lane) {
      if (!links_of_loop.count(loop) || !all_green(loop)) continue;
      bool usable = true;
      for (uint32_t c = net_.lane_conn_begin[lane]; c < net_.lane_conn_begin[lane + 1] && usable; ++c) {
        if (net_.conn_dir[c] == 't') continue;
        auto next = loop_of_lane.find(net_.conn_to_lane[c]);
        if (next != loop_of_lane.end() && !all_green(next->second)) usable = false;
      }
      if (usable) loops.push_back(loop);
    }
    std::sort(loops.begin(), loops.end());
    return loops;
  }

  // Some link with an approach lane in common with link i is green with priority in phase p.
  bool has_major(uint32_t p, size_t i) const {
    for (size_t j = 0; j < num_links_; ++j)
      if (state(p, j) == 'G' && shares_lane(links_.lanes[j], links_.lanes[i])) return true;
    return false;
  }

  Network& net_;
  uint32_t s_;
  const Incoming& incoming_;
  uint32_t p0_ = 0, p1_ = 0;
  size_t num_links_ = 0;
  size_t loops_added_ = 0;
  SignalLinks links_;
};

}  // namespace

void place_actuated_detectors(Network& net) {
  const uint32_t ns = net.num_signals();
  net.signal_det_begin.assign(1, 0);
  net.phase_det_begin.assign(1, 0);
  net.det_lane.clear();
  net.det_pos.clear();
  net.phase_det.clear();
  std::vector<std::vector<uint32_t>> conns_of_signal(ns);
  Incoming incoming{std::vector<uint32_t>(net.num_lanes(), 0), std::vector<uint32_t>(net.num_lanes(), 0)};
  for (uint32_t c = 0; c < net.num_connections(); ++c) {
    const int32_t s = net.conn_signal[c];
    if (s >= 0 && net.signal_actuated[static_cast<uint32_t>(s)])
      conns_of_signal[static_cast<uint32_t>(s)].push_back(c);
    if (net.edge_is_internal[net.lane_edge[net.conn_from_lane[c]]]) continue;  // the via lane's own link
    ++incoming.count[net.conn_to_lane[c]];
    incoming.from[net.conn_to_lane[c]] = net.conn_from_lane[c];
  }
  for (uint32_t s = 0; s < ns; ++s) {
    const uint32_t first_det = static_cast<uint32_t>(net.det_lane.size());
    std::vector<std::vector<uint32_t>> per_phase;
    if (net.signal_actuated[s])
      per_phase = SignalDetectors(net, s, conns_of_signal[s], incoming).place(first_det);
    for (uint32_t p = net.signal_phase_begin[s]; p < net.signal_phase_begin[s + 1]; ++p) {
      const size_t k = p - net.signal_phase_begin[s];
      if (k < per_phase.size())
        net.phase_det.insert(net.phase_det.end(), per_phase[k].begin(), per_phase[k].end());
      net.phase_det_begin.push_back(static_cast<uint32_t>(net.phase_det.size()));
    }
    net.signal_det_begin.push_back(static_cast<uint32_t>(net.det_lane.size()));
  }
}

}  // namespace lpsim

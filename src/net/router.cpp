#include "net/router.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/for_each_index.hpp"
#include "kernels/rng.hpp"

namespace lpsim {
namespace {

// Cost model: a path's cost is the sum of length/speed over ALL its edges, the first and the last included
// (depart and arrival positions are ignored), plus the junction crossings between them (see Router). For
// a single destination this ranks paths exactly as leaving the last edge out would, as SUMO's router does;
// with several destinations a long destination edge counts against itself.
// Edges without a lane the request's vClass may use, moves between edges it may not make (see
// Network::edge_succ_permissions) and edges with speed 0 are impassable; internal edges are never part of a
// route because edge_succ links normal edges only, and internal edges given as origin, destination or via
// yield no path.
//
// Ties: the heap pops the smallest (cost, edge index), and an edge keeps the predecessor that first
// reached its final cost, so among equal-cost paths the one through earlier-settled edges wins. The
// outcome depends only on the request, never on the thread or on which requests share a search.

// Edge e's cost when entered at time t on interval travel times: its time in t's interval, else `free_cost`.
double interval_time(const IntervalTravelTimes& times, const std::vector<float>& free_cost, uint32_t e,
                     double t) {
  const float x = times.time[size_t(times.interval_at(t)) * times.num_edges + e];
  return std::isnan(x) ? double(free_cost[e]) : double(x);
}

struct HeapItem {
  double dist;
  uint32_t edge;
};
// std heap functions build a max-heap; "after" puts the smallest (dist, edge) on top.
inline bool heap_after(const HeapItem& a, const HeapItem& b) {
  return a.dist > b.dist || (a.dist == b.dist && a.edge > b.edge);
}

// One Dijkstra workspace per thread. Per-edge arrays are tagged with the search version instead of being
// cleared, so a query costs only what it touches.
class Search {
 public:
  Search(const Network& net, const std::vector<float>& cost, const std::vector<double>& step_cost,
         const std::vector<double>& crossing_cost, const RandomWeights& random)
      : net_(net),
        cost_(cost),
        step_cost_(step_cost),
        crossing_cost_(crossing_cost),
        random_(random),
        dist_(net.num_edges()),
        pred_(net.num_edges()),
        seen_(net.num_edges(), 0),
        settled_(net.num_edges(), 0),
        target_(net.num_edges(), 0),
        target_slot_(net.num_edges()) {}

  /// Runs from `seeds` (each starting at its own cost, or at seed_dist[k] when given) and calls
  /// on_settle(edge) for each settled edge in order; stops when it returns true or nothing is left. A timed
  /// search's distances are times (s since the request's departure) at the end of each edge.
  template <class OnSettle>
  void run(const std::vector<uint32_t>& seeds, OnSettle&& on_settle, const double* seed_dist = nullptr) {
    heap_.clear();
    for (size_t k = 0; k < seeds.size(); ++k) {
      const uint32_t s = seeds[k];
      const double c = seed_dist ? seed_dist[k] : timed_ ? edge_time(s, 0.0) : cost_[s] * factor(s);
      if (!std::isfinite(c) || net_.edge_is_internal[s] || (net_.edge_permissions[s] & vclass_) == 0)
        continue;
      if (seen_[s] != version_ || c < dist_[s]) {
        seen_[s] = version_;
        dist_[s] = c;
        pred_[s] = kNone;
        push(c, s);
      }
    }
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), heap_after);
      const HeapItem top = heap_.back();
      heap_.pop_back();
      const uint32_t e = top.edge;
      if (settled_[e] == version_ || top.dist > dist_[e]) continue;  // stale entry
      settled_[e] = version_;
      if (on_settle(e)) return;
      for (uint32_t i = net_.edge_succ_begin[e]; i < net_.edge_succ_begin[e + 1]; ++i) {
        const uint32_t s = net_.edge_succ[i];
        if (settled_[s] == version_ || (net_.edge_succ_permissions[i] & vclass_) == 0) continue;
        const double c = timed_ ? timed_step(i, s, top.dist) : step_cost_[i] * factor(s);
        if (!std::isfinite(c)) continue;
        const double d = top.dist + c;
        if (seen_[s] != version_ || d < dist_[s]) {
          seen_[s] = version_;
          dist_[s] = d;
          pred_[s] = static_cast<int32_t>(e);
          push(d, s);
        }
      }
    }
  }

  /// The vClass mask and the random stream (RouteRequest::random_stream) of the following searches.
  void set_request(uint32_t vclass, uint64_t random_stream) {
    vclass_ = vclass;
    stream_ = random_stream;
  }

  /// Following searches are timed (null: not): edges cost their travel time in `times` at the time they are
  /// entered, the request departing at `depart`.
  void set_timed(const IntervalTravelTimes* times, double depart) {
    timed_ = times;
    depart_ = depart;
  }

  /// Edge e's cost when entered `since` seconds after the departure of a timed search.
  double edge_time(uint32_t e, double since) const {
    return interval_time(*timed_, cost_, e, depart_ + since);
  }

  /// Cost of move i onto edge s after reaching the end of its predecessor `since` seconds after departure.
  double timed_step(uint32_t i, uint32_t s, double since) const {
    const double crossing = crossing_cost_[i];
    return crossing + edge_time(s, since + crossing);
  }

  /// The distance a search reached edge e at (valid for the edges it settled).
  double dist(uint32_t e) const { return dist_[e]; }

  /// Starts a new search: all per-edge tags become stale.
  void next_version() {
    if (++version_ == 0) {  // wrapped: clear once every 2^32 searches
      std::fill(seen_.begin(), seen_.end(), 0);
      std::fill(settled_.begin(), settled_.end(), 0);
      std::fill(target_.begin(), target_.end(), 0);
      version_ = 1;
    }
  }

  /// Path from a seed to the settled edge `e`.
  std::vector<uint32_t> path_to(uint32_t e) const {
    std::vector<uint32_t> path;
    for (int32_t x = static_cast<int32_t>(e); x != kNone; x = pred_[x])
      path.push_back(static_cast<uint32_t>(x));
    std::reverse(path.begin(), path.end());
    return path;
  }

  /// Fastest path from any of `origins` to any of `targets` (the first target settled); empty if none.
  std::vector<uint32_t> segment(const std::vector<uint32_t>& origins, const std::vector<uint32_t>& targets,
                                const double* seed_dist = nullptr) {
    next_version();
    for (uint32_t t : targets) target_[t] = version_;
    int32_t reached = kNone;
    run(
        origins,
        [&](uint32_t e) {
          if (target_[e] != version_) return false;
          reached = static_cast<int32_t>(e);
          return true;
        },
        seed_dist);
    return reached == kNone ? std::vector<uint32_t>{} : path_to(static_cast<uint32_t>(reached));
  }

  /// One search from `origins` answering every request in `group` (all have these origins and no via).
  void one_to_many(const std::vector<uint32_t>& origins, const std::vector<uint32_t>& group,
                   const std::vector<RouteRequest>& requests, std::vector<std::vector<uint32_t>>& out) {
    next_version();
    // (destination, position in group) pairs sorted by destination; target_slot_ points at an edge's first
    // pair.
    pairs_.clear();
    for (uint32_t k = 0; k < group.size(); ++k)
      for (uint32_t d : requests[group[k]].destinations) pairs_.push_back({d, k});
    std::sort(pairs_.begin(), pairs_.end());
    for (uint32_t i = 0; i < pairs_.size(); ++i)
      if (target_[pairs_[i].first] != version_) {
        target_[pairs_[i].first] = version_;
        target_slot_[pairs_[i].first] = i;
      }
    size_t remaining = 0;
    for (uint32_t r : group) remaining += requests[r].destinations.empty() ? 0 : 1;
    if (remaining == 0) return;
    answered_.assign(group.size(), 0);
    run(origins, [&](uint32_t e) {
      if (target_[e] != version_) return false;
      for (uint32_t i = target_slot_[e]; i < pairs_.size() && pairs_[i].first == e; ++i) {
        const uint32_t k = pairs_[i].second;
        if (answered_[k]) continue;  // an earlier-settled destination of this request won
        answered_[k] = 1;
        out[group[k]] = path_to(e);
        --remaining;
      }
      return remaining == 0;
    });
  }

 private:
  // The random factor of edge e's cost for the current request (1 without random weights).
  double factor(uint32_t e) const {
    if (stream_ == 0 || !(random_.factor > 1)) return 1.0;
    return 1.0 + (random_.factor - 1.0) * rng_uniform_double(random_.seed, stream_, e);
  }

  void push(double d, uint32_t e) {
    heap_.push_back({d, e});
    std::push_heap(heap_.begin(), heap_.end(), heap_after);
  }

  const Network& net_;
  const std::vector<float>& cost_;
  const std::vector<double>& step_cost_;
  const std::vector<double>& crossing_cost_;
  const RandomWeights& random_;
  std::vector<double> dist_;
  std::vector<int32_t> pred_;
  std::vector<uint32_t> seen_, settled_, target_, target_slot_;
  uint32_t version_ = 1;
  uint32_t vclass_ = kAllVClasses;
  uint64_t stream_ = 0;
  const IntervalTravelTimes* timed_ = nullptr;
  double depart_ = 0;
  std::vector<HeapItem> heap_;
  std::vector<std::pair<uint32_t, uint32_t>> pairs_;
  std::vector<char> answered_;
};

std::vector<uint32_t> route_one(Search& search, const RouteRequest& r) {
  search.set_request(r.vclass, r.random_stream);
  std::vector<uint32_t> path;
  std::vector<uint32_t> sources = r.origins;
  for (uint32_t v : r.via) {
    std::vector<uint32_t> leg = search.segment(sources, {v});
    if (leg.empty()) return {};
    // The leg starts on the previous via edge, which already ends `path`.
    path.insert(path.end(), leg.begin() + (path.empty() ? 0 : 1), leg.end());
    sources = {v};
  }
  std::vector<uint32_t> leg = search.segment(sources, r.destinations);
  if (leg.empty()) return {};
  path.insert(path.end(), leg.begin() + (path.empty() ? 0 : 1), leg.end());
  return path;
}

// route_one on a timed search: each leg starts on the previous via edge at the time the last leg reached
// its end. `cost` receives the path's travel time (infinite: none).
std::vector<uint32_t> route_one_timed(Search& search, const RouteRequest& r, double* cost) {
  search.set_request(r.vclass, 0);
  *cost = std::numeric_limits<double>::infinity();
  std::vector<uint32_t> path;
  std::vector<uint32_t> sources = r.origins;
  double at = 0;
  auto leg_to = [&](const std::vector<uint32_t>& targets) {
    const std::vector<uint32_t> leg = search.segment(sources, targets, path.empty() ? nullptr : &at);
    if (leg.empty()) return false;
    path.insert(path.end(), leg.begin() + (path.empty() ? 0 : 1), leg.end());
    at = search.dist(leg.back());
    sources = {leg.back()};
    return true;
  };
  for (uint32_t v : r.via)
    if (!leg_to({v})) return {};
  if (!leg_to(r.destinations)) return {};
  *cost = at;
  return path;
}

// SUMO's MSRoutingEngine::getEffort: length over the averaged speed (at least NUMERICAL_EPS), at least the
// free-flow time (SUMO's minimum travel time, here at the speed limit).
double congested_time(double length, double limit, double speed) {
  constexpr double kNumericalEps = 0.001;
  return std::max(length / limit, length / std::max(speed, kNumericalEps));
}

// Time to cross the junction-internal lanes of connection c: from its via lane on, through any internal
// junction, to the next normal lane. Each internal lane costs its length / speed, and minor_penalty
// when the link entering it has no priority (state not an upper-case letter) and no signal, as SUMO adds
// to such internal edges' travel time.
// With `speeds` (per edge), an internal lane takes at least its length at its internal edge's speed.
double crossing_cost(const Network& net, uint32_t c, double minor_penalty,
                     const std::vector<double>* speeds) {
  double total = 0;
  for (int parts = 0; parts < 8; ++parts) {  // a junction has at most a few internal lanes in a row
    const int32_t via = net.conn_via_lane[c];
    if (via < 0) return total;
    const float speed = net.lane_speed[via];
    if (speed <= 0) return std::numeric_limits<double>::infinity();
    total += speeds ? congested_time(net.lane_length[via], speed, (*speeds)[net.lane_edge[via]])
                    : net.lane_length[via] / speed;
    const char state = net.conn_state[c];
    if (net.conn_signal[c] < 0 && !(state >= 'A' && state <= 'Z')) total += minor_penalty;
    const uint32_t next = net.lane_conn_begin[via];
    if (next == net.lane_conn_begin[via + 1]) return total;
    c = next;  // the internal lane's link onward (to a second internal lane, or out of the junction)
  }
  return total;
}

}  // namespace

void check_request_edges(const std::vector<RouteRequest>& requests, uint32_t num_edges) {
  for (size_t i = 0; i < requests.size(); ++i)
    for (const auto* list : {&requests[i].origins, &requests[i].destinations, &requests[i].via})
      for (uint32_t e : *list)
        if (e >= num_edges)
          throw std::out_of_range("route request " + std::to_string(i) + " names edge index " +
                                  std::to_string(e) + " of " + std::to_string(num_edges));
}

Router::Router(const Network& net, double minor_penalty, RandomWeights random)
    : net_(net),
      random_(random),
      minor_penalty_(minor_penalty),
      edge_cost_(net.num_edges()),
      step_cost_(net.edge_succ.size()),
      crossing_cost_(net.edge_succ.size()),
      crossing_(net.edge_succ.size(), -1) {
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    for (uint32_t i = net.edge_succ_begin[e]; i < net.edge_succ_begin[e + 1]; ++i) {
      const uint32_t to = net.edge_succ[i];
      // SUMO keeps one crossing per successor edge: that of the first link onto it, in lane order.
      int32_t first = -1;
      const uint32_t l0 = net.edge_first_lane[e];
      for (uint32_t l = l0; l < l0 + net.edge_num_lanes[e] && first < 0; ++l)
        for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c)
          if (net.lane_edge[net.conn_to_lane[c]] == to) {
            first = static_cast<int32_t>(c);
            break;
          }
      crossing_[i] = first;
    }
  set_costs(nullptr);
}

void Router::set_speeds(const std::vector<double>& edge_speed) {
  if (edge_speed.size() != net_.num_edges())
    throw std::invalid_argument("Router::set_speeds: " + std::to_string(edge_speed.size()) + " speeds for " +
                                std::to_string(net_.num_edges()) + " edges");
  set_costs(&edge_speed);
}

void Router::set_costs(const std::vector<double>* speeds) {
  const Network& net = net_;
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    const float limit = net.edge_speed[e];
    if (limit <= 0)
      edge_cost_[e] = std::numeric_limits<float>::infinity();
    else if (speeds)
      edge_cost_[e] = static_cast<float>(congested_time(net.edge_length[e], limit, (*speeds)[e]));
    else
      edge_cost_[e] = net.edge_length[e] / limit;
  }
  for (uint32_t i = 0; i < step_cost_.size(); ++i) {
    const int32_t first = crossing_[i];
    crossing_cost_[i] =
        first >= 0 ? crossing_cost(net, static_cast<uint32_t>(first), minor_penalty_, speeds) : 0.0;
    step_cost_[i] = edge_cost_[net.edge_succ[i]] + crossing_cost_[i];
  }
}

void Router::set_interval_costs(const IntervalTravelTimes& times, uint32_t k) {
  if (times.num_edges != net_.num_edges() || k >= times.intervals())
    throw std::invalid_argument("Router::set_interval_costs: no interval " + std::to_string(k) +
                                " of this network's edges");
  set_costs(nullptr);
  for (uint32_t e = 0; e < net_.num_edges(); ++e) {
    const float t = times.time[size_t(k) * times.num_edges + e];
    if (!std::isnan(t) && std::isfinite(edge_cost_[e])) edge_cost_[e] = t;
  }
  for (uint32_t i = 0; i < step_cost_.size(); ++i)
    step_cost_[i] = edge_cost_[net_.edge_succ[i]] + crossing_cost_[i];
}

void IntervalTravelTimes::resize(uint32_t edges, uint32_t intervals) {
  num_edges = edges;
  time.assign(size_t(edges) * intervals, std::numeric_limits<float>::quiet_NaN());
}

uint32_t IntervalTravelTimes::interval_at(double t) const {
  const uint32_t n = intervals();
  if (n == 0) throw std::logic_error("IntervalTravelTimes: no interval");
  const double k = std::floor((t - begin) / period);
  if (!(k > 0)) return 0;
  return k >= n - 1 ? n - 1 : static_cast<uint32_t>(k);
}

std::vector<std::vector<uint32_t>> Router::route_timed(const std::vector<RouteRequest>& requests,
                                                       const std::vector<double>& depart,
                                                       const IntervalTravelTimes& times, int threads,
                                                       std::vector<double>* costs) const {
  check_request_edges(requests, net_.num_edges());
  if (depart.size() != requests.size())
    throw std::invalid_argument("Router::route_timed: " + std::to_string(depart.size()) + " departures for " +
                                std::to_string(requests.size()) + " requests");
  if (times.num_edges != net_.num_edges() || times.intervals() == 0)
    throw std::invalid_argument("Router::route_timed: travel times not sized to the network's edges");
  std::vector<std::vector<uint32_t>> out(requests.size());
  std::vector<double> cost(requests.size());
  for_each_index(
      requests.size(), threads, [&] { return Search(net_, edge_cost_, step_cost_, crossing_cost_, random_); },
      [&](Search& search, size_t k) {
        search.set_timed(&times, depart[k]);
        out[k] = route_one_timed(search, requests[k], &cost[k]);
      });
  if (costs) *costs = std::move(cost);
  return out;
}

double Router::timed_edge_cost(uint32_t e, double t, const IntervalTravelTimes& times) const {
  return interval_time(times, edge_cost_, e, t);
}

double Router::timed_cost(std::span<const uint32_t> path, double depart,
                          const IntervalTravelTimes& times) const {
  if (path.empty()) return std::numeric_limits<double>::infinity();
  // As a timed search costs it (Search::timed_step), move by move.
  double at = interval_time(times, edge_cost_, path[0], depart);
  for (size_t k = 1; k < path.size(); ++k) {
    const uint32_t e = path[k - 1];
    double step = std::numeric_limits<double>::infinity();
    for (uint32_t i = net_.edge_succ_begin[e]; i < net_.edge_succ_begin[e + 1]; ++i)
      if (net_.edge_succ[i] == path[k])
        step = std::min(step, crossing_cost_[i] +
                                  interval_time(times, edge_cost_, path[k], depart + at + crossing_cost_[i]));
    at += step;
  }
  return at;
}

double Router::cost(const std::vector<uint32_t>& path) const {
  double total = 0;
  for (size_t k = 0; k < path.size(); ++k) {
    if (k == 0) {
      total += edge_cost_[path[0]];
      continue;
    }
    const uint32_t e = path[k - 1];
    double step = std::numeric_limits<double>::infinity();
    for (uint32_t i = net_.edge_succ_begin[e]; i < net_.edge_succ_begin[e + 1]; ++i)
      if (net_.edge_succ[i] == path[k]) step = std::min(step, step_cost_[i]);
    total += step;
  }
  return total;
}

std::vector<std::vector<uint32_t>> Router::route_all(const std::vector<RouteRequest>& requests,
                                                     int threads) const {
  check_request_edges(requests, net_.num_edges());

  // Work items: one per distinct origin set and vClass (requests without via sharing them, e.g. trips between
  // junctions or zones, share one one-to-many search), and one per request with via or random weights. A
  // search settles edges in the same order whatever it stops on, so sharing gives each request the path its
  // own search would. Items depend only on the requests, never on the thread count.
  std::vector<uint32_t> by_origins;  // requests without via, grouped by equal origin lists
  std::vector<uint32_t> singles;
  for (uint32_t i = 0; i < requests.size(); ++i) {
    if (requests[i].via.empty() && requests[i].random_stream == 0)
      by_origins.push_back(i);
    else
      singles.push_back(i);
  }
  std::sort(by_origins.begin(), by_origins.end(), [&](uint32_t a, uint32_t b) {
    if (requests[a].vclass != requests[b].vclass) return requests[a].vclass < requests[b].vclass;
    const auto& oa = requests[a].origins;
    const auto& ob = requests[b].origins;
    return oa != ob ? oa < ob : a < b;
  });
  struct Item {
    uint32_t first, last;  // range in by_origins, or a request in singles when first == last == kSingle
    uint32_t single;
  };
  constexpr uint32_t kSingle = std::numeric_limits<uint32_t>::max();
  std::vector<Item> items;
  for (uint32_t i = 0; i < by_origins.size();) {
    uint32_t j = i;
    while (j < by_origins.size() && requests[by_origins[j]].origins == requests[by_origins[i]].origins &&
           requests[by_origins[j]].vclass == requests[by_origins[i]].vclass)
      ++j;
    items.push_back({i, j, kSingle});
    i = j;
  }
  for (uint32_t r : singles) items.push_back({0, 0, r});

  std::vector<std::vector<uint32_t>> out(requests.size());
  for_each_index(
      items.size(), threads, [&] { return Search(net_, edge_cost_, step_cost_, crossing_cost_, random_); },
      [&](Search& search, size_t k) {
        const Item& it = items[k];
        if (it.single != kSingle) {
          out[it.single] = route_one(search, requests[it.single]);
          return;
        }
        std::vector<uint32_t> group;
        for (uint32_t i = it.first; i < it.last; ++i) group.push_back(by_origins[i]);
        search.set_request(requests[group.front()].vclass, 0);
        search.one_to_many(requests[group.front()].origins, group, requests, out);
      });
  return out;
}

}  // namespace lpsim

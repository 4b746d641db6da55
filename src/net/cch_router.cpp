#include "net/cch_router.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>

#include "core/for_each_index.hpp"

namespace lpsim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// METIS's own random choices, fixed: the same order (and so the same hierarchy) on every run.
constexpr idx_t kOrderSeed = 1;
// Separators METIS tries at each dissection, keeping the smallest: on the Bay Area network 10 instead of 1
// took the ordering from 0.6 s to 1.8 s and a query's relaxations from 14,700 to 13,100.
constexpr idx_t kSeparatorTries = 10;

// Each node's neighbours in the edge graph taken as undirected (no self-loops, no repeats).
std::vector<std::vector<uint32_t>> undirected_neighbours(const Network& net) {
  const uint32_t n = net.num_edges();
  std::vector<std::vector<uint32_t>> adj(n);
  for (uint32_t e = 0; e < n; ++e)
    for (uint32_t i = net.edge_succ_begin[e]; i < net.edge_succ_begin[e + 1]; ++i) {
      const uint32_t f = net.edge_succ[i];
      if (f == e) continue;
      adj[e].push_back(f);
      adj[f].push_back(e);
    }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return adj;
}

// The elimination order: per node, its rank (METIS's inverse permutation of a nested dissection).
std::vector<uint32_t> nested_dissection_ranks(const std::vector<std::vector<uint32_t>>& adj) {
  const uint32_t n = static_cast<uint32_t>(adj.size());
  std::vector<uint32_t> rank(n);
  std::vector<idx_t> xadj(n + 1, 0), adjncy;
  for (uint32_t v = 0; v < n; ++v) {
    for (const uint32_t w : adj[v]) adjncy.push_back(static_cast<idx_t>(w));
    xadj[v + 1] = static_cast<idx_t>(adjncy.size());
  }
  if (adjncy.empty()) {  // no moves at all: any order is perfect
    for (uint32_t v = 0; v < n; ++v) rank[v] = v;
    return rank;
  }
  idx_t nvtxs = static_cast<idx_t>(n);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = kOrderSeed;
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_NSEPS] = kSeparatorTries;
  std::vector<idx_t> perm(n), iperm(n);
  if (METIS_NodeND(&nvtxs, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data()) !=
      METIS_OK)
    throw std::runtime_error("METIS_NodeND failed to order the edge graph of " + std::to_string(n) +
                             " edges");
  for (uint32_t v = 0; v < n; ++v) rank[v] = static_cast<uint32_t>(iperm[v]);
  return rank;
}

}  // namespace

CchRouter::CchRouter(const Network& net) : net_(net) {
  const uint32_t n = net.num_edges();
  const std::vector<std::vector<uint32_t>> adj = undirected_neighbours(net);
  rank_ = nested_dissection_ranks(adj);
  order_.assign(n, kNone);
  for (uint32_t e = 0; e < n; ++e) order_[rank_[e]] = e;
  // Chordal completion: eliminating a node joins its higher neighbours into a clique; the lowest of them (its
  // parent in the elimination tree) inherits the others, which is all the cliques need.
  std::vector<std::vector<uint32_t>> up(n);
  for (uint32_t e = 0; e < n; ++e)
    for (const uint32_t f : adj[e])
      if (rank_[f] > rank_[e]) up[rank_[e]].push_back(rank_[f]);
  parent_.assign(n, kNone);
  std::vector<uint32_t> merged;
  for (uint32_t r = 0; r < n; ++r) {
    std::vector<uint32_t>& u = up[r];
    std::sort(u.begin(), u.end());
    u.erase(std::unique(u.begin(), u.end()), u.end());
    if (u.empty()) continue;
    const uint32_t p = u.front();
    parent_[r] = p;
    std::vector<uint32_t>& pu = up[p];
    std::sort(pu.begin(), pu.end());
    merged.clear();
    std::set_union(pu.begin(), pu.end(), u.begin() + 1, u.end(), std::back_inserter(merged));
    pu.swap(merged);
  }
  begin_.assign(n + 1, 0);
  for (uint32_t r = 0; r < n; ++r) begin_[r + 1] = begin_[r] + static_cast<uint32_t>(up[r].size());
  head_.reserve(begin_[n]);
  tail_.reserve(begin_[n]);
  for (uint32_t r = 0; r < n; ++r) {
    head_.insert(head_.end(), up[r].begin(), up[r].end());
    tail_.insert(tail_.end(), up[r].size(), r);
    std::vector<uint32_t>().swap(up[r]);
  }
  // Depth in the elimination tree, from the roots down (a parent's rank is above its children's).
  std::vector<uint32_t> depth(n, 1);
  for (uint32_t r = n; r-- > 0;) {
    if (parent_[r] != kNone) depth[r] = depth[parent_[r]] + 1;
    height_ = std::max(height_, depth[r]);
  }
}

uint32_t CchRouter::arc(uint32_t lo, uint32_t hi) const {
  const auto first = head_.begin() + begin_[lo], last = head_.begin() + begin_[lo + 1];
  const auto it = std::lower_bound(first, last, hi);
  return it != last && *it == hi ? static_cast<uint32_t>(it - head_.begin()) : kNone;
}

CchRouter::Metric CchRouter::customize(const Router& costs, uint32_t vclass) const {
  const uint32_t n = num_nodes(), m = num_arcs();
  Metric w;
  w.up.assign(m, kInf);
  w.down.assign(m, kInf);
  w.up_first.assign(m, kNone);
  w.up_second.assign(m, kNone);
  w.down_first.assign(m, kNone);
  w.down_second.assign(m, kNone);
  w.first_cost.assign(n, kInf);
  for (uint32_t e = 0; e < n; ++e) {
    if (!net_.edge_is_internal[e] && (net_.edge_permissions[e] & vclass) != 0)
      w.first_cost[e] = costs.edge_cost(e);
    for (uint32_t i = net_.edge_succ_begin[e]; i < net_.edge_succ_begin[e + 1]; ++i) {
      const uint32_t f = net_.edge_succ[i];
      const double c = costs.step_cost(i);
      if (f == e || (net_.edge_succ_permissions[i] & vclass) == 0 || !std::isfinite(c)) continue;
      const uint32_t a = rank_[e], b = rank_[f];
      if (a < b) {
        const uint32_t k = arc(a, b);
        w.up[k] = std::min(w.up[k], c);
      } else {
        const uint32_t k = arc(b, a);
        w.down[k] = std::min(w.down[k], c);
      }
    }
  }
  // From the lowest node up: a node's arcs are final once every lower node has been passed, and the
  // triangles it closes improve the arcs between its higher neighbours. An arc keeps its own cost on a tie.
  for (uint32_t r = 0; r < n; ++r)
    for (uint32_t i = begin_[r]; i < begin_[r + 1]; ++i) {
      const uint32_t x = head_[i];
      for (uint32_t j = i + 1; j < begin_[r + 1]; ++j) {
        const uint32_t y = head_[j];
        const uint32_t k = arc(x, y);             // exists: the completion is chordal
        const double up = w.down[i] + w.up[j];    // x -> r -> y
        const double down = w.down[j] + w.up[i];  // y -> r -> x
        if (up < w.up[k]) {
          w.up[k] = up;
          w.up_first[k] = i;
          w.up_second[k] = j;
        }
        if (down < w.down[k]) {
          w.down[k] = down;
          w.down_first[k] = j;
          w.down_second[k] = i;
        }
      }
    }
  return w;
}

CchRouter::Workspace::Workspace(const CchRouter& cch)
    : forward_(cch.num_nodes(), kInf),
      backward_(cch.num_nodes(), kInf),
      forward_pred_(cch.num_nodes(), kNone),
      backward_pred_(cch.num_nodes(), kNone) {}

void CchRouter::unpack(const Metric& m, uint32_t k, bool upwards, std::vector<uint32_t>& path,
                       std::vector<std::pair<uint32_t, bool>>& stack) const {
  stack.assign(1, {k, upwards});
  while (!stack.empty()) {
    const auto [a, up] = stack.back();
    stack.pop_back();
    const uint32_t first = up ? m.up_first[a] : m.down_first[a];
    if (first == kNone) {  // a move: it ends at the head going up, at the tail going down
      path.push_back(order_[up ? head_[a] : tail_[a]]);
      continue;
    }
    stack.push_back({up ? m.up_second[a] : m.down_second[a], true});
    stack.push_back({first, false});
  }
}

std::vector<uint32_t> CchRouter::route(const Metric& m, uint32_t origin, uint32_t destination, Workspace& ws,
                                       double* cost) const {
  if (origin >= num_nodes() || destination >= num_nodes())
    throw std::out_of_range("CCH query names edge " + std::to_string(std::max(origin, destination)) + " of " +
                            std::to_string(num_nodes()));
  if (cost != nullptr) *cost = kInf;
  const double first = m.first_cost[origin];
  if (!std::isfinite(first)) return {};
  if (origin == destination) {
    if (cost != nullptr) *cost = first;
    return {origin};
  }
  // Upward searches along the two elimination-tree paths, taken together in rank order: every arc leads to
  // an ancestor, so each node is final when its turn comes. Where the paths have joined (the common
  // ancestors), a node is a meeting candidate, and a side whose distance there is no better than the best
  // meeting found cannot lead to a better one: its arcs are not relaxed.
  const auto relax = [&](uint32_t x, const std::vector<double>& arc_cost, std::vector<double>& dist,
                         std::vector<uint32_t>& pred) {
    const double dx = dist[x];
    for (uint32_t k = begin_[x]; k < begin_[x + 1]; ++k) {
      const double d = dx + arc_cost[k];
      const uint32_t h = head_[k];
      if (d < dist[h]) {
        if (ws.forward_[h] == kInf && ws.backward_[h] == kInf) ws.touched_.push_back(h);
        dist[h] = d;
        pred[h] = k;
      }
    }
  };
  const uint32_t a = rank_[origin], b = rank_[destination];
  ws.forward_[a] = 0;
  ws.backward_[b] = 0;
  ws.touched_.push_back(a);
  ws.touched_.push_back(b);
  double best = kInf;
  uint32_t meet = kNone;
  for (uint32_t x = a, y = b; x != kNone || y != kNone;) {
    if (x == y) {
      const double d = ws.forward_[x] + ws.backward_[x];
      if (d < best) {
        best = d;
        meet = x;
      }
      if (ws.forward_[x] < best) relax(x, m.up, ws.forward_, ws.forward_pred_);
      if (ws.backward_[x] < best) relax(x, m.down, ws.backward_, ws.backward_pred_);
      x = y = parent_[x];
    } else if (x < y) {  // kNone is above every rank
      if (ws.forward_[x] < best) relax(x, m.up, ws.forward_, ws.forward_pred_);
      x = parent_[x];
    } else {
      if (ws.backward_[y] < best) relax(y, m.down, ws.backward_, ws.backward_pred_);
      y = parent_[y];
    }
  }
  std::vector<uint32_t> path;
  if (meet != kNone) {
    std::vector<uint32_t>& up_arcs = ws.touched_arcs_;  // from the meeting node back down to the origin
    up_arcs.clear();
    for (uint32_t x = meet; x != a; x = tail_[ws.forward_pred_[x]]) up_arcs.push_back(ws.forward_pred_[x]);
    path.push_back(origin);
    for (auto it = up_arcs.rbegin(); it != up_arcs.rend(); ++it) unpack(m, *it, true, path, ws.stack_);
    for (uint32_t x = meet; x != b; x = tail_[ws.backward_pred_[x]])
      unpack(m, ws.backward_pred_[x], false, path, ws.stack_);
    if (cost != nullptr) *cost = first + best;
  }
  for (const uint32_t x : ws.touched_) {
    ws.forward_[x] = ws.backward_[x] = kInf;
    ws.forward_pred_[x] = ws.backward_pred_[x] = kNone;
  }
  ws.touched_.clear();
  return path;
}

std::vector<std::vector<uint32_t>> CchRouter::route_all(const Router& dijkstra,
                                                        const std::vector<RouteRequest>& requests,
                                                        int threads) const {
  std::vector<std::vector<uint32_t>> out(requests.size());
  std::vector<RouteRequest> others;
  std::vector<size_t> others_at;
  std::map<uint32_t, Metric> metrics;  // per vehicle class
  std::vector<size_t> mine;
  check_request_edges(requests, num_nodes());
  for (size_t i = 0; i < requests.size(); ++i) {
    const RouteRequest& r = requests[i];
    if (r.origins.size() == 1 && r.destinations.size() == 1 && r.random_stream == 0) {
      if (!metrics.count(r.vclass)) metrics.emplace(r.vclass, customize(dijkstra, r.vclass));
      mine.push_back(i);
    } else {
      others.push_back(r);
      others_at.push_back(i);
    }
  }
  const auto answer = [&](size_t i, Workspace& ws) {
    const RouteRequest& r = requests[i];
    const Metric& m = metrics.at(r.vclass);
    std::vector<uint32_t>& path = out[i];
    uint32_t from = r.origins[0];
    for (size_t leg = 0; leg <= r.via.size(); ++leg) {
      const uint32_t to = leg < r.via.size() ? r.via[leg] : r.destinations[0];
      std::vector<uint32_t> part = route(m, from, to, ws);
      if (part.empty()) {
        path.clear();
        return;
      }
      // A leg starts on the edge the one before ended on.
      path.insert(path.end(), part.begin() + (path.empty() ? 0 : 1), part.end());
      from = to;
    }
  };
  for_each_index(
      mine.size(), threads, [&] { return Workspace(*this); },
      [&](Workspace& ws, size_t k) { answer(mine[k], ws); });
  if (!others.empty()) {
    std::vector<std::vector<uint32_t>> paths = dijkstra.route_all(others, threads);
    for (size_t k = 0; k < others.size(); ++k) out[others_at[k]] = std::move(paths[k]);
  }
  return out;
}

}  // namespace lpsim

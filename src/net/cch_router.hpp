#pragma once
// A customizable contraction hierarchy (CCH) over the network's edge graph: the graph whose nodes are the
// network's edges and whose arcs are the moves between them (Network::edge_succ), so that turn restrictions
// and the junction crossings' costs are the arcs' own. Three phases, as in Dibbelt, Strasser and Wagner's
// CCH:
//  1. ordering and contraction, once per network: a nested-dissection order of the nodes (METIS_NodeND) and
//     the shortcuts that eliminating the nodes in that order adds (the chordal completion), independent of
//     any cost;
//  2. customization, once per cost metric (a vehicle class, a time interval's travel times): every arc's and
//     shortcut's cost both ways, from the lowest node up, over the triangles each node closes;
//  3. queries: an upward search from the origin and one from the destination along their ancestors in the
//     elimination tree (no priority queue), met at the best common node; the path is unpacked through the
//     middle node each shortcut recorded.
// Path costs equal Dijkstra's (net/router.hpp) on the same metric; among paths of equal cost the two may
// choose different ones.
#include <cstdint>
#include <limits>
#include <vector>

#include "net/network.hpp"
#include "net/router.hpp"

namespace lpsim {

class CchRouter {
 public:
  /// Orders and contracts `net`'s edge graph (METIS with a fixed seed: the same hierarchy on every run).
  explicit CchRouter(const Network& net);

  /// One customized cost metric: the cost of every upward arc both ways, and the shortcuts' middle nodes.
  struct Metric {
    std::vector<double> up, down;  // per arc: lower node -> higher node, and back (s; inf: no move)
    // Per arc and way, the two arcs a shortcut's cost runs through, the first taken downwards and the second
    // upwards (kNone: the arc is a move of the network).
    std::vector<uint32_t> up_first, up_second, down_first, down_second;
    std::vector<double> first_cost;  // per network edge: its own cost as a path's first edge (inf: none)
  };
  /// The metric of `costs` (each move's step_cost, each edge's own cost) for vehicle class mask `vclass`:
  /// moves and origins the class may not use are impassable, as in Router.
  Metric customize(const Router& costs, uint32_t vclass = kAllVClasses) const;

  /// A query's scratch space (one per thread).
  class Workspace {
   public:
    explicit Workspace(const CchRouter& cch);

   private:
    friend class CchRouter;
    std::vector<double> forward_, backward_;
    std::vector<uint32_t> forward_pred_, backward_pred_;  // the arc each node was reached by
    std::vector<uint32_t> touched_;
    std::vector<uint32_t> touched_arcs_;
    std::vector<std::pair<uint32_t, bool>> stack_;
  };

  /// The fastest path from network edge `origin` to `destination` (both included; empty: none) under `m`,
  /// and its cost in `*cost` when given (the origin's own cost plus each move's).
  std::vector<uint32_t> route(const Metric& m, uint32_t origin, uint32_t destination, Workspace& ws,
                              double* cost = nullptr) const;

  /// Router::route_all's answers with this hierarchy: each request from one origin to one destination (its
  /// via edges in order) on the metric of its class (customized once per class), on `threads` threads (0:
  /// all). Requests this query does not answer (several origins or destinations, random edge costs) go to
  /// `dijkstra`, whose costs are the metrics'. The same paths on any number of threads.
  std::vector<std::vector<uint32_t>> route_all(const Router& dijkstra,
                                               const std::vector<RouteRequest>& requests, int threads) const;

  uint32_t num_nodes() const { return static_cast<uint32_t>(rank_.size()); }
  /// Arcs of the contracted graph, shortcuts included.
  uint32_t num_arcs() const { return static_cast<uint32_t>(head_.size()); }
  /// Nodes on the longest path from a node to the root of its elimination tree (a query's bound).
  uint32_t elimination_tree_height() const { return height_; }

  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

 private:
  // The arc between ranks lo < hi, stored at lo; kNone when there is none.
  uint32_t arc(uint32_t lo, uint32_t hi) const;
  // Appends the network edges after the start of arc k taken upwards (or downwards), unpacked.
  void unpack(const Metric& m, uint32_t k, bool upwards, std::vector<uint32_t>& path,
              std::vector<std::pair<uint32_t, bool>>& stack) const;

  const Network& net_;
  std::vector<uint32_t> rank_;    // per network edge: its place in the elimination order
  std::vector<uint32_t> order_;   // per rank: the network edge
  std::vector<uint32_t> begin_;   // per rank + 1: its upward arcs in head_
  std::vector<uint32_t> head_;    // upward arcs' higher ranks, ascending per node
  std::vector<uint32_t> tail_;    // upward arcs' lower ranks
  std::vector<uint32_t> parent_;  // per rank: the lowest upward neighbour (kNone: a root)
  uint32_t height_ = 0;
};

}  // namespace lpsim

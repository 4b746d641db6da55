#pragma once
// Vehicles waiting to be inserted: one first-in-first-out queue per edge, of departures and of teleported
// vehicles re-entering. Each step the head of every non-empty queue is offered to the backend as one batch
// (kernels/insert_vehicle.hpp), and what it inserted leaves the queues.
#include <cstdint>
#include <vector>

#include "kernels/insert_vehicle.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Vehicle indices stay below this bit (kInsertTeleported is the one above it).
constexpr uint32_t kMaxVehicles = 0x40000000u;

/// The queue entry of vehicle v, departing or re-entering after a teleport.
inline uint32_t queue_entry(uint32_t v, bool teleported) { return v | (teleported ? kInsertTeleported : 0u); }

/// Per vehicle, what a re-entering one asks for: its route position, lane (-1: any best lane), front position
/// (-1: the lane start) and speed (the trip ledger's account).
struct ReentryWants {
  const uint32_t* route_pos;
  const int32_t* lane;
  const float* pos;
  const float* speed;
};

class InsertionQueues {
 public:
  explicit InsertionQueues(const Network& net);

  /// Whether vehicles can enter at edge e at all (it has car lanes).
  bool has_lanes(uint32_t e) const { return queue_[e].lanes > 0; }
  /// A departure joins the tail of edge e's queue.
  void push_back(uint32_t e, uint32_t entry);
  /// A teleported vehicle goes first: it has been on the road already.
  void push_front(uint32_t e, uint32_t entry);
  /// Whether `entry` (queue_entry) waits in edge e's queue.
  bool holds(uint32_t e, uint32_t entry) const;
  /// Takes `entry` out of edge e's queue, keeping the order of the others; false when it was not there.
  bool remove(uint32_t e, uint32_t entry);
  /// Vehicles queued on all edges.
  uint64_t waiting() const { return waiting_; }
  /// Vehicles queued on edge e.
  uint32_t waiting_at(uint32_t e) const {
    return static_cast<uint32_t>(queue_[e].entries.size()) - queue_[e].head;
  }

  /// The batch of this step: up to kMaxInsertPerEdge heads of each queue, edges ascending, with the route
  /// position each enters at (0 for a departure) and, for a re-entering vehicle, the lane, position and
  /// speed it asks for, all from `wants`. Its output arrays are sized for the backend to fill.
  const InsertBatch& offer(const ReentryWants& wants);
  uint32_t offered_entries() const { return static_cast<uint32_t>(entry_.size()); }
  /// After the backend filled the batch: calls inserted(i) for each inserted entry i of the batch, in batch
  /// order, and removes those entries from their queues.
  template <class Inserted>
  void take_inserted(Inserted&& inserted);
  /// Removes the departures (not re-entering vehicles) for which drop(v) is true from every queue, keeping
  /// the order of the others; edges ascending, each queue from its head.
  template <class Drop>
  void drop_departures(Drop&& drop);

  /// f(edge, first, last) for each non-empty queue, edges ascending: its entries [first, last) from its head.
  template <class F>
  void for_each_queue(F&& f) const {
    for (const uint32_t e : queued_edges_) {
      const EdgeQueue& q = queue_[e];
      f(e, q.entries.data() + q.head, q.entries.data() + q.entries.size());
    }
  }

  /// The queues' entries, of the queued edges only (StateOut, StateIn: engine/state_archive.hpp).
  template <class Out>
  void save_state(Out& a) const {
    std::vector<uint32_t> edges = queued_edges_, counts, entries;
    for (const uint32_t e : queued_edges_) {
      const EdgeQueue& q = queue_[e];
      counts.push_back(static_cast<uint32_t>(q.entries.size()) - q.head);
      entries.insert(entries.end(), q.entries.begin() + q.head, q.entries.end());
    }
    a(edges);
    a(counts);
    a(entries);
  }
  template <class In>
  void load_state(In& a) {
    std::vector<uint32_t> edges, counts, entries;
    a(edges);
    a(counts);
    a(entries);
    if (counts.size() != edges.size()) a.fail("insertion queues: a count per queued edge");
    for (const uint32_t e : queued_edges_) queue_[e].entries.clear(), queue_[e].head = 0;
    queued_edges_.clear();
    waiting_ = 0;
    size_t at = 0;
    for (size_t i = 0; i < edges.size(); ++i) {
      if (edges[i] >= queue_.size() || at + counts[i] > entries.size() || (i > 0 && edges[i] <= edges[i - 1]))
        a.fail("insertion queues: an edge or a count out of range");
      EdgeQueue& q = queue_[edges[i]];
      q.entries.assign(entries.begin() + static_cast<std::ptrdiff_t>(at),
                       entries.begin() + static_cast<std::ptrdiff_t>(at + counts[i]));
      at += counts[i];
      waiting_ += counts[i];
      queued_edges_.push_back(edges[i]);
    }
  }

 private:
  struct EdgeQueue {
    std::vector<uint32_t> entries;  // those before head have been inserted
    uint32_t head = 0;
    uint32_t lanes = 0;  // the edge's car lanes (none: its departures are removed)
  };
  std::vector<EdgeQueue> queue_;        // per edge
  std::vector<uint32_t> queued_edges_;  // edges with a non-empty queue, ascending
  uint64_t waiting_ = 0;
  // The batch (InsertBatch's arrays).
  std::vector<uint32_t> edge_, begin_, entry_, rp_, inserted_;
  std::vector<float> enter_speed_, enter_pos_;
  std::vector<int32_t> enter_lane_;
  std::vector<int32_t> lane_;
  std::vector<float> pos_, speed_;
  InsertBatch batch_{};
  std::vector<uint32_t> still_;  // the edges still queued, built by take_inserted and drop_departures

  // After edge e's queue changed: e stays listed while it has entries; an empty queue is reset.
  void keep_listed_if_waiting(EdgeQueue& q, uint32_t e) {
    if (q.head < q.entries.size()) {
      still_.push_back(e);
    } else {
      q.entries.clear();
      q.head = 0;
    }
  }
};

template <class Inserted>
void InsertionQueues::take_inserted(Inserted&& inserted) {
  still_.clear();
  for (uint32_t slot = 0; slot < batch_.num_slots; ++slot) {
    const uint32_t e = edge_[slot];
    if (inserted_[slot] == 0) {  // as it was: still waiting (most queues, on a congested road)
      still_.push_back(e);
      continue;
    }
    EdgeQueue& q = queue_[e];
    // The offered entries that stay move up behind the inserted ones, keeping their order, and the head
    // passes the inserted ones.
    const uint32_t offered = begin_[slot + 1] - begin_[slot];
    size_t keep = q.head + offered;
    for (uint32_t k = offered; k-- > 0;) {
      const uint32_t i = begin_[slot] + k;
      if (lane_[i] >= 0) continue;
      q.entries[--keep] = q.entries[q.head + k];
    }
    for (uint32_t i = begin_[slot]; i < begin_[slot + 1]; ++i) {
      if (lane_[i] < 0) continue;
      inserted(i);
      --waiting_;
    }
    q.head = static_cast<uint32_t>(keep);
    keep_listed_if_waiting(q, e);
  }
  queued_edges_.swap(still_);
}

template <class Drop>
void InsertionQueues::drop_departures(Drop&& drop) {
  still_.clear();
  for (const uint32_t e : queued_edges_) {
    EdgeQueue& q = queue_[e];
    size_t keep = q.head;
    for (size_t i = q.head; i < q.entries.size(); ++i) {
      const uint32_t entry = q.entries[i];
      if (!(entry & kInsertTeleported) && drop(entry)) {
        --waiting_;
        continue;
      }
      q.entries[keep++] = entry;
    }
    q.entries.resize(keep);
    keep_listed_if_waiting(q, e);
  }
  queued_edges_.swap(still_);
}

}  // namespace lpsim

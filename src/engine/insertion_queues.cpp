#include "engine/insertion_queues.hpp"

#include <algorithm>

namespace lpsim {

InsertionQueues::InsertionQueues(const Network& net) : queue_(net.num_edges()) {
  for (uint32_t e = 0; e < net.num_edges(); ++e) queue_[e].lanes = net.edge_num_lanes[e];
}

void InsertionQueues::push_back(uint32_t e, uint32_t entry) {
  EdgeQueue& q = queue_[e];
  if (q.head == q.entries.size()) {
    q.entries.clear();
    q.head = 0;
    queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), e), e);
  }
  q.entries.push_back(entry);
  ++waiting_;
}

void InsertionQueues::push_front(uint32_t e, uint32_t entry) {
  EdgeQueue& q = queue_[e];
  q.entries.insert(q.entries.begin() + q.head, entry);
  if (q.head + 1 == q.entries.size())
    queued_edges_.insert(std::lower_bound(queued_edges_.begin(), queued_edges_.end(), e), e);
  ++waiting_;
}

// Up to kMaxInsertPerEdge entries of each queue, from its head: the insertion tries them in order, and as
// SUMO any of them may go in while one before it waits.
const InsertBatch& InsertionQueues::offer(const ReentryWants& wants) {
  edge_.clear();
  begin_.assign(1, 0);
  entry_.clear();
  rp_.clear();
  enter_speed_.clear();
  enter_lane_.clear();
  enter_pos_.clear();
  for (const uint32_t e : queued_edges_) {
    const EdgeQueue& q = queue_[e];
    const size_t end = std::min<size_t>(q.entries.size(), q.head + kMaxInsertPerEdge);
    for (size_t i = q.head; i < end; ++i) {
      const uint32_t offered = q.entries[i];
      entry_.push_back(offered);
      const bool reentry = (offered & kInsertTeleported) != 0;
      const uint32_t v = offered & ~kInsertTeleported;
      rp_.push_back(reentry ? wants.route_pos[v] : 0u);
      enter_speed_.push_back(reentry ? wants.speed[v] : 0.0f);
      enter_lane_.push_back(reentry ? wants.lane[v] : -1);
      enter_pos_.push_back(reentry ? wants.pos[v] : -1.0f);
    }
    edge_.push_back(e);
    begin_.push_back(static_cast<uint32_t>(entry_.size()));
  }
  const size_t entries = entry_.size();
  inserted_.assign(edge_.size(), 0);
  lane_.resize(entries);
  pos_.resize(entries);
  speed_.resize(entries);
  batch_ = InsertBatch{static_cast<uint32_t>(edge_.size()),
                       edge_.data(),
                       begin_.data(),
                       entry_.data(),
                       rp_.data(),
                       enter_speed_.data(),
                       enter_lane_.data(),
                       enter_pos_.data(),
                       inserted_.data(),
                       lane_.data(),
                       pos_.data(),
                       speed_.data()};
  return batch_;
}

bool InsertionQueues::holds(uint32_t e, uint32_t entry) const {
  const EdgeQueue& q = queue_[e];
  return std::find(q.entries.begin() + q.head, q.entries.end(), entry) != q.entries.end();
}

bool InsertionQueues::remove(uint32_t e, uint32_t entry) {
  EdgeQueue& q = queue_[e];
  const auto it = std::find(q.entries.begin() + q.head, q.entries.end(), entry);
  if (it == q.entries.end()) return false;
  q.entries.erase(it);
  --waiting_;
  if (q.head == q.entries.size()) {
    q.entries.clear();
    q.head = 0;
    queued_edges_.erase(std::find(queued_edges_.begin(), queued_edges_.end(), e));
  }
  return true;
}

}  // namespace lpsim

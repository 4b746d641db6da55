#pragma once
// Slots of the vehicles on the road (VehicleView's columns). The lowest free slot is taken first, so the
// slots in use stay dense (a pass over them reads the columns nearly contiguously) and the same sequence of
// takes and releases gives the same slots on every backend.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace lpsim {

class SlotPool {
 public:
  uint32_t take() {
    if (free_.empty()) {
      peak_ = std::max(peak_, used_ + 1);
      return used_++;
    }
    std::pop_heap(free_.begin(), free_.end(), std::greater<uint32_t>());
    const uint32_t slot = free_.back();
    free_.pop_back();
    return slot;
  }
  void release(uint32_t slot) {
    free_.push_back(slot);
    std::push_heap(free_.begin(), free_.end(), std::greater<uint32_t>());
  }
  /// Slots 0..n-1 in use, every other one free (after the slots in use were renumbered densely).
  void reset(uint32_t n) {
    free_.clear();
    used_ = n;
  }
  template <class A>
  void visit_state(A& a) {
    a(free_);
    a(used_);
    a(peak_);
  }
  /// Slots handed out at least once since the last reset: the length the slot columns need now.
  uint32_t size() const { return used_; }
  /// The most slots size() ever reached: the length the slot columns grew to.
  uint32_t peak() const { return peak_; }

 private:
  std::vector<uint32_t> free_;  // a heap: the lowest on top
  uint32_t used_ = 0, peak_ = 0;
};

}  // namespace lpsim

#pragma once
// Slots of the vehicles on the road (VehicleView's columns). The lowest free slot is taken first, so the
// slots in use stay dense (a pass over them reads the columns nearly contiguously) and the same sequence of
// takes and releases gives the same slots on every backend.
#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

namespace lpsim {

class SlotPool {
 public:
  uint32_t take() {
    if (free_.empty()) return used_++;
    const uint32_t slot = free_.top();
    free_.pop();
    return slot;
  }
  void release(uint32_t slot) { free_.push(slot); }
  /// Slots handed out at least once: the length the slot columns need.
  uint32_t size() const { return used_; }

 private:
  std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<uint32_t>> free_;
  uint32_t used_ = 0;
};

}  // namespace lpsim

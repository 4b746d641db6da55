#pragma once
// A run's saved state (Simulation::save_state) taken apart: the parts that saved it, and each part's own
// state as its clock and each piece of the engine's state as a section of bytes of its own, so that a piece
// can be taken whole without reading its fields (a partitioned run's state re-cut for other parts reads only
// the pieces that differ by part). Simulation::save_state and load_state go through these lists.
#include <cstdint>
#include <vector>

namespace lpsim {

enum StateSection : int {
  kSectionBooks,         // HostBooks: slots, insertion queues, trip ledger, counts, schedule, retiring slots
  kSectionRoutes,        // the trip table's added trips and replaced routes (TripTable::visit_routes)
  kSectionLaneCounters,  // the lane counters drained so far
  kSectionRerouting,     // whether the run has a rerouting device, and its state
  kSectionLink,          // what the boundary link carries between steps
  kSectionBackend,       // the backend's own state (backends/backend_state.hpp)
  kNumStateSections
};

struct SavedPartState {
  int64_t time_ms = 0;
  uint32_t step = 0;
  int32_t map = 0;  // the lane map the state is in
  std::vector<uint8_t> sections[kNumStateSections];

  template <class A>
  void visit_state(A& a) {
    a(time_ms);
    a(step);
    a(map);
    for (std::vector<uint8_t>& s : sections) a.raw(s);
  }
};

/// The parts that saved a state, by the part each edge's lanes belong to (none: a run of one part), and each
/// part's state (a SavedPartState's bytes) in part order.
struct SavedState {
  std::vector<int32_t> edge_part;
  std::vector<std::vector<uint8_t>> parts;

  template <class A>
  void visit_state(A& a) {
    a(edge_part);
    auto n = static_cast<uint32_t>(parts.size());
    a(n);
    if constexpr (A::kReads) {
      if (n == 0) a.fail("a state of no part");
      parts.resize(n);
    }
    for (std::vector<uint8_t>& p : parts) a.raw(p);
  }
};

}  // namespace lpsim

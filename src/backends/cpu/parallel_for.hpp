#pragma once
// The CPU backend's parallel loop: a fixed team of threads that split an index range into equal
// contiguous chunks. Idle workers sleep on a condition variable instead of spinning, so a run's CPU time
// is its work (OpenMP's default spin-waiting between the step's passes doubled it on a shared machine).
// Which thread runs which index never affects results: every pass writes only its own vehicle's entries
// and order-independent integer atomics.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace lpsim {

class ParallelFor {
 public:
  explicit ParallelFor(int threads);
  ~ParallelFor();
  ParallelFor(const ParallelFor&) = delete;
  ParallelFor& operator=(const ParallelFor&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  /// Calls body(begin, end) on contiguous sub-ranges covering [0, n), one per thread of the team; returns
  /// when all are done (a range, not an index, per call: one indirect call per thread, not per vehicle).
  /// Ranges smaller than `serial_below` run on the calling thread as one call.
  using RangeBody = std::function<void(int64_t begin, int64_t end)>;
  void run(int64_t n, const RangeBody& body, int64_t serial_below = 0);

 private:
  void work(int index);
  void chunk(int index, int64_t n, const RangeBody& body) const;

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  uint64_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
  int64_t n_ = 0;
  const RangeBody* body_ = nullptr;
};

}  // namespace lpsim

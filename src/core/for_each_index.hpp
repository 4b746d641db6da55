#pragma once
// The one loop over independent indices on a few threads of the routers and the assignment: workers claim
// indices in chunks from a shared counter, each with its own scratch state, so that the result at an index
// depends only on that index, never on the thread that computed it.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace lpsim {

/// Calls job(state, k) for every k in [0, n) on `threads` threads (0: all cores; never more than there are
/// chunks), each worker with its own `state` from make_state(); indices are claimed `chunk` at a time.
template <class MakeState, class Job>
void for_each_index(size_t n, int threads, MakeState&& make_state, Job&& job, size_t chunk = 1) {
  std::atomic<size_t> next{0};
  auto worker = [&] {
    auto state = make_state();
    for (size_t k; (k = next.fetch_add(chunk, std::memory_order_relaxed)) < n;)
      for (size_t i = k; i < std::min(n, k + chunk); ++i) job(state, i);
  };
  size_t count =
      threads > 0 ? static_cast<size_t>(threads) : std::max(1u, std::thread::hardware_concurrency());
  count = std::min(count, std::max<size_t>(1, (n + chunk - 1) / chunk));
  if (count == 1) return worker();
  std::vector<std::thread> pool;
  for (size_t t = 0; t < count; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
}

}  // namespace lpsim

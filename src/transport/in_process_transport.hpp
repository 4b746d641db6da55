#pragma once
// K ranks in one process, each stepped by its own thread: a fabric of mailboxes the endpoints post to and
// take from. A rank that fails (its thread throws) marks the fabric broken, so the others stop at their next
// round with an error naming it instead of waiting out the timeout. A take waits for its buffer spinning for
// a few tens of microseconds, then asleep: a step's rounds mostly come that soon, and waking a sleeping
// thread costs about as long again, while a peer that stopped costs no more than that spin.
#include <atomic>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>

#include "transport/transport.hpp"

namespace lpsim {

class InProcessFabric {
 public:
  /// `size` ranks; a round waits at most timeout_s seconds for a peer's buffer.
  InProcessFabric(int size, double timeout_s);
  int size() const { return size_; }

  /// The endpoint of `rank`, to be used by one thread.
  std::unique_ptr<Transport> endpoint(int rank);

  /// Marks rank `rank` as failed with `reason`: every later or waiting take on the fabric throws.
  void fail(int rank, const std::string& reason);

  void post(int from, int to, uint64_t round, Bytes data);
  Bytes take(int to, int from, uint64_t round, const std::string& what);

 private:
  int size_;
  double timeout_s_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::map<std::tuple<int, int, uint64_t>, Bytes> mail_;  // (to, from, round) -> data
  std::string failure_;
  std::atomic<uint64_t> posts_{0};  // buffers posted and failures marked so far: what a waiting take watches
};

}  // namespace lpsim

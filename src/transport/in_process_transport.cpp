#include "transport/in_process_transport.hpp"

#include <chrono>
#include <thread>

namespace lpsim {

namespace {

// How long a take spins for its buffer before it sleeps: about what waking a sleeping thread costs here, so
// that spinning costs at most what sleeping would.
constexpr std::chrono::microseconds kSpin{50};

class InProcessEndpoint : public Transport {
 public:
  InProcessEndpoint(InProcessFabric& fabric, int rank) : fabric_(fabric), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return fabric_.size(); }

  std::vector<Bytes> exchange(const std::vector<int>& to, const std::vector<Bytes>& send,
                              const std::vector<int>& from, const std::string& what) override {
    const uint64_t round = round_++;
    for (size_t i = 0; i < to.size(); ++i) fabric_.post(rank_, to[i], round, send[i]);
    std::vector<Bytes> got;
    got.reserve(from.size());
    for (int f : from) got.push_back(fabric_.take(rank_, f, round, what));
    return got;
  }

 private:
  InProcessFabric& fabric_;
  int rank_;
  uint64_t round_ = 0;
};

}  // namespace

InProcessFabric::InProcessFabric(int size, double timeout_s) : size_(size), timeout_s_(timeout_s) {}

std::unique_ptr<Transport> InProcessFabric::endpoint(int rank) {
  return std::make_unique<InProcessEndpoint>(*this, rank);
}

void InProcessFabric::fail(int rank, const std::string& reason) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (failure_.empty()) failure_ = "rank " + std::to_string(rank) + " failed: " + reason;
    posts_.fetch_add(1, std::memory_order_release);
  }
  arrived_.notify_all();
}

void InProcessFabric::post(int from, int to, uint64_t round, Bytes data) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mail_[{to, from, round}] = std::move(data);
    posts_.fetch_add(1, std::memory_order_release);
  }
  arrived_.notify_all();
}

Bytes InProcessFabric::take(int to, int from, uint64_t round, const std::string& what) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto key = std::make_tuple(to, from, round);
  const auto now = std::chrono::steady_clock::now();
  const auto deadline = now + std::chrono::duration<double>(timeout_s_);
  const auto spin_until = now + kSpin;
  while (mail_.find(key) == mail_.end()) {
    if (!failure_.empty())
      throw TransportError("rank " + std::to_string(to) + ", round '" + what + "': " + failure_);
    if (std::chrono::steady_clock::now() < spin_until) {
      // Spinning, the lock is released: the peer posts under it. Any post ends the spin, to look again.
      const uint64_t seen = posts_.load(std::memory_order_acquire);
      lock.unlock();
      while (posts_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < spin_until)
        std::this_thread::yield();
      lock.lock();
      continue;
    }
    if (arrived_.wait_until(lock, deadline) == std::cv_status::timeout && mail_.find(key) == mail_.end())
      throw TransportError("rank " + std::to_string(to) + ": no data from rank " + std::to_string(from) +
                           " in round '" + what + "' (#" + std::to_string(round) + ") within " +
                           seconds_text(timeout_s_) + " s: has it stopped?");
  }
  auto it = mail_.find(key);
  Bytes data = std::move(it->second);
  mail_.erase(it);
  return data;
}

}  // namespace lpsim

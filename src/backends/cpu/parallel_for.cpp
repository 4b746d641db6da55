#include "backends/cpu/parallel_for.hpp"

namespace lpsim {

ParallelFor::ParallelFor(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

ParallelFor::~ParallelFor() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (auto& w : workers_) w.join();
}

void ParallelFor::chunk(int index, int64_t n, const RangeBody& body) const {
  const int64_t t = threads();
  const int64_t begin = n * index / t, end = n * (index + 1) / t;
  if (begin < end) body(begin, end);
}

void ParallelFor::run(int64_t n, const RangeBody& body, int64_t serial_below) {
  if (workers_.empty() || n < serial_below) {
    if (n > 0) body(0, n);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    n_ = n;
    body_ = &body;
    pending_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  start_.notify_all();
  chunk(0, n, body);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return pending_ == 0; });
}

void ParallelFor::work(int index) {
  uint64_t seen = 0;
  for (;;) {
    int64_t n;
    const RangeBody* body;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      n = n_;
      body = body_;
    }
    chunk(index, n, *body);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }
}

}  // namespace lpsim

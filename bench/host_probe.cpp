// Host probe for the benchmarks: how fast this (shared, virtual) machine is right now, in three numbers
// that separate a slower clock from a slower memory system. SUMO's CPU time per vehicle-update varies
// twofold between sessions while LPSim's varies far less; recording these beside each benchmark says
// whether a session's host computes slower, or only reaches its caches and memory slower.
//
//   compute: ns per step of a dependent floating-point chain (tracks the core clock);
//   chase N: ns per load of a random pointer chase through N bytes of cache lines (a miss per load in every
//   cache too small or too contended to hold them: 512 KiB sits in L2, 4 and 16 MiB in an L3 of 32 MiB if
//   this VM gets its share of it, 256 MiB in DRAM).
//
// Build: g++ -O2 -std=c++20 bench/host_probe.cpp -o host_probe (bench/lib.sh does this on first use).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A dependent multiply-add chain: each step waits for the previous one, so its time is the latency of
// two floating-point operations, a fixed number of core cycles.
double compute_ns_per_step() {
  const int64_t steps = 100'000'000;
  volatile double seed = 1.0000001;
  double x = seed, a = 0.9999999, b = 1e-9;
  const auto t0 = Clock::now();
  for (int64_t i = 0; i < steps; ++i) x = x * a + b;
  const double s = seconds_since(t0);
  volatile double sink = x;
  (void)sink;
  return s * 1e9 / static_cast<double>(steps);
}

// One random cycle through cache lines (Sattolo's shuffle), so that every load depends on the previous one,
// touches a new line, and the hardware prefetchers cannot guess the next address.
double chase_ns_per_load(size_t kib, size_t loads) {
  struct alignas(64) Line {
    uint32_t next;
  };
  const size_t n = kib * (size_t{1} << 10) / sizeof(Line);
  std::vector<Line> lines(n);
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  uint64_t x = 0x9E3779B97F4A7C15ull;  // xorshift64: the shuffle's quality barely matters, its speed does
  for (size_t i = n - 1; i > 0; --i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    std::swap(order[i], order[x % i]);
  }
  for (size_t i = 0; i < n; ++i) lines[order[i]].next = order[(i + 1) % n];
  uint32_t at = 0;
  for (size_t i = 0; i < n; ++i) at = lines[at].next;  // warm the caches and the page tables
  const auto t0 = Clock::now();
  for (size_t i = 0; i < loads; ++i) at = lines[at].next;
  const double s = seconds_since(t0);
  volatile uint32_t sink = at;
  (void)sink;
  return s * 1e9 / static_cast<double>(loads);
}

}  // namespace

int main() {
  const double compute = compute_ns_per_step();
  const double l2 = chase_ns_per_load(512, 20'000'000);
  const double l3 = chase_ns_per_load(4096, 10'000'000);
  const double l3_full = chase_ns_per_load(16384, 4'000'000);
  const double dram = chase_ns_per_load(262144, 2'000'000);
  std::printf("compute %.2f ns/step, chase 512 KiB %.1f ns, 4 MiB %.1f ns, 16 MiB %.1f ns, 256 MiB %.1f ns\n",
              compute, l2, l3, l3_full, dram);
  return 0;
}

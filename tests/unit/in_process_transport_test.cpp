// The in-process transport: K ranks as threads exchange rounds intact and in order; a rank that stops
// answering is an error naming it within the timeout; a rank that fails stops the others at once; ranks of
// different builds refuse to go on.
#include "transport/in_process_transport.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace lpsim {
namespace {

Bytes message(int from, int to, int round) {
  const std::string s = std::to_string(from) + ">" + std::to_string(to) + "@" + std::to_string(round);
  return Bytes(s.begin(), s.end());
}

// Runs body(rank, transport) on `size` threads; returns each rank's error text ("" if none).
template <class Body>
std::vector<std::string> run_ranks(InProcessFabric& fabric, Body body) {
  std::vector<std::string> errors(static_cast<size_t>(fabric.size()));
  std::vector<std::thread> threads;
  for (int r = 0; r < fabric.size(); ++r)
    threads.emplace_back([&, r] {
      auto t = fabric.endpoint(r);
      try {
        body(r, *t);
      } catch (const std::exception& e) {
        errors[static_cast<size_t>(r)] = e.what();
        fabric.fail(r, e.what());
      }
    });
  for (auto& t : threads) t.join();
  return errors;
}

TEST(InProcessTransportTest, RingRoundsAndGatherArriveIntact) {
  InProcessFabric fabric(4, 10.0);
  const auto errors = run_ranks(fabric, [](int rank, Transport& t) {
    t.check_same_build("b");
    const int size = t.size(), next = (rank + 1) % size, prev = (rank + size - 1) % size;
    for (int round = 0; round < 100; ++round) {
      const auto got = t.exchange({next, prev}, {message(rank, next, round), message(rank, prev, round)},
                                  {prev, next}, "ring");
      ASSERT_EQ(got[0], message(prev, rank, round));
      ASSERT_EQ(got[1], message(next, rank, round));
    }
    const auto all = t.allgather(message(rank, -1, 0), "gather");
    for (int r = 0; r < size; ++r) ASSERT_EQ(all[static_cast<size_t>(r)], message(r, -1, 0));
  });
  for (const auto& e : errors) EXPECT_EQ(e, "");
}

TEST(InProcessTransportTest, ASilentRankIsAnErrorWithinTheTimeout) {
  InProcessFabric fabric(2, 0.3);
  const auto t0 = std::chrono::steady_clock::now();
  const auto errors = run_ranks(fabric, [](int rank, Transport& t) {
    if (rank == 1) return;  // never answers
    t.exchange({1}, {Bytes{1}}, {1}, "plan");
  });
  EXPECT_NE(errors[0].find("rank 0: no data from rank 1 in round 'plan' (#0) within"), std::string::npos)
      << errors[0];
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));
}

TEST(InProcessTransportTest, AFailedRankStopsTheOthers) {
  InProcessFabric fabric(3, 60.0);
  const auto t0 = std::chrono::steady_clock::now();
  const auto errors = run_ranks(fabric, [](int rank, Transport& t) {
    if (rank == 2) throw std::runtime_error("bad lane");
    t.exchange({2}, {Bytes{1}}, {2}, "commit");
  });
  EXPECT_NE(errors[0].find("rank 2 failed: bad lane"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("rank 2 failed: bad lane"), std::string::npos) << errors[1];
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));  // not the 60 s timeout
}

TEST(InProcessTransportTest, RanksOfDifferentBuildsRefuse) {
  InProcessFabric fabric(2, 10.0);
  const auto errors =
      run_ranks(fabric, [](int rank, Transport& t) { t.check_same_build(rank == 0 ? "abc" : "abd"); });
  EXPECT_NE(errors[0].find("rank 1 runs build 'abd', rank 0 build 'abc'"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("rank 0 runs build 'abc', rank 1 build 'abd'"), std::string::npos) << errors[1];
}

}  // namespace
}  // namespace lpsim

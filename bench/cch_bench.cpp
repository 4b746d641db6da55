// The contraction hierarchy's router (src/net/cch_router.hpp) on one network, side by side with the Dijkstra
// router it must equal: ordering and contraction time, customization time, random origin-destination queries
// per second on 1..T threads, Dijkstra's queries per second on a sample, and that sample's costs compared.
// Built as lpsim_cch_bench; bench/cch_bench.sh runs it on the Bay Area network.
//
//   lpsim_cch_bench [--queries N] [--dijkstra N] [--threads T] [--seed S] SCENARIO OPTIONS...
//
// SCENARIO OPTIONS are those of `lpsim info` (-n net.xml, -c cfg, --lpsim-nodes/--lpsim-edges, a snapshot).
// Origins and destinations are drawn uniformly among the edges passenger cars may use.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "app/scenario_args.hpp"
#include "core/error.hpp"
#include "core/vclass.hpp"
#include "net/cch_router.hpp"
#include "net/router.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lpsim;
  int queries = 200000, dijkstra = 2000, threads = 2;
  uint32_t seed = 1;
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "cch_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::atoi(argv[++i]);
    };
    if (a == "--queries")
      queries = value();
    else if (a == "--dijkstra")
      dijkstra = value();
    else if (a == "--threads")
      threads = value();
    else if (a == "--seed")
      seed = static_cast<uint32_t>(value());
    else
      args.push_back(a);
  }
  try {
    const Scenario sc = scenario_from_args(args, nullptr, CliCommand::Info);
    const Network& net = sc.network;
    std::vector<uint32_t> usable;
    for (uint32_t e = 0; e < net.num_edges(); ++e)
      if (!net.edge_is_internal[e] && (net.edge_permissions[e] & kVClassPassenger) != 0) usable.push_back(e);
    std::printf("network: %u edges (%zu usable by passenger cars), %zu moves\n", net.num_edges(),
                usable.size(), net.edge_succ.size());

    const Router router(net);
    auto t0 = Clock::now();
    const CchRouter cch(net);
    const double preprocessing = seconds_since(t0);
    t0 = Clock::now();
    const CchRouter::Metric metric = cch.customize(router, kVClassPassenger);
    const double customization = seconds_since(t0);
    std::printf("ordering and contraction: %.2f s (%u arcs with shortcuts, elimination tree height %u)\n",
                preprocessing, cch.num_arcs(), cch.elimination_tree_height());
    std::printf("customization (passenger): %.3f s\n", customization);

    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, usable.size() - 1);
    std::vector<std::pair<uint32_t, uint32_t>> pairs(static_cast<size_t>(queries));
    for (auto& p : pairs) p = {usable[pick(rng)], usable[pick(rng)]};

    for (int t = 1; t <= threads; t *= 2) {
      std::vector<std::thread> pool;
      std::vector<uint64_t> found(static_cast<size_t>(t), 0);
      t0 = Clock::now();
      for (int k = 0; k < t; ++k)
        pool.emplace_back([&, k] {
          CchRouter::Workspace ws(cch);
          for (size_t q = static_cast<size_t>(k); q < pairs.size(); q += static_cast<size_t>(t))
            found[static_cast<size_t>(k)] +=
                cch.route(metric, pairs[q].first, pairs[q].second, ws).empty() ? 0 : 1;
        });
      for (auto& th : pool) th.join();
      const double s = seconds_since(t0);
      uint64_t with_path = 0;
      for (const uint64_t f : found) with_path += f;
      std::printf("CCH, %d thread%s: %d queries (%llu with a path, paths unpacked) in %.3f s: %.0f per s\n",
                  t, t > 1 ? "s" : "", queries, static_cast<unsigned long long>(with_path), s, queries / s);
    }

    const size_t sample = std::min(pairs.size(), static_cast<size_t>(dijkstra));
    std::vector<RouteRequest> requests(sample);
    for (size_t q = 0; q < sample; ++q) {
      requests[q].origins = {pairs[q].first};
      requests[q].destinations = {pairs[q].second};
      requests[q].vclass = kVClassPassenger;
    }
    t0 = Clock::now();
    const auto reference = router.route_all(requests, 1);
    const double dijkstra_s = seconds_since(t0);
    CchRouter::Workspace ws(cch);
    size_t equal = 0, differ = 0;
    double worst = 0;
    for (size_t q = 0; q < sample; ++q) {
      double cost = 0;
      const std::vector<uint32_t> path = cch.route(metric, pairs[q].first, pairs[q].second, ws, &cost);
      if (path.empty() != reference[q].empty()) {
        ++differ;
        continue;
      }
      if (path.empty()) {
        ++equal;
        continue;
      }
      const double expected = router.cost(reference[q]);
      const double rel = std::fabs(router.cost(path) - expected) / std::max(1.0, expected);
      worst = std::max(worst, rel);
      ++(rel <= 1e-9 ? equal : differ);
    }
    std::printf("Dijkstra, 1 thread: %zu queries in %.3f s: %.0f per s\n", sample, dijkstra_s,
                static_cast<double>(sample) / dijkstra_s);
    std::printf("sample: %zu of %zu with Dijkstra's cost (largest relative difference %.1e)\n", equal, sample,
                worst);
    return differ == 0 ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "cch_bench: %s\n", e.what());
    return 2;
  }
}

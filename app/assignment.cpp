#include "app/assignment.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

#include "app/part_launcher.hpp"
#include "converters/mean_data_writer.hpp"
#include "core/error.hpp"
#include "core/for_each_index.hpp"
#include "demand/demand_draws.hpp"
#include "demand/trip_routes.hpp"
#include "demand/trip_table.hpp"
#include "kernels/rng.hpp"
#include "transport/byte_buffer.hpp"

namespace lpsim {
namespace {

constexpr double kTimeSlack = 1e-6;  // s: float noise in comparisons of step times
constexpr double kMinSamples = 1.0;  // s: duaIterate's edgeData minSamples
constexpr uint64_t kDrawRouteChoice = 0x8000000000000004ull;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

// The trips as routed vehicles: a trip's routing at insertion (SUMO's rerouting device for trips) is the
// assignment's to do; vehicles equipped with the device by options or params keep it.
Demand without_insertion_routing(Demand d) {
  bool any = false;
  for (uint8_t& flags : d.rerouting) {
    if (!(flags & kRerouteEquipped)) flags = 0;
    any = any || flags != 0;
  }
  if (!any) d.rerouting.clear();  // no device: the runs sample no speeds for it
  return d;
}

}  // namespace

GapSums gap_sums(const Router& router, const Demand& d, const IntervalTravelTimes& times,
                 const std::vector<double>& best_cost) {
  GapSums g;
  for (uint32_t v = 0; v < d.size(); ++v) {
    if (!std::isfinite(best_cost[v])) continue;
    const std::span<const uint32_t> route(d.route_edges.data() + d.route_begin[v], d.route_length[v]);
    const double used = router.timed_cost(route, d.depart[v], times);
    if (!std::isfinite(used)) continue;
    g.route_cost_sum += used;
    // The hierarchy's best route is found on the depart interval's times alone: costed time-dependently it
    // may cost more than the route driven, which is then the best response known.
    g.best_cost_sum += std::min(best_cost[v], used);
    ++g.vehicles;
  }
  return g;
}

GapSums relative_gap(const Network& net, const Router& router, const Demand& d,
                     const IntervalTravelTimes& times, int threads) {
  std::vector<RouteRequest> requests(d.size());
  for (uint32_t v = 0; v < d.size(); ++v) requests[v] = trip_request(d, net, v);
  std::vector<double> best_cost;
  router.route_timed(requests, d.depart, times, threads, &best_cost);
  return gap_sums(router, d, times, best_cost);
}

Assignment::Assignment(const Network& net, Demand demand, SimulationOptions options, const AssignSpec& spec,
                       double begin, double end, int threads, bool hierarchy)
    : net_(net),
      base_(without_insertion_routing(std::move(demand))),
      assigned_(base_),
      options_(options),
      spec_(spec),
      begin_(begin),
      end_(end),
      threads_(threads),
      router_(net, options.rerouting.minor_penalty),
      interval_router_(net, options.rerouting.minor_penalty) {
  if (hierarchy) hierarchy_ = std::make_unique<CchRouter>(net);
  options_.lane_counters = true;
  choice_.method = spec.logit ? RouteChoiceOptions::Method::Logit : RouteChoiceOptions::Method::Gawron;
  choice_.gawron_beta = spec.gawron_beta;
  choice_.gawron_a = spec.gawron_a;
  choice_.logit_beta = spec.logit_beta;
  choice_.logit_gamma = spec.logit_gamma;
  choice_.logit_theta = spec.logit_theta;
  choice_.max_alternatives = static_cast<uint32_t>(std::max(1, spec.max_alternatives));
  choice_.keep_all_routes = spec.keep_all_routes;
  requests_.resize(base_.size());
  for (uint32_t v = 0; v < base_.size(); ++v)
    if (end < 0 || base_.depart[v] <= end) requests_[v] = trip_request(base_, net, v);
  times_.begin = begin;
  times_.period = spec.aggregation;
  times_.resize(net.num_edges(), 1);  // free flow
  alternatives_.resize(base_.size());
}

void Assignment::route_all() {
  if (!hierarchy_) {
    best_ = router_.route_timed(requests_, base_.depart, times_, threads_, &best_cost_);
    return;
  }
  // Per interval: the hierarchy customized on its times routes the vehicles departing in it.
  best_.assign(requests_.size(), {});
  best_cost_.assign(requests_.size(), std::numeric_limits<double>::infinity());
  std::vector<std::vector<uint32_t>> by_interval(times_.intervals());
  for (uint32_t v = 0; v < requests_.size(); ++v)
    if (!requests_[v].origins.empty()) by_interval[times_.interval_at(base_.depart[v])].push_back(v);
  for (uint32_t k = 0; k < by_interval.size(); ++k) {
    if (by_interval[k].empty()) continue;
    interval_router_.set_interval_costs(times_, k);
    std::vector<RouteRequest> requests;
    for (uint32_t v : by_interval[k]) requests.push_back(requests_[v]);
    std::vector<std::vector<uint32_t>> paths = hierarchy_->route_all(interval_router_, requests, threads_);
    for (size_t i = 0; i < paths.size(); ++i) best_[by_interval[k][i]] = std::move(paths[i]);
  }
  for_each_index(
      best_.size(), threads_, [] { return 0; },
      [&](int, size_t v) {
        if (!best_[v].empty()) best_cost_[v] = router_.timed_cost(best_[v], base_.depart[v], times_);
      },
      64);
}

void Assignment::choose_routes() {
  std::vector<std::vector<uint32_t>> chosen(base_.size());
  const uint64_t iteration = static_cast<uint64_t>(done_);
  for_each_index(
      base_.size(), threads_, [] { return 0; },
      [&](int, size_t v) {
        if (best_[v].empty()) return;  // no route: the loaded one stays
        const double depart = base_.depart[v];
        auto cost_of = [&](const std::vector<uint32_t>& edges) {
          return router_.timed_cost(edges, depart, times_);
        };
        const double draw =
            rng_uniform_double(options_.seed ^ kDrawRouteChoice, draw_stream(base_.vehicle_id[v]), iteration);
        RouteAlternatives& alts = alternatives_[v];
        // C-logit's commonalities weigh each edge by its travel time at the departure, as duarouter's.
        auto edge_time = [&](uint32_t e) { return router_.timed_edge_cost(e, depart, times_); };
        const uint32_t k = choose_route(alts, best_[v], cost_of, edge_time, choice_, draw);
        chosen[v] = alts.routes[k].edges;
      },
      64);
  assigned_ = base_;
  replace_routes(assigned_, net_, chosen);
}

Assignment::Simulated Assignment::simulate() {
  Simulated s;
  if (launcher_ == nullptr) return simulate_part0(options_);
  if (launcher_->leads())
    launcher_->run_part0(net_, assigned_, options_,
                         [&](const SimulationOptions& o) { s = simulate_part0(o); });
  else
    launcher_->serve(net_, assigned_, options_);
  if (launcher_->ranks() != nullptr) share_with_ranks(&s);
  return s;
}

void Assignment::share_with_ranks(Simulated* s) {
  Transport& ranks = *launcher_->ranks();
  Bytes mine;
  if (launcher_->leads()) {
    ByteWriter w(mine);
    w.put(s->finished);
    w.put(s->teleports);
    w.put(s->mean_trip_time);
    w.put_array(times_.time);
  }
  const std::vector<Bytes> all = ranks.allgather(mine, "assignment travel times");
  if (launcher_->leads()) return;
  ByteReader r(all[0]);
  s->finished = r.get<uint64_t>();
  s->teleports = r.get<uint64_t>();
  s->mean_trip_time = r.get<double>();
  times_.time = r.get_array<float>();
}

Assignment::Simulated Assignment::simulate_part0(const SimulationOptions& options) {
  Simulation sim(net_, assigned_, options);
  const double dt = sim.step_length();
  const double period = spec_.aggregation;
  std::vector<LaneCounters> interval_counters;  // cumulative at each interval's end
  double interval_end = begin_ + period;
  Simulated s;
  auto done = [&] {
    if (end_ >= 0) return sim.time() + dt > end_ - kTimeSlack;
    return sim.finished();
  };
  while (!done()) {
    sim.step();
    for (const TripRecord& r : sim.take_finished_trips()) {
      if (r.unfinished) continue;
      ++s.finished;
      s.mean_trip_time += r.arrival - r.depart;
    }
    if (sim.time() + dt + kTimeSlack >= interval_end) {
      interval_counters.push_back(sim.collect_lane_counters());
      interval_end += period;
    }
  }
  interval_counters.push_back(sim.collect_lane_counters());
  s.teleports = sim.counts().teleports;
  if (s.finished > 0) s.mean_trip_time /= double(s.finished);

  // Each interval's travel times, from the counters' differences.
  const uint32_t n = static_cast<uint32_t>(interval_counters.size());
  times_.resize(net_.num_edges(), n);
  LaneCounters zero;
  zero.resize(net_.num_lanes());
  for (uint32_t k = 0; k < n; ++k) {
    const LaneCounters c = counters_since(interval_counters[k], k == 0 ? zero : interval_counters[k - 1]);
    for (uint32_t e = 0; e < net_.num_edges(); ++e) {
      if (net_.edge_is_internal[e]) continue;
      const MeanDataTotals t = sum_lane_counters(c, net_.edge_first_lane[e], net_.edge_num_lanes[e], dt);
      if (t.sampled_seconds < kMinSamples) continue;
      const MeanDataMeasures m =
          derive_mean_data(t, net_.edge_length[e], net_.edge_num_lanes[e], net_.edge_speed[e], period, 0);
      if (m.has_traveltime) times_.time[size_t(k) * net_.num_edges() + e] = static_cast<float>(m.traveltime);
    }
  }
  return s;
}

void Assignment::resume(int first, const std::unordered_map<std::string, RouteAlternatives>& alternatives) {
  std::vector<std::vector<uint32_t>> chosen(base_.size());
  for (uint32_t v = 0; v < base_.size(); ++v) {
    const auto it = alternatives.find(base_.vehicle_id[v]);
    if (it == alternatives.end() || it->second.routes.empty()) continue;
    // Each must be a route this vehicle can drive from its origin to its destination.
    const RouteRequest& q = requests_[v];
    for (const RouteAlternative& r : it->second.routes)
      if (q.origins.empty() || r.edges.front() != q.origins[0] || r.edges.back() != q.destinations[0] ||
          !TripTable::connected(net_, r.edges, q.vclass))
        throw InputError("vehicle '" + base_.vehicle_id[v] +
                         "': a route among its alternatives does not lead from its origin to its destination "
                         "on edges it may use");
    alternatives_[v] = it->second;
    chosen[v] = it->second.routes[it->second.last].edges;
  }
  assigned_ = base_;
  replace_routes(assigned_, net_, chosen);
  done_ = first;
  resumed_ = true;
}

IterationResult Assignment::iterate() {
  IterationResult result;
  result.iteration = done_;
  result.vehicles = base_.size();
  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  const double cpu0 = cpu_seconds();
  double resumed_simulation = 0;
  if (resumed_) {
    // The times the chosen routes met: their simulation again, which gives the same run.
    simulate();
    resumed_simulation = cpu_seconds() - cpu0;
    route_all();
    resumed_ = false;
  } else if (done_ == 0) {
    route_all();  // on free flow; later iterations take the last one's best responses
  }
  choose_routes();
  const double cpu1 = cpu_seconds();
  const auto wall1 = Clock::now();
  const Simulated simulated = simulate();
  const double cpu2 = cpu_seconds();
  const auto wall2 = Clock::now();
  route_all();
  result.gap = gap_sums(router_, assigned_, times_, best_cost_);
  const double cpu3 = cpu_seconds();
  result.finished = simulated.finished;
  result.teleports = simulated.teleports;
  result.mean_trip_time = simulated.mean_trip_time;
  result.routing_cpu_seconds = (cpu1 - cpu0 - resumed_simulation) + (cpu3 - cpu2);
  result.simulation_cpu_seconds = cpu2 - cpu1 + resumed_simulation;
  result.simulation_wall_seconds = std::chrono::duration<double>(wall2 - wall1).count();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0).count();
  ++done_;
  return result;
}

}  // namespace lpsim

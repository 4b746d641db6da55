#pragma once
// A whole run recorded step by step in comparable form (positions, summary rows, trip records, per-vehicle
// queries, lane counters), for tests that two ways of running give the same results bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {

// Everything a run shows, step by step, in comparable form.
struct Trace {
  std::vector<double> fcd;  // per step and running vehicle: time, vehicle, lane, pos, speed
  std::vector<double> summary;
  std::vector<double> trips;
  std::vector<int64_t> counters;
  std::vector<double> queries;  // lane/pos/speed/status per vehicle, through slot_of_, every 7th step
  uint64_t teleports = 0;
  uint32_t max_active = 0;
};

inline Trace run_trace(const Scenario& sc, const SimulationOptions& o) {
  Simulation sim(sc.network, sc.demand, o);
  Trace t;
  FcdFrame frame;
  while (!sim.finished() && sim.time() < 7200) {
    sim.step();
    sim.sample_fcd(frame);
    for (size_t i = 0; i < frame.vehicle.size(); ++i)
      t.fcd.insert(t.fcd.end(), {frame.time, double(frame.vehicle[i]), double(frame.lane[i]),
                                 double(frame.pos[i]), double(frame.speed[i])});
    const SummaryRow r = sim.summary_row();
    t.summary.insert(t.summary.end(), {r.time, double(r.running), double(r.waiting), double(r.halting),
                                       r.mean_speed, r.mean_speed_relative, r.mean_travel_time});
    for (const TripRecord& x : sim.take_finished_trips())
      t.trips.insert(t.trips.end(), {double(x.vehicle), x.depart, x.arrival, double(x.arrival_lane),
                                     double(x.arrival_pos), double(x.arrival_speed), x.route_length,
                                     x.waiting_time, x.time_loss, double(x.teleported)});
    if (sim.step_index() % 7 == 0)
      for (uint32_t v = 0; v < sc.demand.size(); ++v)
        t.queries.insert(t.queries.end(), {double(sim.query().status(v)), double(sim.query().lane(v)),
                                           double(sim.query().pos(v)), double(sim.query().speed(v))});
    t.max_active = std::max<uint32_t>(t.max_active, static_cast<uint32_t>(sim.active().size()));
  }
  EXPECT_TRUE(sim.finished());
  const LaneCounters& c = sim.collect_lane_counters();
  for (const auto* col : {&c.sampled_steps, &c.travelled_mm, &c.waiting_steps, &c.time_loss_ms,
                          &c.occupied_mm_steps, &c.departed, &c.arrived, &c.entered, &c.left})
    t.counters.insert(t.counters.end(), col->begin(), col->end());
  t.teleports = sim.counts().teleports;
  return t;
}

inline void expect_same_trace(const Trace& a, const Trace& b, const std::string& what) {
  // Bitwise: a difference in the last bit of a float is a difference.
  auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
  };
  EXPECT_TRUE(same(a.fcd, b.fcd)) << what << ": positions differ";
  EXPECT_TRUE(same(a.summary, b.summary)) << what << ": summary differs";
  EXPECT_TRUE(same(a.trips, b.trips)) << what << ": trip records differ";
  EXPECT_TRUE(same(a.queries, b.queries)) << what << ": per-vehicle queries differ";
  EXPECT_EQ(a.counters, b.counters) << what << ": lane counters differ";
}

}  // namespace lpsim::engine_test

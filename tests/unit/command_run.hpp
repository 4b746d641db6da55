#pragma once
// Test support: a run of grid_tls with a driver's commands between steps (engine/vehicle_commands.hpp), in
// one part or in three, on either backend (tests/unit/engine_commands_test.cpp, tests/gpu).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "app/partitioned_parts.hpp"
#include "partition/junction_graph.hpp"
#include "partition/partition_method.hpp"
#include "unit/engine_invariant_checker.hpp"

namespace lpsim::engine_test {

struct CommandRun {
  std::vector<TripRecord> trips;  // in the order they ended
  std::vector<double> fcd;        // time, vehicle, lane, pos, speed of each running vehicle, every step
  std::vector<std::string> errors;
  RunCounts counts;
  std::string lane_map;  // the first lane-map inconsistency (one part only)
  uint32_t running_removed = 0, junction_removed = 0, not_due_removed = 0, queued_removed = 0;
  uint32_t inserted_removed = 0;  // inserted at the end of the last step
  double removed_at = 0;
  SummaryRow last_row;
};

// grid_tls: at t = 60 six trips are added on one edge that two parts of three hold, due at once (one enters a
// step, the rest queue); at t = 61 the last of them (queued), the first (inserted in the last step), a
// running vehicle, one on a junction's internal lane and the last loaded trip (not due) are removed, then the
// running one again and a vehicle that does not exist (both refused).
inline std::vector<PartPlan> three_parts(const Scenario& sc) {
  const Network& net = sc.network;
  const std::vector<int32_t> edge_part = edge_parts_from_junctions(
      net, partition_junctions(build_junction_graph(net, sc.demand, 1.0), 3, PartitionMethod::Metis, 2));
  return part_plans(net, edge_part, 3, longest_vehicle(sc.demand));
}

// A loaded trip whose first edge's lanes two parts of three hold: a vehicle inserted there is seen by both.
inline int64_t trip_from_a_shared_edge(const Scenario& sc) {
  const PartPlan plan = three_parts(sc)[0];
  const Demand& d = sc.demand;
  for (uint32_t v = 0; v < d.size(); ++v) {
    const uint32_t lane = sc.network.edge_first_lane[d.route_edges[d.route_begin[v]]];
    if (plan.holder_begin[lane + 1] - plan.holder_begin[lane] > 1 && d.route_length[v] > 2) return v;
  }
  return -1;
}

inline CommandRun run_with_removals(const Scenario& sc, SimulationOptions options, bool in_three_parts) {
  CommandRun out;
  const Network& net = sc.network;
  std::unique_ptr<InProcessParts> others;
  if (in_three_parts) {
    others = std::make_unique<InProcessParts>(net, sc.demand, options, three_parts(sc), 60);
    options = others->part0_options(options);
  }
  const auto copied = static_cast<uint32_t>(std::max<int64_t>(0, trip_from_a_shared_edge(sc)));
  run_part0(others.get(), [&] {
    Simulation sim(net, sc.demand, options);
    const uint32_t loaded = sim.demand().size();
    FcdFrame frame;
    CommandQueue queue;
    auto apply = [&] {
      for (const CommandOutcome& o : sim.apply_commands(queue.take())) out.errors.push_back(o.error);
    };
    while (!sim.finished() && sim.time() < 3600) {
      if (sim.time() == 60) {
        const Demand& d = sim.demand();
        for (int k = 0; k < 6; ++k) {
          NewTrip t;
          t.id = "added_" + std::to_string(k);
          t.route.assign(d.route_edges.begin() + d.route_begin[copied],
                         d.route_edges.begin() + d.route_begin[copied] + d.route_length[copied]);
          t.depart = 60;
          queue.push(VehicleCommand::add(t));
        }
        apply();
      }
      if (sim.time() == 61) {
        out.removed_at = sim.time();
        sim.sample_fcd(frame);
        EXPECT_GT(frame.vehicle.size(), 10u);
        for (size_t i = 0; i < frame.vehicle.size(); ++i) {
          const bool internal = net.edge_is_internal[net.lane_edge[frame.lane[i]]] != 0;
          if (internal && out.junction_removed == 0) out.junction_removed = frame.vehicle[i];
          if (!internal && frame.speed[i] > 5 && out.running_removed == 0)
            out.running_removed = frame.vehicle[i];
        }
        EXPECT_NE(out.junction_removed, 0u) << "no vehicle inside a junction";
        EXPECT_NE(out.running_removed, 0u) << "no vehicle driving";
        out.queued_removed = static_cast<uint32_t>(sim.vehicle_index("added_5"));
        out.inserted_removed = static_cast<uint32_t>(sim.vehicle_index("added_0"));
        out.not_due_removed = loaded - 1;
        for (const uint32_t v :
             {out.queued_removed, out.inserted_removed, out.running_removed, out.junction_removed,
              out.not_due_removed, out.running_removed, sim.demand().size()})
          queue.push(VehicleCommand::remove(v));
        apply();
      }
      sim.step();
      if (!in_three_parts && out.lane_map.empty()) out.lane_map = sim.check_lane_map();
      const std::vector<TripRecord> ended = sim.take_finished_trips();
      out.trips.insert(out.trips.end(), ended.begin(), ended.end());
      sim.sample_fcd(frame);
      for (size_t i = 0; i < frame.vehicle.size(); ++i)
        out.fcd.insert(out.fcd.end(), {frame.time, double(frame.vehicle[i]), double(frame.lane[i]),
                                       double(frame.pos[i]), double(frame.speed[i])});
      out.last_row = sim.summary_row();
    }
    EXPECT_TRUE(sim.finished());
    out.counts = sim.counts();
  });
  return out;
}

inline bool drives_after(const CommandRun& run, uint32_t v, double t) {
  for (size_t i = 0; i < run.fcd.size(); i += 5)
    if (run.fcd[i] > t && run.fcd[i + 1] == double(v)) return true;
  return false;
}

inline const TripRecord* record_of(const CommandRun& run, uint32_t v) {
  for (const TripRecord& r : run.trips)
    if (r.vehicle == v) return &r;
  return nullptr;
}

/// Steps `sim` (grid_tls) to step `steps`, with commands on the way: at step 60 six trips added (three due at
/// once, three at 153-155 s) and the last loaded trip removed before it is due; at step 70 a running
/// vehicle removed.
inline void drive_with_commands(Simulation& sim, uint32_t steps) {
  const Demand& d = sim.demand();
  while (sim.step_index() < steps) {
    if (sim.step_index() == 60) {
      CommandQueue queue;
      for (int k = 0; k < 6; ++k) {
        NewTrip t;
        t.id = "added_" + std::to_string(k);
        t.type = d.vehicle_type[k];
        t.route.assign(d.route_edges.begin() + d.route_begin[k],
                       d.route_edges.begin() + d.route_begin[k] + d.route_length[k]);
        t.depart = k < 3 ? sim.time() : 150.0 + k;  // some due after the save
        t.speed_factor = 0.95f;
        queue.push(VehicleCommand::add(t));
      }
      queue.push(VehicleCommand::remove(d.size() - 1));  // not due yet
      for (const CommandOutcome& o : sim.apply_commands(queue.take())) EXPECT_TRUE(o.done()) << o.error;
    }
    if (sim.step_index() == 70) {
      FcdFrame frame;
      sim.sample_fcd(frame);
      ASSERT_GE(frame.vehicle.size(), 2u);
      const CommandOutcome o = sim.apply_commands({VehicleCommand::remove(frame.vehicle[0])})[0];
      EXPECT_TRUE(o.done()) << o.error;
    }
    sim.step();
  }
}

/// The two runs alike: the same outcomes, FCD, trip records and counts.
inline void expect_same_command_run(const CommandRun& one, const CommandRun& other, const char* what) {
  EXPECT_EQ(other.errors, one.errors) << what;
  EXPECT_EQ(other.running_removed, one.running_removed) << what;
  EXPECT_EQ(other.junction_removed, one.junction_removed) << what;
  EXPECT_TRUE(other.fcd == one.fcd) << what << ": FCD differs";
  ASSERT_EQ(other.trips.size(), one.trips.size()) << what;
  for (size_t i = 0; i < one.trips.size(); ++i) {
    const TripRecord &a = one.trips[i], &b = other.trips[i];
    EXPECT_TRUE(a.vehicle == b.vehicle && a.arrival == b.arrival && a.arrival_lane == b.arrival_lane &&
                a.arrival_pos == b.arrival_pos && a.route_length == b.route_length &&
                a.removed == b.removed && a.time_loss == b.time_loss)
        << what << ": trip " << a.vehicle << " / " << b.vehicle << ": arrival " << a.arrival << " / "
        << b.arrival << ", lane " << a.arrival_lane << " / " << b.arrival_lane << ", pos " << a.arrival_pos
        << " / " << b.arrival_pos << ", removed " << a.removed << " / " << b.removed;
  }
  EXPECT_EQ(other.counts.cancelled, one.counts.cancelled) << what;
  EXPECT_EQ(other.counts.arrived, one.counts.arrived) << what;
  EXPECT_EQ(other.last_row.ended, one.last_row.ended) << what;
}

}  // namespace lpsim::engine_test

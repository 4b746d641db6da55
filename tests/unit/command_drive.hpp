#pragma once
// Test support without gtest (also for the mpirun probe, tests/mpi/mpi_commands_probe.cpp): a run of grid_tls
// with a driver's commands between steps (engine/vehicle_commands.hpp), and its account as text.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "app/partitioned_parts.hpp"
#include "app/scenario.hpp"
#include "engine/simulation.hpp"
#include "partition/junction_graph.hpp"
#include "partition/partition_method.hpp"

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
  bool finished = false;
  size_t vehicles_at_removal = 0;
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

/// Part 0's Simulation `sim` of grid_tls driven to its end with the commands above. `check_lane_map`: compare
/// the lane map with the vehicles after every step (a run of one part).
inline void drive_removals(Simulation& sim, const Scenario& sc, bool check_lane_map, CommandRun& out) {
  const Network& net = sc.network;
  const auto copied = static_cast<uint32_t>(std::max<int64_t>(0, trip_from_a_shared_edge(sc)));
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
      out.vehicles_at_removal = frame.vehicle.size();
      for (size_t i = 0; i < frame.vehicle.size(); ++i) {
        const bool internal = net.edge_is_internal[net.lane_edge[frame.lane[i]]] != 0;
        if (internal && out.junction_removed == 0) out.junction_removed = frame.vehicle[i];
        if (!internal && frame.speed[i] > 5 && out.running_removed == 0)
          out.running_removed = frame.vehicle[i];
      }
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
    if (check_lane_map && out.lane_map.empty()) out.lane_map = sim.check_lane_map();
    const std::vector<TripRecord> ended = sim.take_finished_trips();
    out.trips.insert(out.trips.end(), ended.begin(), ended.end());
    sim.sample_fcd(frame);
    for (size_t i = 0; i < frame.vehicle.size(); ++i)
      out.fcd.insert(out.fcd.end(), {frame.time, double(frame.vehicle[i]), double(frame.lane[i]),
                                     double(frame.pos[i]), double(frame.speed[i])});
    out.last_row = sim.summary_row();
  }
  out.finished = sim.finished();
  out.counts = sim.counts();
}

/// Everything a run's account holds that does not depend on its parts, exactly (floats as hex).
inline std::string command_run_text(const CommandRun& run) {
  std::string out;
  char buf[256];
  for (const std::string& e : run.errors) out += "outcome " + e + "\n";
  for (size_t i = 0; i < run.fcd.size(); i += 5) {
    std::snprintf(buf, sizeof buf, "fcd %a %a %a %a %a\n", run.fcd[i], run.fcd[i + 1], run.fcd[i + 2],
                  run.fcd[i + 3], run.fcd[i + 4]);
    out += buf;
  }
  for (const TripRecord& t : run.trips) {
    std::snprintf(buf, sizeof buf, "trip %u %a %a %a %u %a %a %a %d\n", t.vehicle, t.depart, t.arrival,
                  t.route_length, t.arrival_lane, static_cast<double>(t.arrival_pos), t.time_loss,
                  static_cast<double>(t.arrival_speed), t.removed ? 1 : 0);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "counts %llu %llu %llu %llu ended %llu\n",
                static_cast<unsigned long long>(run.counts.loaded),
                static_cast<unsigned long long>(run.counts.inserted),
                static_cast<unsigned long long>(run.counts.arrived),
                static_cast<unsigned long long>(run.counts.cancelled),
                static_cast<unsigned long long>(run.last_row.ended));
  return out + buf;
}

}  // namespace lpsim::engine_test

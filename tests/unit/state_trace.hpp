#pragma once
// What a checkpoint test compares: every value the outputs read after each step of a run, written exactly.
#include <cstdio>
#include <string>

#include "engine/simulation.hpp"

namespace lpsim::engine_test {

// Every value the outputs read, written exactly (floats as hex), after each step from now to the end.
inline std::string trace_to_end(Simulation& sim, uint32_t max_steps) {
  std::string out;
  char buf[256];
  FcdFrame frame;
  for (uint32_t n = 0; n < max_steps && !sim.finished(); ++n) {
    sim.step();
    sim.sample_fcd(frame);
    std::snprintf(buf, sizeof buf, "t %a\n", frame.time);
    out += buf;
    for (size_t i = 0; i < frame.vehicle.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%u %u %a %a\n", frame.vehicle[i], frame.lane[i],
                    static_cast<double>(frame.pos[i]), static_cast<double>(frame.speed[i]));
      out += buf;
    }
    const SummaryRow r = sim.summary_row();
    std::snprintf(buf, sizeof buf, "summary %llu %llu %llu %llu %llu %llu %a %a %a %a\n",
                  static_cast<unsigned long long>(r.inserted), static_cast<unsigned long long>(r.running),
                  static_cast<unsigned long long>(r.waiting), static_cast<unsigned long long>(r.arrived),
                  static_cast<unsigned long long>(r.teleports), static_cast<unsigned long long>(r.halting),
                  r.mean_speed, r.mean_speed_relative, r.mean_waiting_time, r.mean_travel_time);
    out += buf;
    for (const TripRecord& t : sim.take_finished_trips()) {
      std::snprintf(buf, sizeof buf, "trip %u %a %a %a %u %a %a %a %u %d\n", t.vehicle, t.depart, t.arrival,
                    t.route_length, t.arrival_lane, static_cast<double>(t.arrival_pos), t.waiting_time,
                    t.time_loss, t.waiting_count, t.teleported ? 1 : 0);
      out += buf;
    }
  }
  const LaneCounters& c = sim.collect_lane_counters();
  for (size_t l = 0; l < c.sampled_steps.size(); ++l) {
    std::snprintf(buf, sizeof buf, "lane %zu %lld %lld %lld %lld %lld %lld\n", l,
                  static_cast<long long>(c.sampled_steps[l]), static_cast<long long>(c.travelled_mm[l]),
                  static_cast<long long>(c.waiting_steps[l]), static_cast<long long>(c.time_loss_ms[l]),
                  static_cast<long long>(c.departed[l]), static_cast<long long>(c.left[l]));
    out += buf;
  }
  for (const TripRecord& t : sim.unfinished_trips(sim.time(), true)) {
    std::snprintf(buf, sizeof buf, "unfinished %u %u %a\n", t.vehicle, t.unfinished, t.route_length);
    out += buf;
  }
  return out;
}

// "" when the traces are equal, else their first differing line.
inline std::string first_difference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  size_t at = 0, line = 1;
  while (at < a.size() && at < b.size() && a[at] == b[at]) {
    if (a[at] == '\n') ++line;
    ++at;
  }
  const size_t begin = a.rfind('\n', at == 0 ? 0 : at - 1);
  const size_t from = begin == std::string::npos ? 0 : begin + 1;
  return "line " + std::to_string(line) + ": '" + a.substr(from, a.find('\n', from) - from) + "' against '" +
         b.substr(from, b.find('\n', from) - from) + "'";
}

}  // namespace lpsim::engine_test

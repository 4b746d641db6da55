// The co-simulation's results completed at its end from SUMO's: one tripinfo line per trip, and SUMO's
// measurements on the corridor's edges in each edgeData/laneData output.
#include <algorithm>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "converters/meandata_merge.hpp"
#include "converters/sumo_tripinfo_reader.hpp"
#include "sumo_bridge/cosimulation.hpp"
#include "sumo_bridge/sumo_arguments.hpp"

namespace lpsim {

namespace {

// How SUMO's tripinfo marks a piece that ended with a hand-over back (TraCI's vehicle.remove).
const std::string kHandedBack = "traci";

}  // namespace

// One tripinfo line per trip that ended, for the whole trip: its start where it departed (LPSim's
// departure, or SUMO's first piece), its end where it arrived, and the sums of both sides' pieces.
void Cosimulation::merge_tripinfo(bool after_failure) {
  const Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  std::unordered_map<std::string, uint32_t> visited_ids;
  for (uint32_t v = 0; v < visited_.size(); ++v)
    if (visited_[v]) visited_ids.emplace(d.vehicle_id[v], v);
  std::unordered_map<uint32_t, std::vector<SumoTripPiece>> pieces;
  for (SumoTripPiece& p : read_sumo_tripinfo(sumo_side_path(sumo_tripinfo_), after_failure)) {
    const auto it = visited_ids.find(p.id);
    if (it != visited_ids.end()) pieces[it->second].push_back(std::move(p));
  }
  const auto lane_of = [&](const std::string& id) {
    const auto it = net_.lane_index_by_id.find(id);
    if (it == net_.lane_index_by_id.end())
      throw SumoError("SUMO's tripinfo names lane " + id + ", not in LPSim's network");
    return it->second;
  };
  const double dt = sim.step_length();
  std::vector<TripRecord> merged;
  for (uint32_t v = 0; v < visited_.size(); ++v) {
    if (!visited_[v]) continue;
    const auto pit = pieces.find(v);
    const std::vector<SumoTripPiece>* ps = pit == pieces.end() ? nullptr : &pit->second;
    if (after_failure && (visited_[v] == 255 || (ps == nullptr ? 0u : ps->size()) != visited_[v])) continue;
    const DepartRecord dep = sim.ledger().departure(v);
    TripRecord r;
    const auto held = held_trips_.find(v);
    if (held != held_trips_.end()) {  // it arrived in LPSim, whose record sums LPSim's pieces
      r = held->second;
    } else if (ps != nullptr && ps->back().vaporized != kHandedBack) {  // its trip ended in SUMO
      const SumoTripPiece& last = ps->back();
      r.vehicle = v;
      r.arrival = last.arrival;
      r.arrival_lane = lane_of(last.arrival_lane);
      r.arrival_pos = static_cast<float>(last.arrival_pos);
      r.arrival_speed = static_cast<float>(last.arrival_speed);
      r.speed_factor = d.speed_factor[v];
      r.depart = dep.time;
      r.depart_delay = dep.time - d.depart[v];
      r.depart_lane = static_cast<uint32_t>(std::max(0, dep.lane));
      r.depart_pos = dep.pos;
      r.depart_speed = dep.speed;
      if (const TripCounters* c = sim.ledger().carried(v)) {  // what LPSim measured of it
        r.route_length = c->route_length;
        r.time_loss = c->time_loss;
        r.waiting_time = static_cast<double>(c->waiting_steps) * dt;
        r.waiting_count = c->waiting_count;
        r.stop_time = static_cast<double>(c->stop_steps) * dt;
      }
    } else {
      continue;  // still on its way when the run ended
    }
    // Where it departed: in LPSim's record of its trip (kept on by the ledger until it ended), lane -1 when
    // it departed in SUMO.
    const int32_t depart_lane = held != held_trips_.end() ? static_cast<int32_t>(r.depart_lane) : dep.lane;
    if (depart_lane < 0 && ps != nullptr) {  // it departed in SUMO
      const SumoTripPiece& first = ps->front();
      r.depart = first.depart;
      r.depart_delay = first.depart_delay;
      r.depart_lane = lane_of(first.depart_lane);
      r.depart_pos = static_cast<float>(first.depart_pos);
      r.depart_speed = static_cast<float>(first.depart_speed);
    }
    if (const auto between = driven_between_.find(v); between != driven_between_.end())
      r.route_length += static_cast<float>(between->second);
    if (ps != nullptr)
      for (const SumoTripPiece& p : *ps) {
        r.route_length += p.route_length;
        r.waiting_time += p.waiting_time;
        r.waiting_count += static_cast<uint32_t>(p.waiting_count);
        r.stop_time += p.stop_time;
        r.time_loss += p.time_loss;
      }
    merged.push_back(r);
  }
  std::sort(merged.begin(), merged.end(), [](const TripRecord& a, const TripRecord& b) {
    return a.arrival != b.arrival ? a.arrival < b.arrival : a.vehicle < b.vehicle;
  });
  for (const TripRecord& r : merged) run_.write_trip(r);
}

// Each edgeData/laneData output: the corridor's edges as SUMO measured them, the others as LPSim did.
void Cosimulation::merge_edge_data() const {
  std::unordered_set<std::string> corridor;
  for (uint32_t e = 0; e < net_.num_edges(); ++e)
    if (corridor_edge(e)) corridor.insert(net_.edge_id[e]);
  std::vector<std::string> files{run_.config().outputs.edgedata, run_.config().outputs.lanedata};
  for (const MeanDataSpec& m : run_.scenario().mean_data) files.push_back(m.file);
  for (const std::string& f : files)
    if (!f.empty())
      for (const MeanDataSpanDiff& d : merge_meandata(f, sumo_side_path(f), corridor))
        if (!run_.config().no_warnings)
          std::fprintf(
              stderr,
              "Warning: %s: the interval from %s s ends at %s s in LPSim's measurements and at %s s in "
              "SUMO's, whose last step runs past the end: the corridor's entries cover SUMO's (an end "
              "on the coupling period's grid makes them equal)\n",
              f.c_str(), sumo_number(d.begin).c_str(), sumo_number(d.lpsim_end).c_str(),
              sumo_number(d.sumo_end).c_str());
}

}  // namespace lpsim

#include "sumo_bridge/cosimulation.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "converters/meandata_merge.hpp"
#include "converters/output_file.hpp"
#include "converters/sumo_tripinfo_reader.hpp"
#include "core/error.hpp"

namespace lpsim {

namespace {

// SUMO writes its side of every output beside LPSim's, under this prefix of the file name (SUMO's
// --output-prefix, which also covers the outputs the scenario's additional files define).
constexpr const char* kSumoPrefix = "sumo.";
// The longest coupling period: vehicles cross the boundary once per period, so a longer one would let them
// stand at the boundary for longer than a signal's cycle.
constexpr int64_t kLongestPeriodMs = 60000;
// A vehicle SUMO has not inserted for this long (s) after it was handed over is stuck for good: SUMO retries a
// pending vehicle at the same place for ever, which would keep the run from ending.
constexpr double kLongestPending = 3600;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ",") + s;
  return out;
}

const char* depart_lane_value(DepartLane k) {
  switch (k) {
    case DepartLane::Random:
      return "random";
    case DepartLane::Free:
      return "free";
    case DepartLane::Allowed:
      return "allowed";
    case DepartLane::Best:
      return "best";
    default:
      return "first";
  }
}

const char* depart_pos_value(DepartPos k) {
  switch (k) {
    case DepartPos::Random:
      return "random";
    case DepartPos::Free:
      return "free";
    case DepartPos::RandomFree:
      return "random_free";
    case DepartPos::Last:
      return "last";
    default:
      return "base";
  }
}

const char* depart_speed_value(DepartSpeed k) {
  switch (k) {
    case DepartSpeed::Random:
      return "random";
    case DepartSpeed::Max:
      return "max";
    case DepartSpeed::Desired:
      return "desired";
    case DepartSpeed::SpeedLimit:
      return "speedLimit";
    case DepartSpeed::Last:
      return "last";
    case DepartSpeed::Avg:
      return "avg";
    default:
      return "0";
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<uint8_t> corridor_lanes(const Network& net, const std::vector<uint32_t>& corridor_edges) {
  std::vector<uint8_t> lanes(net.num_lanes(), 0);
  for (const uint32_t e : corridor_edges)
    for (uint32_t l = net.edge_first_lane[e]; l < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++l) lanes[l] = 1;
  return lanes;
}

std::string sumo_side_path(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (std::string(kSumoPrefix) + p.filename().string())).string();
}

Cosimulation::Cosimulation(Run& run, const std::vector<uint8_t>& corridor_lanes, const CosimOptions& options)
    : run_(run), net_(run.scenario().network), corridor_(corridor_lanes), options_(options) {
  if (run_.options().outside_lanes != &corridor_)
    throw std::invalid_argument("the co-simulation's run must drive outside the corridor's lanes");
  const ConfigSpec& c = run_.config();
  if (c.net_file.empty())
    throw InputError("a co-simulation needs the scenario's SUMO files (-c or -n/-r), not a snapshot or CSV");
  // SUMO's tripinfo is needed to complete the trips it drove part of: beside the run's, or a scratch file.
  if (!c.outputs.tripinfo.empty()) {
    sumo_tripinfo_ = c.outputs.tripinfo;
  } else {
    sumo_tripinfo_ = (std::filesystem::temp_directory_path() /
                      ("lpsim-cosim-" + std::to_string(::getpid()) + "-tripinfo.xml"))
                         .string();
    scratch_tripinfo_.path = sumo_side_path(sumo_tripinfo_);
  }
  // SUMO's --edgedata-output counts from time 0 whatever the begin time (SUMO 1.15): definitions in an
  // additional file span the run, as LPSim's intervals do.
  const OutputSpec& o = c.outputs;
  if (!o.edgedata.empty() || !o.lanedata.empty()) {
    mean_data_file_.path = (std::filesystem::temp_directory_path() /
                       ("lpsim-cosim-" + std::to_string(::getpid()) + "-meandata.add.xml"))
                          .string();
    OutputFile add(mean_data_file_.path);
    add.text("<additional>\n");
    if (!o.edgedata.empty()) {
      add.text("    <edgeData id=\"edgedata\"");
      add.attr("file", o.edgedata);
      add.text("/>\n");
    }
    if (!o.lanedata.empty()) {
      add.text("    <laneData id=\"lanedata\"");
      add.attr("file", o.lanedata);
      add.text("/>\n");
    }
    add.text("</additional>\n");
    add.close();
  }
  visited_.assign(run_.simulation().demand().size(), 0);
  run_.hold_trips([this](const TripRecord& r) {
    if (r.vehicle >= visited_.size() || !visited_[r.vehicle]) return false;
    held_trips_[r.vehicle] = r;
    return true;
  });
  sumo_ = start_sumo(options_.mode, options_.sumo_binary, sumo_arguments(), options_.answer_timeout_s);
  const int64_t lpsim_ms = run_.options().step_ms;
  const double sumo_step = sumo_->step_length();
  sumo_step_ms_ = std::llround(sumo_step * 1000.0);
  if (sumo_step_ms_ <= 0 || std::fabs(static_cast<double>(sumo_step_ms_) - sumo_step * 1000.0) > 1e-6)
    throw InputError("SUMO's step length " + number(sumo_step) +
                     " s is not a whole number of milliseconds: no common coupling period with LPSim's " +
                     number(static_cast<double>(lpsim_ms) / 1000.0) + " s");
  period_ms_ = std::lcm(lpsim_ms, sumo_step_ms_);
  if (period_ms_ > kLongestPeriodMs)
    throw InputError("SUMO's step length " + number(sumo_step) + " s and LPSim's " +
                     number(static_cast<double>(lpsim_ms) / 1000.0) + " s have no common multiple up to " +
                     number(kLongestPeriodMs / 1000.0) + " s to couple them at (the least is " +
                     number(static_cast<double>(period_ms_) / 1000.0) + " s): give step lengths that divide one another");
  report_.period = static_cast<double>(period_ms_) / 1000.0;
  const double sumo_begin = sumo_->time();
  if (std::fabs(sumo_begin - run_.simulation().time()) > 1e-6)
    throw InputError("SUMO starts at " + number(sumo_begin) + " s, LPSim at " +
                     number(run_.simulation().time()) + " s: give both the same --begin");
}

Cosimulation::~Cosimulation() = default;

Cosimulation::ScratchFile::~ScratchFile() {
  std::error_code ignored;
  if (!path.empty()) std::filesystem::remove(path, ignored);
}

std::vector<std::string> Cosimulation::sumo_arguments() const {
  const ConfigSpec& c = run_.config();
  // The co-simulation's options, as (name, value) pairs.
  std::vector<std::pair<std::string, std::string>> ours{{"--net-file", c.net_file}};
  // The route files for their vTypes (and distributions) only: SUMO drops every vehicle and flow at scale 0.
  if (!c.route_files.empty()) {
    ours.emplace_back("--route-files", joined(c.route_files));
    ours.emplace_back("--scale", "0");
  }
  std::vector<std::string> additional = c.additional_files;
  if (!mean_data_file_.path.empty()) additional.push_back(mean_data_file_.path);
  if (!additional.empty()) ours.emplace_back("--additional-files", joined(additional));
  ours.insert(ours.end(), {{"--begin", number(c.begin)},
                           {"--step-length", number(c.step_length)},
                           {"--seed", std::to_string(c.seed)},
                           {"--time-to-teleport", number(c.time_to_teleport)},
                           {"--time-to-impatience", number(c.time_to_impatience)},
                           {"--default.carfollowmodel", c.default_car_follow_model},
                           {"--no-step-log", "true"},
                           {"--output-prefix", kSumoPrefix},
                           {"--tripinfo-output", sumo_tripinfo_}});
  const OutputSpec& o = c.outputs;
  if (!o.fcd.empty()) ours.emplace_back("--fcd-output", o.fcd);
  if (o.fcd_period > 0) ours.emplace_back("--device.fcd.period", number(o.fcd_period));
  if (!o.summary.empty()) ours.emplace_back("--summary-output", o.summary);
  // SUMO refuses an option given twice: one the user passes replaces ours (its short forms too).
  std::unordered_set<std::string> given;
  for (const std::string& a : options_.sumo_args) {
    const std::string name = a.substr(0, a.find('='));
    given.insert(name == "-n" ? "--net-file"
                 : name == "-r" ? "--route-files"
                 : name == "-a" ? "--additional-files"
                 : name == "-b" ? "--begin"
                 : name);
  }
  for (const char* kept : {"--output-prefix", "--tripinfo-output", "--scale"})
    if (given.count(kept))
      throw InputError(std::string("--sumo-args: the co-simulation sets SUMO's ") + kept +
                       " itself (SUMO's outputs are written beside LPSim's, as sumo.<name>)");
  std::vector<std::string> a;
  for (const auto& [name, value] : ours)
    if (!given.count(name)) a.insert(a.end(), {name, value});
  a.insert(a.end(), options_.sumo_args.begin(), options_.sumo_args.end());
  return a;
}

void Cosimulation::step() {
  if (finished_) throw std::logic_error("Cosimulation::step() after finish()");
  Simulation& sim = run_.simulation();
  const int64_t target_ms = sim.time_ms() + period_ms_;
  // LPSim's steps: the vehicles handed out at the end of each go into SUMO as they were then.
  // Never past an end time (without one LPSim steps on while SUMO has vehicles, even when it is empty).
  const bool has_end = run_.config().end >= 0;
  while (sim.time_ms() < target_ms && !(has_end && run_.done())) {
    run_.step();
    const auto t0 = std::chrono::steady_clock::now();
    for (const Simulation::HandOut& h : sim.hand_outs()) hand_into_sumo(h);
    report_.handover_seconds += seconds_since(t0);
  }
  // SUMO's steps over the same period, one by one: it lists the arrivals of its last step only.
  for (int64_t t = target_ms - period_ms_ + sumo_step_ms_; t <= target_ms; t += sumo_step_ms_) {
    const auto t0 = std::chrono::steady_clock::now();
    sumo_->step_to(static_cast<double>(t) / 1000.0);
    report_.sumo_seconds += seconds_since(t0);
    for (const std::string& id : sumo_->arrived()) {
      if (removed_since_step_.count(id)) continue;
      const auto it = in_sumo_.find(id);
      if (it == in_sumo_.end()) continue;
      if (it->second.pending) --pending_;  // inserted and arrived within one step
      ++arrived_in_sumo_;
      ++report_.arrived_in_sumo;
      in_sumo_.erase(it);
    }
    removed_since_step_.clear();
    // What SUMO inserted reports where it is with every step from now on.
    for (const std::string& id : sumo_->departed()) {
      const auto it = in_sumo_.find(id);
      if (it == in_sumo_.end() || !it->second.pending) continue;
      it->second.pending = false;
      --pending_;
      report_.longest_boundary_wait =
          std::max(report_.longest_boundary_wait, static_cast<double>(t) / 1000.0 - it->second.since);
      it->second.since = static_cast<double>(t) / 1000.0;
      if (it->second.entry_lane >= 0) {  // its maximum speed capped its speed at the insertion
        const Demand& d = run_.simulation().demand();
        sumo_->restore_max_speed(id, d.types.max_speed[d.vehicle_type[it->second.vehicle]]);
      }
      sumo_->watch(id);
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  after_sumo_step();
  report_.handover_seconds += seconds_since(t0);
}

void Cosimulation::hand_into_sumo(const Simulation::HandOut& h) {
  const Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  const uint32_t v = h.vehicle;
  SumoEntry e;
  e.id = d.vehicle_id[v];
  e.type = d.types.id[d.vehicle_type[v]];
  for (uint32_t k = d.route_begin[v] + h.route_pos; k < d.route_begin[v] + d.route_length[v]; ++k)
    e.route.push_back(net_.edge_id[d.route_edges[k]]);
  e.speed_factor = d.speed_factor[v];
  if (h.lane >= 0) {
    e.lane = static_cast<int>(net_.lane_index[static_cast<uint32_t>(h.lane)]);
    e.pos = std::min(h.pos, net_.lane_length[static_cast<uint32_t>(h.lane)]);  // LPSim's front may overhang
    e.speed = h.speed;
  } else {
    e.lane = -1;
    if (h.route_pos == 0) {  // its trip departs here, as its depart attributes say
      const auto lane_kind = static_cast<DepartLane>(d.depart_lane_kind[v]);
      e.depart_lane =
          lane_kind == DepartLane::Given ? std::to_string(d.depart_lane[v]) : depart_lane_value(lane_kind);
      const auto pos_kind = static_cast<DepartPos>(d.depart_pos_kind[v]);
      e.depart_pos = pos_kind == DepartPos::Given ? number(d.depart_pos[v]) : depart_pos_value(pos_kind);
      const auto speed_kind = static_cast<DepartSpeed>(d.depart_speed_kind[v]);
      e.depart_speed =
          speed_kind == DepartSpeed::Given ? number(d.depart_speed[v]) : depart_speed_value(speed_kind);
    } else {  // a teleport's re-entry: at the start of the best lane, standing
      e.depart_lane = "best";
    }
  }
  sumo_->add(e);
  visited_[v] = 1;
  InSumo s;
  s.vehicle = v;
  s.route_pos = h.route_pos;
  s.entry_lane = h.lane;
  s.entry_pos = h.pos;
  s.since = sim.time();
  in_sumo_[e.id] = s;
  ++pending_;
  ++report_.into_sumo;
}

// After SUMO's steps: what it could not insert yet stays pending where it was to enter (in LPSim's lane
// map); a vehicle that has reached an edge outside the corridor comes back (or waits in SUMO); the others
// are mirrored.
void Cosimulation::after_sumo_step() {
  Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  const double now = sim.time();
  mirror_.clear();
  std::unordered_set<std::string> pending;
  if (pending_ > 0)
    for (std::string& id : sumo_->pending()) pending.insert(std::move(id));
  if (pending_ > 0)
    for (const auto& [id, s] : in_sumo_) {
      if (!s.pending) continue;
      // SUMO drops a vehicle it will never insert (an error of its own above): that would lose it.
      if (!pending.count(id))
        throw SumoError("SUMO dropped vehicle " + id + " instead of inserting it (SUMO's messages above say why)");
      if (now - s.since > kLongestPending)
        throw SumoError("SUMO has not inserted vehicle " + id + " for " + number(now - s.since) +
                        " s since LPSim handed it over: no room where it enters, for ever");
      report_.longest_boundary_wait = std::max(report_.longest_boundary_wait, now - s.since);
      if (s.entry_lane >= 0)
        mirror_.push_back(Simulation::OutsideVehicle{s.entry_lane, s.entry_pos,
                                                     d.types.length[d.vehicle_type[s.vehicle]], 0.0f});
    }
  std::vector<std::pair<std::string, SumoVehicle>> running = sumo_->watched();
  // In vehicle order: the take-backs queue in it, and the results must not depend on SUMO's order.
  std::vector<std::pair<uint32_t, size_t>> order;
  order.reserve(running.size());
  for (size_t i = 0; i < running.size(); ++i) {
    const auto it = in_sumo_.find(running[i].first);
    if (it == in_sumo_.end()) throw SumoError("SUMO reports vehicle " + running[i].first + ", which LPSim did not hand to it");
    order.emplace_back(it->second.vehicle, i);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [v, i] : order) {
    const std::string& id = running[i].first;
    const SumoVehicle& q = running[i].second;
    InSumo& s = in_sumo_.at(id);
    if (q.edge.empty() || q.edge[0] == ':') continue;  // inside a junction: SUMO's until the next edge
    const auto e = net_.edge_index.find(q.edge);
    if (e == net_.edge_index.end())
      throw SumoError("SUMO has vehicle " + id + " on edge " + q.edge + ", not in LPSim's network");
    const uint32_t edge = e->second;
    if (net_.edge_num_lanes[edge] == 0 || !corridor_[net_.edge_first_lane[edge]]) {
      take_back_or_hold(id, s, edge, q);
      continue;
    }
    const int32_t lane = lpsim_lane(edge, q.lane);
    if (lane < 0) continue;
    // The map LPSim's next step writes shows the state at its end: SUMO's vehicles a period on at their
    // speed (else LPSim's vehicles would follow them a period's distance behind where they are). One that
    // would pass the lane's end stands at it: the next lane is SUMO's too.
    const float ahead = static_cast<float>(q.pos + q.speed * report_.period);
    mirror_.push_back(Simulation::OutsideVehicle{lane, std::min(ahead, net_.lane_length[static_cast<uint32_t>(lane)]),
                                                 d.types.length[d.vehicle_type[v]], static_cast<float>(q.speed)});
  }
  sim.mirror_outside_vehicles(mirror_);
}

// LPSim keeps the lanes road vehicles use, so SUMO's lane index on an edge (which counts sidewalks and bike
// lanes too) is found among them; -1 for a lane LPSim does not have.
int32_t Cosimulation::lpsim_lane(uint32_t edge, int sumo_index) const {
  for (uint32_t l = net_.edge_first_lane[edge]; l < net_.edge_first_lane[edge] + net_.edge_num_lanes[edge]; ++l)
    if (static_cast<int>(net_.lane_index[l]) == sumo_index) return static_cast<int32_t>(l);
  return -1;
}

void Cosimulation::take_back_or_hold(const std::string& id, InSumo& s, uint32_t edge, const SumoVehicle& q) {
  Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  const double now = sim.time();
  // Where it is in its trip's route: SUMO's route index, counted from the route SUMO was given.
  uint32_t rp = s.route_pos + static_cast<uint32_t>(q.route_index);
  const uint32_t* route = d.route_edges.data() + d.route_begin[s.vehicle];
  if (rp >= d.route_length[s.vehicle] || route[rp] != edge) {
    rp = s.route_pos;
    while (rp < d.route_length[s.vehicle] && route[rp] != edge) ++rp;
    if (rp == d.route_length[s.vehicle])
      throw SumoError("SUMO drove vehicle " + id + " onto edge " + q.edge + ", which is not on its route");
  }
  if (!sim.has_entry_room(edge)) {
    if (!s.held) {
      sumo_->hold(id);
      s.held = true;
      ++report_.held;
      s.since = now;
    }
    report_.longest_boundary_wait = std::max(report_.longest_boundary_wait, now - s.since);
    return;
  }
  if (s.held) report_.longest_boundary_wait = std::max(report_.longest_boundary_wait, now - s.since);
  // SUMO measured its piece of the trip: its tripinfo has it (merged at the end), not these counters.
  // On the lane SUMO chose for its route (SUMO's own lane-change model got it there), or any best lane
  // where LPSim does not have that lane.
  sim.take_back(s.vehicle, rp, lpsim_lane(edge, q.lane), static_cast<float>(q.speed), TripCounters{});
  sumo_->remove(id);
  removed_since_step_.insert(id);
  in_sumo_.erase(id);
  ++report_.out_of_sumo;
}

bool Cosimulation::done() const {
  if (run_.config().end >= 0) return run_.done();
  return run_.simulation().finished() && in_sumo_.empty();
}

Cosimulation::Census Cosimulation::census() const {
  const Simulation& sim = run_.simulation();
  Census c;
  c.loaded = sim.demand().size();
  uint64_t migrated = 0, ended = 0;
  for (uint32_t v = 0; v < sim.demand().size(); ++v) {
    const uint8_t st = sim.ledger_status(v);
    if (st == kMigrated)
      ++migrated;
    else if (st == kArrived)
      ++ended;
    else
      ++c.in_lpsim;
  }
  for (const auto& [id, s] : in_sumo_) ++(s.pending ? c.in_handover : c.in_sumo);
  c.arrived = ended + arrived_in_sumo_;
  const auto fail = [](const std::string& what) { throw std::logic_error("co-simulation census: " + what); };
  if (migrated != in_sumo_.size() + arrived_in_sumo_)
    fail(std::to_string(migrated) + " vehicles handed to SUMO by LPSim's account, " +
         std::to_string(in_sumo_.size()) + " in SUMO + " + std::to_string(arrived_in_sumo_) +
         " arrived there by the bridge's");
  const uint64_t sumo_running = static_cast<uint64_t>(sumo_->running());
  const uint64_t sumo_pending = sumo_->pending().size();
  if (sumo_running != c.in_sumo || sumo_pending != c.in_handover)
    fail("SUMO runs " + std::to_string(sumo_running) + " and has " + std::to_string(sumo_pending) +
         " pending; the bridge counts " + std::to_string(c.in_sumo) + " and " + std::to_string(c.in_handover));
  if (c.in_lpsim + c.in_sumo + c.in_handover + c.arrived != c.loaded)
    fail(std::to_string(c.loaded) + " loaded but " + std::to_string(c.in_lpsim + c.in_sumo + c.in_handover + c.arrived) +
         " accounted for");
  return c;
}

void Cosimulation::finish() {
  if (finished_) return;
  finished_ = true;
  for (const auto& [id, s] : in_sumo_)
    if (s.pending || s.held) ++report_.in_handover_at_end;
  sumo_->close();
  merge_tripinfo();
  run_.finish();
  merge_edge_data();
}

// Each edgeData/laneData output: the corridor's edges as SUMO measured them, the others as LPSim did.
void Cosimulation::merge_edge_data() const {
  std::unordered_set<std::string> corridor;
  for (uint32_t e = 0; e < net_.num_edges(); ++e)
    if (net_.edge_num_lanes[e] > 0 && corridor_[net_.edge_first_lane[e]]) corridor.insert(net_.edge_id[e]);
  std::vector<std::string> files{run_.config().outputs.edgedata, run_.config().outputs.lanedata};
  for (const MeanDataSpec& m : run_.scenario().mean_data) files.push_back(m.file);
  for (const std::string& f : files)
    if (!f.empty()) merge_meandata(f, sumo_side_path(f), corridor);
}

void Cosimulation::abandon() {
  if (finished_) return;
  finished_ = true;
  try {
    sumo_->close();
  } catch (const SumoError&) {
    // Already gone: what it wrote stays as it is.
  }
  run_.finish();
}

// One tripinfo line per trip that ended, for the whole trip: its start where it departed (LPSim's
// departure, or SUMO's first piece), its end where it arrived, and the sums of both sides' pieces.
void Cosimulation::merge_tripinfo() {
  const Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  std::unordered_map<std::string, uint32_t> visited_ids;
  for (uint32_t v = 0; v < visited_.size(); ++v)
    if (visited_[v]) visited_ids.emplace(d.vehicle_id[v], v);
  std::unordered_map<uint32_t, std::vector<SumoTripPiece>> pieces;
  for (SumoTripPiece& p : read_sumo_tripinfo(sumo_side_path(sumo_tripinfo_))) {
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
    const DepartRecord dep = sim.departure(v);
    TripRecord r;
    const auto held = held_trips_.find(v);
    if (held != held_trips_.end()) {  // it arrived in LPSim, whose record sums LPSim's pieces
      r = held->second;
    } else if (ps != nullptr && !ps->back().vaporized) {  // it arrived in SUMO
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
      if (const TripCounters* c = sim.carried(v)) {  // what LPSim measured of it
        r.route_length = c->route_length;
        r.time_loss = c->time_loss;
        r.waiting_time = static_cast<double>(c->waiting_steps) * dt;
        r.waiting_count = c->waiting_count;
        r.stop_time = static_cast<double>(c->stop_steps) * dt;
      }
    } else {
      continue;  // still on its way when the run ended
    }
    if (dep.lane < 0 && ps != nullptr) {  // it departed in SUMO
      const SumoTripPiece& first = ps->front();
      r.depart = first.depart;
      r.depart_delay = first.depart_delay;
      r.depart_lane = lane_of(first.depart_lane);
      r.depart_pos = static_cast<float>(first.depart_pos);
      r.depart_speed = static_cast<float>(first.depart_speed);
    }
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

}  // namespace lpsim

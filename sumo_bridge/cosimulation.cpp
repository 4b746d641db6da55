#include "sumo_bridge/cosimulation.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "converters/output_file.hpp"
#include "core/error.hpp"
#include "sumo_bridge/sumo_arguments.hpp"

namespace lpsim {

namespace {

// The boundary a co-simulation's run has with SUMO: its run must drive outside the corridor's lanes.
OutsideLink& outside_link_of(Run& run) {
  if (!run.options().outside_lanes)
    throw std::invalid_argument("the co-simulation's run must drive outside the corridor's lanes");
  return run.simulation().outside_link();
}

// The longest coupling period: vehicles cross the boundary once per period, so a longer one would let them
// stand at the boundary for longer than a signal's cycle.
constexpr int64_t kLongestPeriodMs = 60000;
// A vehicle SUMO has not inserted for this long (s) after it was handed over is stuck for good: SUMO retries
// a pending vehicle at the same place for ever, which would keep the run from ending.
constexpr double kLongestPending = 3600;
// SUMO 1.15's LC2013 keeps a look-ahead speed with a memory factor of 1 - 0.1 * action step, asserted
// positive (MSLCM_LC2013::_wantsChange): Debian's build aborts at action steps of 10 s or more.
constexpr int64_t kLc2013LongestStepMs = 10000;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<uint8_t> corridor_lanes(const Network& net, const std::vector<uint32_t>& corridor_edges) {
  std::vector<uint8_t> lanes(net.num_lanes(), 0);
  for (const uint32_t e : corridor_edges)
    for (uint32_t l = net.edge_first_lane[e]; l < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++l)
      lanes[l] = 1;
  return lanes;
}

void refuse_what_cosim_cannot_run(const Scenario& sc, const ConfigSpec& c) {
  if (c.net_file.empty())
    throw InputError("a co-simulation needs the scenario's SUMO files (-c or -n/-r), not a snapshot or CSV");
  // An unfinished trip may be in SUMO, or have pieces on both sides: merging them is not built yet.
  if (c.outputs.tripinfo_write_unfinished || c.outputs.tripinfo_write_undeparted)
    throw InputError(
        std::string(c.outputs.tripinfo_write_undeparted ? "--tripinfo-output.write-undeparted"
                                                        : "--tripinfo-output.write-unfinished") +
        ": a co-simulation's tripinfo holds the trips that ended (unfinished ones are not merged "
        "from both sides yet)");
  // The merge of the two simulators' edgeData (converters/meandata_merge) knows traffic measures only.
  for (const MeanDataSpec& m : sc.mean_data)
    if (m.type == MeanDataType::Emissions)
      throw InputError(m.loc, std::string(m.lane_level ? "laneData" : "edgeData") + " '" + m.id +
                                  "': emissions outputs are not supported in a co-simulation");
}

Cosimulation::Cosimulation(Run& run, const CosimOptions& options)
    : run_(run), net_(run.scenario().network), boundary_(outside_link_of(run)), options_(options) {
  const ConfigSpec& c = run_.config();
  refuse_what_cosim_cannot_run(run_.scenario(), c);
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
  // additional file span the run, as LPSim's intervals do. SUMO resolves their file names against the
  // additional file's folder: absolute ones land where LPSim's are.
  const OutputSpec& o = c.outputs;
  if (!o.edgedata.empty() || !o.lanedata.empty()) {
    mean_data_file_.path = (std::filesystem::temp_directory_path() /
                            ("lpsim-cosim-" + std::to_string(::getpid()) + "-meandata.add.xml"))
                               .string();
    OutputFile add(mean_data_file_.path);
    add.text("<additional>\n");
    if (!o.edgedata.empty()) {
      add.text("    <edgeData id=\"edgedata\"");
      add.attr("file", std::filesystem::absolute(o.edgedata).string());
      add.text("/>\n");
    }
    if (!o.lanedata.empty()) {
      add.text("    <laneData id=\"lanedata\"");
      add.attr("file", std::filesystem::absolute(o.lanedata).string());
      add.text("/>\n");
    }
    add.text("</additional>\n");
    add.close();
  }
  visited_.assign(run_.simulation().demand().size(), 0);
  run_.count_outside([this] { return outside_counts(); });
  run_.hold_trips([this](const TripRecord& r) {
    if (r.vehicle >= visited_.size() || !visited_[r.vehicle]) return false;
    held_trips_[r.vehicle] = r;
    return true;
  });
  sumo_ = start_sumo(options_.mode, options_.sumo_binary,
                     cosim_sumo_arguments(c, sumo_tripinfo_, mean_data_file_.path, options_.sumo_args),
                     options_.answer_timeout_s);
  const int64_t lpsim_ms = run_.options().step_ms;
  const double sumo_step = sumo_->step_length();
  sumo_step_ms_ = std::llround(sumo_step * 1000.0);
  if (sumo_step_ms_ <= 0 || std::fabs(static_cast<double>(sumo_step_ms_) - sumo_step * 1000.0) > 1e-6)
    throw InputError("SUMO's step length " + sumo_number(sumo_step) +
                     " s is not a whole number of milliseconds: no common coupling period with LPSim's " +
                     sumo_number(static_cast<double>(lpsim_ms) / 1000.0) + " s");
  period_ms_ = std::lcm(lpsim_ms, sumo_step_ms_);
  if (period_ms_ > kLongestPeriodMs)
    throw InputError("SUMO's step length " + sumo_number(sumo_step) + " s and LPSim's " +
                     sumo_number(static_cast<double>(lpsim_ms) / 1000.0) +
                     " s have no common multiple up to " + sumo_number(kLongestPeriodMs / 1000.0) +
                     " s to couple them at (the least is " +
                     sumo_number(static_cast<double>(period_ms_) / 1000.0) +
                     " s): give step lengths that divide one another");
  if (sumo_step_ms_ >= kLc2013LongestStepMs)
    throw InputError(
        "SUMO's step length " + sumo_number(sumo_step) +
        " s: SUMO 1.15 aborts on an assertion in its LC2013 lane-change model at action steps of " +
        sumo_number(kLc2013LongestStepMs / 1000.0) + " s or more (give a shorter one)");
  report_.period = static_cast<double>(period_ms_) / 1000.0;
  begin_ms_ = next_sumo_ms_ = run_.simulation().time_ms();
  const double sumo_begin = sumo_->time();
  if (std::fabs(sumo_begin - run_.simulation().time()) > 1e-6)
    throw InputError("SUMO starts at " + sumo_number(sumo_begin) + " s, LPSim at " +
                     sumo_number(run_.simulation().time()) + " s: give both the same --begin");
}

Cosimulation::~Cosimulation() { run_.count_outside(nullptr); }

bool Cosimulation::departs_in_sumo(const InSumo& s) { return s.entry_lane < 0 && s.route_pos == 0; }

// A pending vehicle's step has run in SUMO (it was added to depart at `since`, and SUMO's last step ran at
// its clock less a step): SUMO lists it as pending.
bool Cosimulation::due_in_sumo(const InSumo& s) const {
  return s.since <= sumo_->time() - static_cast<double>(sumo_step_ms_) / 1000.0 + 1e-9;
}

void Cosimulation::count_sumo_departure(uint32_t v, double now) {
  sumo_depart_[v] = now;
  ++outside_.inserted;
  outside_.depart_delay_sum += now - run_.simulation().demand().depart[v];
}

double Cosimulation::depart_time(uint32_t v) const {
  const auto it = sumo_depart_.find(v);
  return it != sumo_depart_.end() ? it->second : run_.simulation().ledger().departure(v).time;
}

// SUMO's side of the summary and statistics: vehicles on its roads or added there after driving in LPSim are
// running; those added to depart there and not yet inserted are waiting.
Run::OutsideCounts Cosimulation::outside_counts() const {
  Run::OutsideCounts o = outside_;
  for (const auto& [id, s] : in_sumo_) ++(s.pending && departs_in_sumo(s) ? o.waiting : o.running);
  return o;
}

Cosimulation::ScratchFile::~ScratchFile() {
  std::error_code ignored;
  if (!path.empty()) std::filesystem::remove(path, ignored);
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
    for (const OutsideLink::HandOut& h : boundary_.hand_outs()) hand_into_sumo(h);
    report_.handover_seconds += seconds_since(t0);
  }
  // SUMO's steps over the same period, one by one, up to the state LPSim is at: its step "at" time t (the one
  // its outputs label t, after which its clock shows t + step) ends in the state LPSim's clock calls t. It
  // lists the arrivals of its last step only. With an end time, the steps SUMO alone runs (those at times
  // before it).
  const int64_t last_ms = sim.time_ms();
  const int64_t end_ms = has_end ? std::llround(run_.config().end * 1000.0) : INT64_MAX;
  for (; next_sumo_ms_ <= last_ms && next_sumo_ms_ < end_ms; next_sumo_ms_ += sumo_step_ms_) {
    const int64_t t = next_sumo_ms_;
    const double now = static_cast<double>(t) / 1000.0;  // the step's time, as SUMO's outputs say
    const auto t0 = std::chrono::steady_clock::now();
    sumo_->step_to(static_cast<double>(t + sumo_step_ms_) / 1000.0);
    report_.sumo_seconds += seconds_since(t0);
    for (const std::string& id : sumo_->arrived()) {
      if (removed_since_step_.count(id)) continue;
      const auto it = in_sumo_.find(id);
      if (it != in_sumo_.end()) arrived_in_sumo(it, now);
    }
    removed_since_step_.clear();
    // What SUMO inserted reports where it is with every step from now on.
    for (const std::string& id : sumo_->departed()) {
      const auto it = in_sumo_.find(id);
      if (it == in_sumo_.end() || !it->second.pending) continue;
      it->second.pending = false;
      --pending_;
      // Inserted in the step at t, as SUMO reports its departure.
      const double inserted = now;
      if (departs_in_sumo(it->second)) count_sumo_departure(it->second.vehicle, inserted);
      report_.longest_boundary_wait = std::max(report_.longest_boundary_wait, inserted - it->second.since);
      it->second.since = inserted;
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

void Cosimulation::arrived_in_sumo(std::unordered_map<std::string, InSumo>::iterator it, double now) {
  if (it->second.pending) {  // inserted and arrived within one step
    --pending_;
    if (departs_in_sumo(it->second)) count_sumo_departure(it->second.vehicle, now);
  }
  ++arrived_in_sumo_;
  ++report_.arrived_in_sumo;
  outside_.arrived = arrived_in_sumo_;
  outside_.travel_time_sum += now - depart_time(it->second.vehicle);
  in_sumo_.erase(it);
}

void Cosimulation::hand_into_sumo(const OutsideLink::HandOut& h) {
  const Simulation& sim = run_.simulation();
  const Demand& d = sim.demand();
  const uint32_t v = h.vehicle;
  SumoEntry e;
  e.id = d.vehicle_id[v];
  e.type = d.types.id[d.vehicle_type[v]];
  for (uint32_t k = d.route_begin[v] + h.route_pos; k < d.route_begin[v] + d.route_length[v]; ++k)
    e.route.push_back(net_.edge_id[d.route_edges[k]]);
  e.speed_factor = d.speed_factor[v];
  // When SUMO is to insert it: a trip departing in the corridor at the time LPSim found it due, as LPSim
  // alone departs it (SUMO inserts it at its first step from then on); a vehicle driving in at SUMO's first
  // step from the time LPSim's state shows it on the corridor's lane, a SUMO step being longer than LPSim's
  // (below: as far on as it drives by then).
  const int64_t now_ms = sim.time_ms();
  const int64_t entry_ms =
      begin_ms_ + (now_ms - begin_ms_ + sumo_step_ms_ - 1) / sumo_step_ms_ * sumo_step_ms_;
  const bool departing = h.lane < 0 && h.route_pos == 0;
  e.depart = static_cast<double>(departing ? now_ms : entry_ms) / 1000.0;
  // Where the trip ends, should it end in SUMO (its route there runs to the trip's last edge).
  switch (static_cast<ArrivalPos>(d.arrival_pos_kind[v])) {
    case ArrivalPos::Given:
      e.arrival_pos = sumo_number(d.arrival_pos[v]);
      break;
    case ArrivalPos::Random:
      e.arrival_pos = "random";
      break;
    case ArrivalPos::Max:
      break;
  }
  if (h.lane >= 0) {
    const float lane_length = net_.lane_length[static_cast<uint32_t>(h.lane)];
    e.lane = static_cast<int>(net_.lane_index[static_cast<uint32_t>(h.lane)]);
    e.pos = position_driven_on<double>(h.pos, h.speed, static_cast<double>(entry_ms - now_ms) / 1000.0,
                                       lane_length);
    e.speed = h.speed;
    // Neither side drives the distance from where LPSim left it to where SUMO inserts it: the trip's
    // route length has it still.
    driven_between_[v] += e.pos - std::min<double>(h.pos, lane_length);
  } else {
    e.lane = -1;
    if (h.route_pos == 0) {  // its trip departs here, as its depart attributes say
      const SumoDepart dep = sumo_depart(d, v);
      e.depart_lane = dep.lane;
      e.depart_pos = dep.pos;
      e.depart_speed = dep.speed;
    } else {  // a teleport's re-entry: at the start of the best lane, standing
      e.depart_lane = "best";
    }
  }
  // The trip's stops on the corridor's edges it drives now (up to the first edge after the corridor, where
  // LPSim takes it back and makes its later stops). On its entry edge only stops it can still brake for.
  const StopTable& stops = d.stops;
  uint32_t visit_end = h.route_pos;
  while (visit_end < d.route_length[v] && corridor_edge(d.route_edges[d.route_begin[v] + visit_end]))
    ++visit_end;
  const double brake = e.speed * e.speed / (2.0 * d.types.decel[d.vehicle_type[v]]) + 1.0;
  for (uint32_t i = stops.first(v); i < stops.last(v); ++i) {
    if (stops.route_pos[i] < h.route_pos || stops.route_pos[i] >= visit_end) continue;
    if (stops.route_pos[i] == h.route_pos && stops.end_pos[i] < e.pos + brake) continue;
    e.stops.push_back({net_.edge_id[d.route_edges[d.route_begin[v] + stops.route_pos[i]]],
                       static_cast<int>(net_.lane_index[stops.lane[i]]), stops.start_pos[i], stops.end_pos[i],
                       stops.duration[i], stops.until[i]});
  }
  sumo_->add(e);
  if (visited_[v] < 255) ++visited_[v];
  InSumo s;
  s.vehicle = v;
  s.route_pos = h.route_pos;
  s.entry_lane = h.lane;
  s.entry_pos = static_cast<float>(e.pos);  // where SUMO is to insert it (on the lane)
  s.since = e.depart;
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
  if (pending_ > 0) {
    std::unordered_set<std::string> pending;
    for (std::string& id : sumo_->pending()) pending.insert(std::move(id));
    for (const auto& [id, s] : in_sumo_) {
      if (!s.pending) continue;
      // SUMO drops a vehicle it will never insert (an error of its own above): that would lose it. One due
      // at a step SUMO has not run yet is not pending there yet.
      if (!pending.count(id) && due_in_sumo(s))
        throw SumoError("SUMO dropped vehicle " + id +
                        " instead of inserting it (SUMO's messages above say why)");
      if (now - s.since > kLongestPending)
        throw SumoError("SUMO has not inserted vehicle " + id + " for " + sumo_number(now - s.since) +
                        " s since LPSim handed it over: no room where it enters, for ever");
      report_.longest_boundary_wait = std::max(report_.longest_boundary_wait, now - s.since);
      if (s.entry_lane >= 0)
        mirror_.push_back(OutsideLink::OutsideVehicle{s.entry_lane, s.entry_pos,
                                                      d.types.length[d.vehicle_type[s.vehicle]], 0.0f});
    }
  }
  std::vector<std::pair<std::string, SumoVehicle>> running = sumo_->watched();
  // In vehicle order: the take-backs queue in it, and the results must not depend on SUMO's order.
  std::vector<std::pair<uint32_t, size_t>> order;
  order.reserve(running.size());
  for (size_t i = 0; i < running.size(); ++i) {
    const auto it = in_sumo_.find(running[i].first);
    if (it == in_sumo_.end())
      throw SumoError("SUMO reports vehicle " + running[i].first + ", which LPSim did not hand to it");
    order.emplace_back(it->second.vehicle, i);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [v, i] : order) {
    const std::string& id = running[i].first;
    const SumoVehicle& q = running[i].second;
    if (q.gone) {  // as an arrival in SUMO's last step
      arrived_in_sumo(in_sumo_.find(id), static_cast<double>(next_sumo_ms_ - sumo_step_ms_) / 1000.0);
      continue;
    }
    InSumo& s = in_sumo_.at(id);
    if (q.edge.empty() || q.edge[0] == ':') continue;  // inside a junction: SUMO's until the next edge
    const auto e = net_.edge_index.find(q.edge);
    if (e == net_.edge_index.end())
      throw SumoError("SUMO has vehicle " + id + " on edge " + q.edge + ", not in LPSim's network");
    const uint32_t edge = e->second;
    if (!corridor_edge(edge)) {
      take_back_or_hold(id, s, edge, q);
      continue;
    }
    const int32_t lane = lpsim_lane(edge, q.lane);
    if (lane < 0) continue;
    // The map LPSim's next step writes shows the state at its end: SUMO's vehicles a period on at their
    // speed (else LPSim's vehicles would follow them a period's distance behind where they are). One that
    // would pass the lane's end stands at it: the next lane is SUMO's too.
    const float ahead = static_cast<float>(q.pos + q.speed * report_.period);
    mirror_.push_back(
        OutsideLink::OutsideVehicle{lane, std::min(ahead, net_.lane_length[static_cast<uint32_t>(lane)]),
                                    d.types.length[d.vehicle_type[v]], static_cast<float>(q.speed)});
  }
  boundary_.mirror_outside_vehicles(mirror_);
}

bool Cosimulation::corridor_edge(uint32_t e) const { return boundary_.outside_edge(e); }

// LPSim keeps the lanes road vehicles use, so SUMO's lane index on an edge (which counts sidewalks and bike
// lanes too) is found among them; -1 for a lane LPSim does not have.
int32_t Cosimulation::lpsim_lane(uint32_t edge, int sumo_index) const {
  for (uint32_t l = net_.edge_first_lane[edge]; l < net_.edge_first_lane[edge] + net_.edge_num_lanes[edge];
       ++l)
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
  if (!boundary_.has_entry_room(edge)) {
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
  // Its piece of the trip in SUMO is in SUMO's tripinfo (merged at the end).
  // On the lane SUMO chose for its route (SUMO's own lane-change model got it there), or any best lane
  // where LPSim does not have that lane.
  boundary_.take_back(s.vehicle, rp, lpsim_lane(edge, q.lane), static_cast<float>(q.pos),
                      static_cast<float>(q.speed));
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
    const uint8_t st = sim.ledger().status(v);
    if (st == kMigrated)
      ++migrated;
    else if (st == kArrived)
      ++ended;
    else
      ++c.in_lpsim;
  }
  uint64_t not_yet_due = 0;
  for (const auto& [id, s] : in_sumo_) {
    ++(s.pending ? c.in_handover : c.in_sumo);
    not_yet_due += s.pending && !due_in_sumo(s) ? 1 : 0;
  }
  c.arrived = ended + arrived_in_sumo_;
  const auto fail = [](const std::string& what) { throw std::logic_error("co-simulation census: " + what); };
  if (migrated != in_sumo_.size() + arrived_in_sumo_)
    fail(std::to_string(migrated) + " vehicles handed to SUMO by LPSim's account, " +
         std::to_string(in_sumo_.size()) + " in SUMO + " + std::to_string(arrived_in_sumo_) +
         " arrived there by the bridge's");
  const uint64_t sumo_running = static_cast<uint64_t>(sumo_->running());
  const uint64_t sumo_pending = sumo_->pending().size();
  if (sumo_running != c.in_sumo || sumo_pending != c.in_handover - not_yet_due)
    fail("SUMO runs " + std::to_string(sumo_running) + " and has " + std::to_string(sumo_pending) +
         " pending; the bridge counts " + std::to_string(c.in_sumo) + " and " +
         std::to_string(c.in_handover));
  if (c.in_lpsim + c.in_sumo + c.in_handover + c.arrived != c.loaded)
    fail(std::to_string(c.loaded) + " loaded but " +
         std::to_string(c.in_lpsim + c.in_sumo + c.in_handover + c.arrived) + " accounted for");
  return c;
}

void Cosimulation::finish() {
  if (finished_) return;
  finished_ = true;
  for (const auto& [id, s] : in_sumo_)
    if (s.pending || s.held) ++report_.in_handover_at_end;
  sumo_->close();
  merge_tripinfo(false);
  run_.finish();
  merge_edge_data();
}

void Cosimulation::abandon() {
  if (finished_) return;
  finished_ = true;
  try {
    sumo_->close();
  } catch (const SumoError&) {
    // Already gone: what it wrote stays as it is.
  }
  // The trips that ended, with every piece SUMO drove of them in what SUMO wrote before it failed, are
  // complete: they go into the tripinfo (a trip that reads wrong is worse than one left out, so the others
  // stay out).
  try {
    merge_tripinfo(true);
  } catch (const std::exception&) {
    // SUMO's file cannot be read at all: only LPSim's own trips.
  }
  run_.finish();
}

}  // namespace lpsim

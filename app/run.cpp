#include "app/run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/emission_models.hpp"
#include "app/interrupt.hpp"
#include "app/state_file.hpp"
#include "core/error.hpp"
#include "engine/state_archive.hpp"

namespace lpsim {

namespace {

// Times are sums of step lengths in double: compare them with this slack.
constexpr double kTimeSlack = 1e-9;

std::string state_file_name(const ConfigSpec& c, double t) {
  char time[64];
  std::snprintf(time, sizeof time, "%.2f", t);
  return c.save_state_prefix + "_" + time + c.save_state_suffix;
}

// What a saved state cannot carry yet, refused before anything is written.
void refuse_what_states_cannot_resume(const ConfigSpec& c) {
  if (!Run::keeps_states(c)) return;
}

const char* teleport_cause(TeleportCause cause) {
  return cause == TeleportCause::Yield ? "yield" : cause == TeleportCause::WrongLane ? "wrong lane" : "jam";
}

}  // namespace

bool Run::keeps_states(const ConfigSpec& c) {
  return !c.save_state_times.empty() || c.save_state_period > 0 || !c.load_state.empty() ||
         c.save_state_on_signal;
}

Run::Run(Scenario scenario, const ConfigSpec& config, SimulationOptions options)
    : scenario_(std::move(scenario)),
      config_(config),
      mean_data_(mean_data_outputs(scenario_, config.outputs)),
      options_(counting_lanes(options, mean_data_)),
      digest_(keeps_states(config) ? scenario_digest(scenario_, options_) : 0),
      sim_(scenario_.network, std::move(scenario_.demand), options_) {
  refuse_what_states_cannot_resume(config_);
  if (!config_.load_state.empty()) {
    resume(config_.load_state);
    return;
  }
  open_outputs(nullptr);
  add_own_actions();
  add_state_saves();
  actions_.run_begin(sim_.time(), end_time());
}

Run::~Run() = default;

std::vector<Run::MeanDataOutput> Run::mean_data_outputs(const Scenario& scenario, const OutputSpec& outputs) {
  std::vector<MeanDataSpec> specs = scenario.mean_data;
  if (!outputs.edgedata.empty())
    specs.push_back(MeanDataSpec{"edgedata", outputs.edgedata, false, -1, -1, -1, false, false, {}});
  if (!outputs.lanedata.empty())
    specs.push_back(MeanDataSpec{"lanedata", outputs.lanedata, true, -1, -1, -1, false, false, {}});
  std::vector<MeanDataOutput> out(specs.size());
  for (size_t k = 0; k < specs.size(); ++k) {
    if (specs[k].type == MeanDataType::Emissions) check_emission_models(scenario.demand.types, specs[k]);
    out[k].spec = std::move(specs[k]);
  }
  return out;
}

bool Run::needs_lane_counters(const Scenario& scenario, const OutputSpec& outputs) {
  return counting_lanes(SimulationOptions{}, mean_data_outputs(scenario, outputs)).lane_counters;
}

bool Run::needs_emission_sums(const Scenario& scenario, const OutputSpec& outputs) {
  return counting_lanes(SimulationOptions{}, mean_data_outputs(scenario, outputs)).emission_sums;
}

SimulationOptions Run::counting_lanes(SimulationOptions options, const std::vector<MeanDataOutput>& outputs) {
  options.lane_counters = options.emission_sums = false;
  for (const MeanDataOutput& m : outputs)
    (m.spec.type == MeanDataType::Emissions ? options.emission_sums : options.lane_counters) = true;
  return options;
}

size_t Run::continued_outputs() const {
  const OutputSpec& out = config_.outputs;
  size_t n = mean_data_.size();
  for (const std::string* o : {&out.fcd, &out.tripinfo, &out.summary, &config_.jam_report})
    n += o->empty() ? 0 : 1;
  return n;
}

void Run::open_outputs(const std::vector<int64_t>* continue_at) {
  const OutputSpec& out = config_.outputs;
  if (continue_at && continue_at->size() != continued_outputs())
    throw std::logic_error("open_outputs: lengths for " + std::to_string(continue_at->size()) + " outputs, " +
                           std::to_string(continued_outputs()) + " to continue");
  size_t next = 0;
  auto at = [&] { return continue_at ? (*continue_at)[next++] : int64_t{-1}; };
  if (!out.fcd.empty()) fcd_ = std::make_unique<FcdWriter>(out.fcd, scenario_.network, demand(), at());
  if (!out.tripinfo.empty()) {
    std::vector<std::string> devices{"tripinfo"};
    if (fcd_) devices.push_back("fcd");
    tripinfo_ = std::make_unique<TripinfoWriter>(out.tripinfo, scenario_.network, demand(), devices, at());
  }
  if (!out.summary.empty()) summary_ = std::make_unique<SummaryWriter>(out.summary, at());
  if (!out.statistic.empty()) statistic_ = std::make_unique<StatisticWriter>(out.statistic);
  if (!config_.jam_report.empty())
    jam_ = std::make_unique<JamRecorder>(config_.jam_report, config_.jam_report_stop_time, scenario_.network,
                                         sim_, at());
  for (MeanDataOutput& m : mean_data_) {
    m.writer =
        std::make_unique<MeanDataWriter>(m.spec, scenario_.network, demand(), options_.volumetric_fuel, at());
    m.interval_begin = m.spec.begin >= 0 ? m.spec.begin : sim_.time();
    // Zero, not the counters now: vehicles inserted at the begin time belong to the first interval.
    m.at_begin.resize(scenario_.network.num_lanes(), options_.emission_sums);
  }
}

void Run::step() {
  if (closed_) throw std::logic_error("Run::step() after finish()");
  sim_.step();
  actions_.run_due(sim_.time(), end_time());
}

void Run::add_action(std::string name, StepTrigger trigger, StepActions::Action action) {
  actions_.add(std::move(name), std::move(trigger), std::move(action));
}

// The Run's own actions, in the order they run after a step. The step's accounts (teleport warnings, totals,
// the jam recorder) skip the begin time; the outputs also write the state at the begin time.
void Run::add_own_actions() {
  using AtBegin = StepActions::AtBegin;
  if (!config_.no_warnings)
    actions_.add(
        "teleport warnings", StepTrigger::every_step(), [this](double) { warn_teleports(); }, AtBegin::Skip);
  actions_.add(
      "totals", StepTrigger::every_step(),
      [this](double) {
        for (const TeleportEvent& t : sim_.teleport_events())
          ++(t.cause == TeleportCause::Yield       ? totals_.teleports_yield
             : t.cause == TeleportCause::WrongLane ? totals_.teleports_wrong_lane
                                                   : totals_.teleports_jam);
        totals_.peak_running = std::max<uint64_t>(totals_.peak_running, sim_.counts().running);
      },
      AtBegin::Skip);
  if (jam_)
    actions_.add(
        "jam report", StepTrigger::every_step(), [this](double) { jam_->after_step(sim_); }, AtBegin::Skip);
  if (fcd_) {
    const double period = config_.outputs.fcd_period;
    actions_.add("fcd", period > 0 ? StepTrigger::every(period, sim_.time()) : StepTrigger::every_step(),
                 [this](double) {
                   sim_.sample_fcd(frame_);
                   fcd_->write(frame_);
                 });
  }
  // Every trip that ended counts in the totals, written or not.
  actions_.add("tripinfo", StepTrigger::every_step(), [this](double) {
    for (const TripRecord& r : sim_.take_finished_trips()) {
      if (hold_trip_ && hold_trip_(r)) continue;
      write_trip(r);
    }
  });
  if (summary_) actions_.add("summary", StepTrigger::every_step(), [this](double) { write_summary_row(); });
  // An interval [b, b + period) holds SUMO's steps b .. b + period - step, whose states the simulation shows
  // at those same times: it closes once the state at its last step is counted, when the step's end reaches
  // its end.
  for (MeanDataOutput& m : mean_data_)
    if (m.spec.period > 0)
      actions_.add(
          "interval " + m.spec.id,
          StepTrigger::every(m.spec.period, m.interval_begin + m.spec.period, StepTrigger::Clock::StepEnd),
          [this, &m](double until) {
            close_interval(m, until);
            interval_closed_ = true;
          });
  // At simulated times, not wall times: a gzip file's bytes then depend on the run alone.
  actions_.add("flush", StepTrigger::every_step(), [this](double) {
    if (interval_closed_) flush_outputs();
    interval_closed_ = false;
  });
}

void Run::step_until(double t) {
  while (!done() && sim_.time() + sim_.step_length() <= t + kTimeSlack) step();
}

bool Run::done() const {
  if (config_.end >= 0) return sim_.time() + sim_.step_length() > config_.end - kTimeSlack;
  return sim_.finished();
}

void Run::finish() {
  if (closed_) return;
  const OutputSpec& o = config_.outputs;
  if (tripinfo_ && (o.tripinfo_write_unfinished || o.tripinfo_write_undeparted)) write_unfinished_trips();
  if (statistic_) {
    statistic_->write(statistics());
    statistic_->close();
  }
  for (MeanDataOutput& m : mean_data_) {
    close_interval(m, end_time());
    m.writer->close();
  }
  if (fcd_) fcd_->close();
  if (tripinfo_) tripinfo_->close();
  if (summary_) summary_->close();
  if (jam_) jam_->finish(sim_);
  closed_ = true;
}

void Run::write_summary_row() {
  SummaryRow row = sim_.summary_row();
  if (outside_) {
    // SUMO's vehicles join LPSim's; the means over inserted and arrived vehicles take in SUMO's sums (the
    // speeds stay LPSim's: they are sampled from its running vehicles).
    const OutsideCounts o = outside_();
    const double delay_sum = row.mean_waiting_time * static_cast<double>(row.inserted) + o.depart_delay_sum;
    const double travel_sum = row.mean_travel_time * static_cast<double>(row.arrived) + o.travel_time_sum;
    row.inserted += o.inserted;
    row.running += o.running;
    row.waiting += o.waiting;
    row.arrived += o.arrived;
    row.ended += o.arrived;
    row.mean_waiting_time = row.inserted > 0 ? delay_sum / static_cast<double>(row.inserted) : 0;
    row.mean_travel_time = row.arrived > 0 ? travel_sum / static_cast<double>(row.arrived) : 0;
  }
  summary_->write(row);
}

void Run::write_trip(const TripRecord& r) {
  if (closed_) throw std::logic_error("Run::write_trip() after finish()");
  ++totals_.trips;
  totals_.duration += r.arrival - r.depart;
  totals_.route_length += r.route_length;
  totals_.waiting += r.waiting_time;
  totals_.time_loss += r.time_loss;
  totals_.depart_delay += r.depart_delay;
  if (r.arrival > r.depart) totals_.speed += r.route_length / (r.arrival - r.depart);
  if (tripinfo_) tripinfo_->write(r);
}

// SUMO's write-unfinished: the trips still on their way count in the statistics like the ended ones (their
// duration up to the end); write-undeparted adds those that never departed, whose mean delay is the
// statistic's departDelayWaiting.
void Run::write_unfinished_trips() {
  double waiting_delay = 0;
  uint64_t waiting = 0;
  for (const TripRecord& r : sim_.unfinished_trips(end_time(), config_.outputs.tripinfo_write_undeparted)) {
    if (r.unfinished == kTripRunning) {
      write_trip(r);
    } else {
      tripinfo_->write(r);
      waiting_delay += r.depart_delay;
      ++waiting;
    }
  }
  if (waiting > 0) depart_delay_waiting_ = waiting_delay / static_cast<double>(waiting);
}

// SUMO's warning for each vehicle that starts a teleport; the time is the end of the step in which its
// clock ran out.
void Run::warn_teleports() const {
  for (const TeleportEvent& t : sim_.teleport_events())
    std::fprintf(stderr, "Warning: Teleporting vehicle '%s'; waited too long (%s%s), lane='%s', time=%.2f.\n",
                 demand().vehicle_id[t.vehicle].c_str(), teleport_cause(t.cause),
                 t.highway ? ", highway" : "", scenario_.network.lane_id[t.lane].c_str(), sim_.time());
}

void Run::close_interval(MeanDataOutput& m, double until) {
  if (until <= m.interval_begin) return;
  LaneCounters d = counters_since(sim_.collect_lane_counters(), m.at_begin);
  MeanDataInterval iv{m.interval_begin, until, sim_.step_length(), &d};
  m.writer->write(iv);
  m.interval_begin = until;
  m.at_begin = sim_.collect_lane_counters();
}

void Run::flush_outputs() {
  for (MeanDataOutput& m : mean_data_) m.writer->flush();
  if (fcd_) fcd_->flush();
  if (tripinfo_) tripinfo_->flush();
  if (summary_) summary_->flush();
  if (jam_) jam_->flush();
}

// The outputs a resumed run continues, in open_outputs()'s order: each handed to its file, and the file's
// length then.
std::vector<int64_t> Run::output_sizes() {
  std::vector<int64_t> sizes;
  if (fcd_) sizes.push_back(static_cast<int64_t>(fcd_->continue_point()));
  if (tripinfo_) sizes.push_back(static_cast<int64_t>(tripinfo_->continue_point()));
  if (summary_) sizes.push_back(static_cast<int64_t>(summary_->continue_point()));
  if (jam_) sizes.push_back(static_cast<int64_t>(jam_->continue_point()));
  for (const MeanDataOutput& m : mean_data_)
    sizes.push_back(static_cast<int64_t>(m.writer->continue_point()));
  return sizes;
}

// The Run's own part of a state: its totals, its open edgeData/laneData intervals and the jam report's
// episodes.
template <class A>
void Run::visit_state(A& a) {
  a(totals_);
  a(depart_delay_waiting_);
  for (MeanDataOutput& m : mean_data_) {
    a(m.interval_begin);
    a(m.at_begin);
  }
  if (jam_) a(*jam_);
}

// SUMO's --save-state.times (each with the next of --save-state.files, else named by its time) and
// --save-state.period, due on the state's clock after every other action of the step: the state saved at
// t is the one the outputs wrote for t, and a run resumed from it goes on with the step after t.
void Run::add_state_saves() {
  own_actions_ = actions_.size();
  const ConfigSpec& c = config_;
  const double now = sim_.time();
  auto named = [&c](double t) { return state_file_name(c, t); };
  if (!c.save_state_files.empty() && c.save_state_files.size() != c.save_state_times.size())
    throw InputError("--save-state.files names " + std::to_string(c.save_state_files.size()) + " files for " +
                     std::to_string(c.save_state_times.size()) + " times of --save-state.times");
  std::vector<std::pair<double, std::string>> due;
  for (size_t k = 0; k < c.save_state_times.size(); ++k) {
    const double t = c.save_state_times[k];
    if (t > now + kTimeSlack)
      due.emplace_back(t, c.save_state_files.empty() ? named(t) : c.save_state_files[k]);
  }
  std::sort(due.begin(), due.end());
  if (!due.empty()) {
    std::vector<double> times;
    for (const auto& d : due) times.push_back(d.first);
    actions_.add(
        "save state", StepTrigger::at(times),
        [this, due](double when) {
          for (const auto& [t, path] : due)
            if (std::abs(t - when) < kTimeSlack) save_state(path);
        },
        StepActions::AtBegin::Skip);
  }
  if (c.save_state_period > 0) {
    const double begin = options_.begin, p = c.save_state_period;
    const double first = begin + (std::floor((now - begin) / p + kTimeSlack) + 1) * p;
    actions_.add(
        "save state every period", StepTrigger::every(p, first),
        [this, named](double when) { save_state(named(when)); }, StepActions::AtBegin::Skip);
  }
}

std::string Run::save_state_now() {
  const std::string path = state_file_name(config_, sim_.time());
  save_state(path);
  return path;
}

void Run::save_state(const std::string& path) {
  flush_outputs();
  StateOut a;
  std::vector<int64_t> sizes = output_sizes();
  a(sizes);
  visit_state(a);
  actions_.visit_state(a, own_actions_);
  std::vector<uint8_t> sim = sim_.save_state();
  a.raw(sim);
  write_state_file(path, digest_, a.bytes());
}

// The saved run's outputs are continued where it had written them to; its triggers fire on as they would
// have; no output is written for the state resumed from (the saved run wrote it).
void Run::resume(const std::string& path) {
  try {
    const std::vector<uint8_t> payload = read_state_file(path, digest_);
    StateIn a(payload.data(), payload.size(), path);
    std::vector<int64_t> sizes;
    a(sizes);
    const size_t outputs = continued_outputs();
    if (sizes.size() != outputs)
      a.fail("saved with " + std::to_string(sizes.size()) + " outputs, resumed with " +
             std::to_string(outputs));
    open_outputs(&sizes);
    visit_state(a);
    add_own_actions();
    actions_.visit_state(a, actions_.size());
    std::vector<uint8_t> sim;
    a.raw(sim);
    if (!a.done()) a.fail("bytes left after the state's end");
    sim_.load_state(sim, path);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(SourceLoc{path, 0}, std::string("not a state of this run: ") + e.what());
  }
  std::fprintf(stderr, "lpsim: resumed from %s at time %.2f\n", path.c_str(), sim_.time());
  add_state_saves();
}

Simulation::Counts Run::counts() const {
  Simulation::Counts c = sim_.counts();
  if (outside_) {
    const OutsideCounts o = outside_();
    c.inserted += o.inserted;
    c.running += o.running;
    c.waiting += o.waiting;
    c.arrived += o.arrived;
  }
  return c;
}

RunStatistics Run::statistics() const {
  const Simulation::Counts c = counts();
  RunStatistics s;
  s.loaded = c.loaded;
  s.inserted = c.inserted;
  s.running = c.running;
  s.waiting = c.waiting;
  s.teleports_jam = totals_.teleports_jam;
  s.teleports_yield = totals_.teleports_yield;
  s.teleports_wrong_lane = totals_.teleports_wrong_lane;
  s.trips = totals_.trips;
  s.route_length = totals_.route_length;
  s.duration = totals_.duration;
  s.waiting_time = totals_.waiting;
  s.time_loss = totals_.time_loss;
  s.depart_delay = totals_.depart_delay;
  s.speed = totals_.speed;
  s.depart_delay_waiting = depart_delay_waiting_;
  return s;
}

void print_run_report(std::FILE* out, const Run& run, double wall, double load_seconds,
                      const char* interrupted_by) {
  const Simulation& sim = run.simulation();
  const Simulation::Counts c = run.counts();
  const Run::Totals& totals = run.totals();
  std::fprintf(out, "Simulation ended at time: %.2f\n", run.end_time());
  if (interrupted_by != nullptr)
    std::fprintf(out, "Reason: Interrupted by %s.\n", interrupted_by);
  else
    // As SUMO: with an end time the run goes on to it even after the last vehicle has left.
    std::fprintf(out, "Reason: %s\n",
                 run.config().end < 0 ? "All vehicles have left the simulation."
                                      : "The final simulation step has been reached.");
  std::fprintf(out, "Performance:\n Duration: %.3fs (load %.3fs)\n", wall, load_seconds);
  std::fprintf(out, " Real time factor: %.6g\n",
               wall > 0 ? (run.end_time() - run.options().begin) / wall : 0.0);
  std::fprintf(out, " UPS: %.6f\n", wall > 0 ? static_cast<double>(c.vehicle_updates) / wall : 0.0);
  // The steps alone, without building the simulation and its first insertions (which do not shrink with
  // more threads or parts).
  const double steps = sim.step_seconds();
  std::fprintf(out, " Steps: %.3fs (UPS of the steps %.6f)\n", steps,
               steps > 0 ? static_cast<double>(c.vehicle_updates) / steps : 0.0);
  std::fprintf(out, " Vehicle updates: %llu (peak running %llu)\n",
               static_cast<unsigned long long>(c.vehicle_updates),
               static_cast<unsigned long long>(totals.peak_running));
  std::fprintf(out, " Threads: %d\n", run.options().threads);
  const std::vector<PartStats> parts = sim.link().part_stats();
  if (!parts.empty()) {
    // Per part: its share of the work, what crossed its cuts, and the time its exchanges took (waiting for
    // slower parts included) against its steps' wall time.
    std::fprintf(out, "Partitions: %zu parts (threads per part: %d)\n", parts.size(), run.options().threads);
    for (size_t p = 0; p < parts.size(); ++p) {
      const PartStats& ps = parts[p];
      std::fprintf(out,
                   " Part %zu: vehicle updates %llu, migrations out %llu, exchanged %.3f MB in %llu rounds, "
                   "step %.3fs of which exchanges %.3fs (%.1f%%), outputs %.3fs\n",
                   p, static_cast<unsigned long long>(ps.vehicle_updates),
                   static_cast<unsigned long long>(ps.migrations), static_cast<double>(ps.bytes_sent) / 1e6,
                   static_cast<unsigned long long>(ps.rounds), ps.step_seconds, ps.exchange_seconds,
                   ps.step_seconds > 0 ? 100.0 * ps.exchange_seconds / ps.step_seconds : 0.0,
                   ps.gather_seconds);
    }
  }
  std::fprintf(out,
               "Vehicles:\n Inserted: %llu (Loaded: %llu)\n Running: %llu\n Waiting: %llu\n Arrived: %llu\n",
               static_cast<unsigned long long>(c.inserted), static_cast<unsigned long long>(c.loaded),
               static_cast<unsigned long long>(c.running), static_cast<unsigned long long>(c.waiting),
               static_cast<unsigned long long>(c.arrived));
  if (c.removed)
    std::fprintf(out, " Removed (departure before begin or no lane for its class): %llu\n",
                 static_cast<unsigned long long>(c.removed));
  if (c.discarded)
    std::fprintf(out, " Discarded (not inserted within --max-depart-delay): %llu\n",
                 static_cast<unsigned long long>(c.discarded));
  if (c.cancelled)
    std::fprintf(out, " Cancelled (removed by a command before departing): %llu\n",
                 static_cast<unsigned long long>(c.cancelled));
  std::fprintf(out, "Teleports: %llu\n", static_cast<unsigned long long>(c.teleports));
  if (totals.trips > 0) {
    const double n = static_cast<double>(totals.trips);
    std::fprintf(
        out,
        "Statistics (avg of %llu):\n RouteLength: %.2f\n Duration: %.2f\n WaitingTime: %.2f\n TimeLoss: "
        "%.2f\n"
        " DepartDelay: %.2f\n",
        static_cast<unsigned long long>(totals.trips), totals.route_length / n, totals.duration / n,
        totals.waiting / n, totals.time_loss / n, totals.depart_delay / n);
  }
}

void report_run_end(const Run& run, double wall_seconds, double load_seconds, int signal) {
  if (signal != 0)
    std::fprintf(stderr, "lpsim: interrupted by %s at time %.2f; outputs closed\n", signal_name(signal),
                 run.end_time());
  print_run_report(stdout, run, wall_seconds, load_seconds, signal != 0 ? signal_name(signal) : nullptr);
}

}  // namespace lpsim

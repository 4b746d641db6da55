// `lpsim run`: load, simulate, write SUMO outputs, print a SUMO-like summary.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "converters/fcd_writer.hpp"
#include "converters/mean_data_writer.hpp"
#include "converters/summary_writer.hpp"
#include "converters/tripinfo_writer.hpp"
#include "engine/device_select.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

namespace {

// One edgeData/laneData definition: its writer, its interval and the cumulative counters at the interval's
// start (the simulation's counters only ever grow; an interval is the difference).
struct MeanDataOutput {
  MeanDataSpec spec;
  std::unique_ptr<MeanDataWriter> writer;
  double interval_begin = 0;
  LaneCounters at_begin;
};

struct RunTotals {
  double duration = 0, route_length = 0, waiting = 0, time_loss = 0, depart_delay = 0;
  uint64_t trips = 0;
  uint64_t peak_running = 0;
};

// SUMO's warning for each vehicle that starts a teleport; the time is the end of the step in which its
// clock ran out.
void warn_teleports(const Simulation& sim, const Network& net, const Demand& demand) {
  for (const TeleportEvent& t : sim.teleport_events()) {
    const char* cause = t.cause == TeleportCause::Yield       ? "yield"
                        : t.cause == TeleportCause::WrongLane ? "wrong lane"
                                                              : "jam";
    std::fprintf(stderr, "Warning: Teleporting vehicle '%s'; waited too long (%s), lane='%s', time=%.2f.\n",
                 demand.vehicle_id[t.vehicle].c_str(), cause, net.lane_id[t.lane].c_str(), sim.time());
  }
}

void print_progress(const Simulation& sim, double wall, double end) {
  const auto& c = sim.counts();
  const double ups = wall > 0 ? static_cast<double>(c.vehicle_updates) / wall : 0;
  std::fprintf(stderr, "\rt=%.2f running %llu arrived %llu waiting %llu  %.3g veh-updates/s", sim.time(),
               static_cast<unsigned long long>(c.running), static_cast<unsigned long long>(c.arrived),
               static_cast<unsigned long long>(c.waiting), ups);
  if (end > 0 && sim.time() > 0 && wall > 0) {
    const double eta = wall / std::max(1e-9, sim.time()) * std::max(0.0, end - sim.time());
    std::fprintf(stderr, "  ETA %.0f s", eta);
  }
  std::fprintf(stderr, "   ");
  std::fflush(stderr);
}

}  // namespace

int command_run(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config);

  SimulationOptions opt = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  opt.gpu = device.gpu;
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());
  const OutputSpec& out = config.outputs;
  std::vector<MeanDataSpec> specs = sc.mean_data;
  if (!out.edgedata.empty())
    specs.push_back(MeanDataSpec{"edgedata", out.edgedata, false, -1, -1, -1, false, false, {}});
  if (!out.lanedata.empty())
    specs.push_back(MeanDataSpec{"lanedata", out.lanedata, true, -1, -1, -1, false, false, {}});
  opt.lane_counters = !specs.empty();
  const auto wall0 = std::chrono::steady_clock::now();
  Simulation sim(sc.network, sc.demand, opt);

  std::unique_ptr<FcdWriter> fcd;
  std::unique_ptr<TripinfoWriter> tripinfo;
  std::unique_ptr<SummaryWriter> summary;
  if (!out.fcd.empty()) fcd = std::make_unique<FcdWriter>(out.fcd, sc.network, sc.demand);
  if (!out.tripinfo.empty()) {
    std::vector<std::string> devices{"tripinfo"};
    if (fcd) devices.push_back("fcd");
    tripinfo = std::make_unique<TripinfoWriter>(out.tripinfo, sc.network, sc.demand, devices);
  }
  if (!out.summary.empty()) summary = std::make_unique<SummaryWriter>(out.summary);
  std::vector<MeanDataOutput> mean;
  for (auto& s : specs) {
    MeanDataOutput m;
    m.spec = s;
    m.writer = std::make_unique<MeanDataWriter>(s, sc.network, sc.demand);
    m.interval_begin = s.begin >= 0 ? s.begin : sim.time();
    // Zero, not the counters now: vehicles inserted at the begin time belong to the first interval.
    m.at_begin.resize(sc.network.num_lanes());
    mean.push_back(std::move(m));
  }

  const double end = config.end;
  const bool tty = isatty(fileno(stderr)) != 0;
  RunTotals totals;
  FcdFrame frame;
  double next_fcd = sim.time();
  auto emit = [&]() {
    if (fcd && sim.time() + 1e-9 >= next_fcd) {
      sim.sample_fcd(frame);
      fcd->write(frame);
      next_fcd = out.fcd_period > 0 ? next_fcd + out.fcd_period : sim.time();
    }
    for (const TripRecord& r : sim.take_finished_trips()) {
      ++totals.trips;
      totals.duration += r.arrival - r.depart;
      totals.route_length += r.route_length;
      totals.waiting += r.waiting_time;
      totals.time_loss += r.time_loss;
      totals.depart_delay += r.depart_delay;
      if (tripinfo) tripinfo->write(r);
    }
    if (summary) summary->write(sim.summary_row());
  };
  auto close_interval = [&](MeanDataOutput& m, double until) {
    if (until <= m.interval_begin) return;
    LaneCounters d = counters_since(sim.lane_counters(), m.at_begin);
    MeanDataInterval iv{m.interval_begin, until, config.step_length, &d};
    m.writer->write(iv);
    m.interval_begin = until;
    m.at_begin = sim.lane_counters();
  };

  emit();
  auto last_progress = std::chrono::steady_clock::now();
  // As SUMO: with an end time the last step simulated starts at end - step (outputs run to end - step).
  while (!(end >= 0 ? sim.time() + config.step_length > end - 1e-9 : sim.finished())) {
    sim.step();
    if (!config.no_warnings) warn_teleports(sim, sc.network, sc.demand);
    totals.peak_running = std::max<uint64_t>(totals.peak_running, sim.counts().running);
    emit();
    for (auto& m : mean)
      if (m.spec.period > 0 && sim.time() + 1e-9 >= m.interval_begin + m.spec.period)
        close_interval(m, m.interval_begin + m.spec.period);
    if (tty) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_progress > std::chrono::milliseconds(500)) {
        last_progress = now;
        print_progress(sim, std::chrono::duration<double>(now - wall0).count(), end);
      }
    }
  }
  for (auto& m : mean) {
    close_interval(m, sim.time());
    m.writer->close();
  }
  if (fcd) fcd->close();
  if (tripinfo) tripinfo->close();
  if (summary) summary->close();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (tty) std::fprintf(stderr, "\n");

  const auto& c = sim.counts();
  std::printf("Simulation ended at time: %.2f\n", sim.time());
  std::printf("Reason: %s\n", sim.finished() ? "All vehicles have left the simulation."
                                             : "The final simulation step has been reached.");
  std::printf("Performance:\n Duration: %.3fs (load %.3fs)\n", wall, sc.load_seconds);
  std::printf(" Real time factor: %.6g\n", wall > 0 ? (sim.time() - config.begin) / wall : 0.0);
  std::printf(" UPS: %.6f\n", wall > 0 ? static_cast<double>(c.vehicle_updates) / wall : 0.0);
  std::printf(" Vehicle updates: %llu (peak running %llu)\n",
              static_cast<unsigned long long>(c.vehicle_updates),
              static_cast<unsigned long long>(totals.peak_running));
  std::printf(" Threads: %d\n", opt.threads);
  std::printf("Vehicles:\n Inserted: %llu (Loaded: %llu)\n Running: %llu\n Waiting: %llu\n Arrived: %llu\n",
              static_cast<unsigned long long>(c.inserted), static_cast<unsigned long long>(c.loaded),
              static_cast<unsigned long long>(c.running), static_cast<unsigned long long>(c.waiting),
              static_cast<unsigned long long>(c.arrived));
  if (c.removed)
    std::printf(" Removed (departure before begin or no car lane): %llu\n",
                static_cast<unsigned long long>(c.removed));
  std::printf("Teleports: %llu\n", static_cast<unsigned long long>(c.teleports));
  if (totals.trips > 0) {
    const double n = static_cast<double>(totals.trips);
    std::printf(
        "Statistics (avg of %llu):\n RouteLength: %.2f\n Duration: %.2f\n WaitingTime: %.2f\n TimeLoss: "
        "%.2f\n"
        " DepartDelay: %.2f\n",
        static_cast<unsigned long long>(totals.trips), totals.route_length / n, totals.duration / n,
        totals.waiting / n, totals.time_loss / n, totals.depart_delay / n);
  }
  return 0;
}

}  // namespace lpsim

// `lpsim run`: load, simulate, write SUMO outputs, print a SUMO-like summary.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "app/commands.hpp"
#include "app/device_select.hpp"
#include "app/output_paths.hpp"
#include "app/run.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"

namespace lpsim {

namespace {

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
  const Scenario sc = scenario_from_args(args, &config);
  refuse_overwrites(sc, CliCommand::Run);

  SimulationOptions options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  options.gpu = device.gpu;
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());

  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  const double load_seconds = sc.load_seconds;
  Run run(std::move(sc), config, options);
  const bool tty = isatty(fileno(stderr)) != 0;
  auto last_progress = Clock::now();
  while (!run.done()) {
    run.step();
    if (!tty) continue;
    const auto now = Clock::now();
    if (now - last_progress > std::chrono::milliseconds(500)) {
      last_progress = now;
      print_progress(run.simulation(), std::chrono::duration<double>(now - wall0).count(), config.end);
    }
  }
  run.finish();
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  if (tty) std::fprintf(stderr, "\n");
  print_run_report(stdout, run, wall, load_seconds);
  return 0;
}

}  // namespace lpsim

// `lpsim run`: load, simulate, write SUMO outputs, print a SUMO-like summary. SIGINT, SIGTERM and SIGHUP
// stop it at the end of the current step with every output closed well-formed (as SUMO does on Ctrl-C), one
// line on stderr and exit status 128 + the signal.
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "app/commands.hpp"
#include "app/device_select.hpp"
#include "app/interrupt.hpp"
#include "app/output_paths.hpp"
#include "app/progress_log.hpp"
#include "app/run.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"

namespace lpsim {

int command_run(const std::vector<std::string>& args) {
  ConfigSpec config;
  // Loading writes nothing, so a signal until the Run is built may end the process as usual.
  Scenario sc = scenario_from_args(args, &config);
  refuse_overwrites(sc, CliCommand::Run);

  SimulationOptions options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  options.gpu = device.gpu;
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());

  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  const double load_seconds = sc.load_seconds;
  // From here on a signal is recorded, not fatal: the Run's constructor creates the output files, and the
  // loop below stops at the first step boundary after a signal, so that finish() closes them well-formed.
  const InterruptGuard interrupt;
  ProgressLog progress(stderr, isatty(fileno(stderr)) != 0, config.no_step_log, config.progress_interval,
                       config.end);
  Run run(std::move(sc), config, options);
  while (!run.done() && interrupt.received() == 0) {
    run.step();
    progress.after_step(run.simulation());
  }
  run.finish();
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  progress.end_line();
  const int signal = interrupt.received();
  if (signal != 0)
    std::fprintf(stderr, "lpsim: interrupted by %s at time %.2f; outputs closed\n", signal_name(signal),
                 run.end_time());
  print_run_report(stdout, run, wall, load_seconds, signal != 0 ? signal_name(signal) : nullptr);
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace lpsim

// `lpsim cosim`: as `lpsim run`, with SUMO driving the corridor. A fault on SUMO's side (it does not start,
// dies, refuses a vehicle) is one error and a non-zero exit, with LPSim's outputs closed well-formed; SIGINT,
// SIGTERM and SIGHUP stop it at the end of the current coupling period as they stop `lpsim run`.
#include "sumo_bridge/cosim_command.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>

#include "app/corridor_resolution.hpp"
#include "app/device_select.hpp"
#include "app/drive_loop.hpp"
#include "app/interrupt.hpp"
#include "app/output_paths.hpp"
#include "app/progress_log.hpp"
#include "app/run.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "converters/corridor_file.hpp"
#include "core/error.hpp"
#include "sumo_bridge/cosimulation.hpp"
#include "sumo_bridge/sumo_arguments.hpp"

namespace lpsim {

std::vector<std::string> split_sumo_args(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  bool in_word = false;
  char quote = 0;
  for (const char ch : text) {
    if (quote != 0) {
      if (ch == quote)
        quote = 0;
      else
        cur += ch;
    } else if (ch == '\'' || ch == '"') {
      quote = ch;
      in_word = true;
    } else if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r') {
      if (in_word) out.push_back(cur);
      cur.clear();
      in_word = false;
    } else {
      cur += ch;
      in_word = true;
    }
  }
  if (quote != 0) throw InputError("--sumo-args: unclosed " + std::string(1, quote) + " in '" + text + "'");
  if (in_word) out.push_back(cur);
  return out;
}

namespace {

int run_cosim(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config, CliCommand::Cosim);
  const std::vector<std::string> sumo_args = split_sumo_args(config.sumo_args);
  refuse_overwrites(sc, CliCommand::Cosim, sumo_args_outputs(sumo_args));
  refuse_what_cosim_cannot_run(sc, config);  // before the Run creates any output file
  if (config.corridor_file.empty())
    throw InputError("cosim needs --corridor <file> (the edges SUMO simulates)");
  const CorridorSpec corridor_spec = read_corridor_file(config.corridor_file);
  if (!corridor_spec.other_kinds.empty()) {
    std::string kinds;
    for (const auto& [kind, n] : corridor_spec.other_kinds)
      kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
    std::fprintf(stderr,
                 "lpsim: warning: corridor %s: left out what is not a road (%s): a corridor is its edges\n",
                 config.corridor_file.c_str(), kinds.c_str());
  }
  const std::vector<uint32_t> selected = resolve_corridor(corridor_spec, sc.network);
  const std::vector<uint32_t> edges = close_corridor(selected, sc.network);
  if (edges.size() > selected.size())
    std::fprintf(
        stderr,
        "lpsim: corridor: %zu edges selected, %zu more taken in so that SUMO drives every approach of the "
        "junctions they lead to\n",
        selected.size(), edges.size() - selected.size());
  const std::vector<uint8_t> corridor = corridor_lanes(sc.network, edges);

  CosimOptions cosim;
  cosim.mode = config.sumo_binary.empty() ? SumoMode::Libsumo : SumoMode::Traci;
  if (!config.sumo_binary.empty()) cosim.sumo_binary = config.sumo_binary;
  cosim.sumo_args = sumo_args;
  refuse_unsupported_sumo_args(cosim.sumo_args);  // before any output file exists
  cosim.answer_timeout_s = config.sumo_timeout;

  SimulationOptions options = simulation_options(config);
  const DeviceChoice device = select_device(config.device);
  options.backend = device.backend;
  options.outside_lanes = &corridor;
  if (config.device != ComputeDevice::Cpu)
    std::fprintf(stderr, "lpsim: device %s\n", device.description.c_str());

  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  const double load_seconds = sc.load_seconds;
  const InterruptGuard interrupt;
  ProgressLog progress(stderr, isatty(fileno(stderr)) != 0, config.no_step_log, config.progress_interval,
                       config.end);
  Run run(std::move(sc), config, options);
  int signal = 0;
  {
    std::optional<Cosimulation> started;
    try {
      started.emplace(run, cosim);
    } catch (const SumoStartInterrupted&) {
      // Nothing has run: the outputs close empty and well-formed, as after a signal at the first step.
      run.finish();
      signal = interrupt.received();
      report_run_end(run, std::chrono::duration<double>(Clock::now() - wall0).count(), load_seconds, signal);
      return 128 + signal;
    }
    Cosimulation& co = *started;
    try {
      drive_to_end(co, run.simulation(), progress, [&] { return interrupt.received(); });
      co.finish();
    } catch (const std::exception&) {
      progress.end_line();
      co.abandon();  // LPSim's outputs end well-formed where the run stopped
      throw;
    }
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    progress.end_line();
    signal = interrupt.received();
    report_run_end(run, wall, load_seconds, signal);
    const Cosimulation::Report& r = co.report();
    std::printf(
        "Co-simulation (SUMO %s, %s, coupling period %.3gs):\n"
        " Handed into SUMO: %llu\n Taken back from SUMO: %llu\n Arrived in SUMO: %llu\n"
        " Held in SUMO for want of room in LPSim: %llu\n"
        " Longest wait at the boundary: %.2fs\n In hand-over at the end: %llu\n"
        " Wall time: SUMO's steps %.2fs, hand-overs %.2fs\n",
        co.sumo().mode() == SumoMode::Libsumo ? "in process" : "over TraCI",
        co.sumo().mode() == SumoMode::Libsumo ? "libsumo" : cosim.sumo_binary.c_str(), r.period,
        static_cast<unsigned long long>(r.into_sumo), static_cast<unsigned long long>(r.out_of_sumo),
        static_cast<unsigned long long>(r.arrived_in_sumo), static_cast<unsigned long long>(r.held),
        r.longest_boundary_wait, static_cast<unsigned long long>(r.in_handover_at_end), r.sumo_seconds,
        r.handover_seconds);
  }
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace

int command_cosim(const std::vector<std::string>& args) {
  try {
    return run_cosim(args);
  } catch (const SumoError& e) {
    // SUMO's fault (it did not start, died, refused a vehicle), not an internal error of LPSim's.
    std::fprintf(stderr, "lpsim: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace lpsim

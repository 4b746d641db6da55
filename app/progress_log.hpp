#pragma once
// The progress `lpsim run` shows while it steps. On a terminal: one line redrawn in place (carriage
// return) twice a second. Otherwise (a log file, a batch job's output): one full line every `interval`
// wall-clock seconds, so that a long run shows life without flooding its log, and never a carriage return.
// Nothing at all with SUMO's --no-step-log.
#include <chrono>
#include <cstdio>

#include "engine/simulation.hpp"

namespace lpsim {

class ProgressLog {
 public:
  /// `out` is where the lines go (stderr); `end` the run's end time, for the ETA (< 0: none).
  ProgressLog(std::FILE* out, bool terminal, bool silent, double interval_seconds, double end);

  /// After each step: prints a line when one is due.
  void after_step(const Simulation& sim);
  /// Ends the redrawn terminal line (before anything else is printed on stderr).
  void end_line();

 private:
  using Clock = std::chrono::steady_clock;
  void print(const Simulation& sim, Clock::time_point now);

  std::FILE* out_;
  bool terminal_, silent_;
  Clock::duration interval_;
  double end_;
  Clock::time_point start_, last_;
  bool line_open_ = false;  // a redrawn terminal line that no newline ended yet
};

}  // namespace lpsim

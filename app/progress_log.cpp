#include "app/progress_log.hpp"

#include <algorithm>

namespace lpsim {

namespace {

// How often the terminal line is redrawn.
constexpr std::chrono::milliseconds kTerminalRedraw{500};

}  // namespace

ProgressLog::ProgressLog(std::FILE* out, bool terminal, bool silent, double interval_seconds, double end)
    : out_(out),
      terminal_(terminal),
      silent_(silent),
      interval_(terminal ? Clock::duration(kTerminalRedraw)
                         : std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(interval_seconds))),
      end_(end),
      start_(Clock::now()),
      last_(start_) {}

void ProgressLog::after_step(const Simulation& sim) {
  if (silent_) return;
  const auto now = Clock::now();
  if (now - last_ <= interval_) return;
  last_ = now;
  print(sim, now);
}

void ProgressLog::end_line() {
  if (!line_open_) return;
  std::fputc('\n', out_);
  line_open_ = false;
}

void ProgressLog::print(const Simulation& sim, Clock::time_point now) {
  const double wall = std::chrono::duration<double>(now - start_).count();
  const auto& c = sim.counts();
  const double ups = wall > 0 ? static_cast<double>(c.vehicle_updates) / wall : 0;
  std::fprintf(out_, "%st=%.2f running %llu arrived %llu waiting %llu  %.3g veh-updates/s",
               terminal_ ? "\r" : "lpsim: ", sim.time(), static_cast<unsigned long long>(c.running),
               static_cast<unsigned long long>(c.arrived), static_cast<unsigned long long>(c.waiting), ups);
  if (end_ > 0 && sim.time() > 0 && wall > 0) {
    const double eta = wall / std::max(1e-9, sim.time()) * std::max(0.0, end_ - sim.time());
    std::fprintf(out_, "  ETA %.0f s", eta);
  }
  if (terminal_) {
    std::fputs("   ", out_);
    line_open_ = true;
  } else {
    std::fputc('\n', out_);
  }
  std::fflush(out_);
}

}  // namespace lpsim

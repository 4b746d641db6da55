#pragma once
// The range of times LPSim accepts, in one place for the command line, the .sumocfg and the route and
// add-files. The engine keeps the clock and every departure as int64 milliseconds (Simulation::time_ms) but
// compares times as doubles (the run's end, FCD periods, edgeData intervals), which hold every millisecond
// exactly only up to 2^53 ms (9.007e12 s); beyond that a step no longer advances the clock as the run's end
// test sees it (`-b 1e17` never ended) and a depart of 1e17 s overflowed the milliseconds outright.
#include <cmath>
#include <cstdint>

namespace lpsim {

/// The largest time magnitude accepted, in seconds (about 31,700 years): a round figure below 2^53 ms.
inline constexpr double kMaxTimeSeconds = 1e12;

/// True when `seconds` is finite and within +-kMaxTimeSeconds.
inline bool time_in_range(double seconds) {
  return std::isfinite(seconds) && std::fabs(seconds) <= kMaxTimeSeconds;
}

/// A time in range as the engine's milliseconds (a departure, a step's end), rounded to the nearest.
inline int64_t seconds_to_ms(double seconds) { return std::llround(seconds * 1000.0); }

}  // namespace lpsim

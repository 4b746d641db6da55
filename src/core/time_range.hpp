#pragma once
// The range of times the engine can represent. It keeps the clock and every departure as int64
// milliseconds (Simulation::time_ms), so a time in seconds must stay below 2^63 ms; beyond it the
// conversion overflows (a depart of 1e17 s came out negative and was inserted at once). SUMO keeps its
// SUMOTime the same way and refuses the same times.
#include <cmath>

namespace lpsim {

/// The largest time, in seconds, whose millisecond count fits an int64 after the conversion's rounding:
/// floor((2^63 - 1) / 1000) = 9223372036854775 is not a double (they are 2 apart there) and would round up
/// past the range, so the even number below it.
inline constexpr double kMaxTimeSeconds = 9223372036854774.0;

/// True when `seconds` is finite and its millisecond count fits an int64 (negative times included).
inline bool time_in_range(double seconds) {
  return std::isfinite(seconds) && std::fabs(seconds) <= kMaxTimeSeconds;
}

}  // namespace lpsim

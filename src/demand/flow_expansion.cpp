#include "demand/flow_expansion.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "demand/demand_draws.hpp"

namespace lpsim {
namespace {

using Millis = int64_t;

constexpr Millis kDefaultDuration = 24 * 3600 * 1000;  // SUMO: undefined end -> begin + 24 h
constexpr Millis kNoEnd = std::numeric_limits<Millis>::max();
constexpr int64_t kMaxVehiclesPerFlow = 1'000'000'000;

Millis to_millis(double seconds) { return static_cast<Millis>(std::llround(seconds * 1000.0)); }
double to_seconds(Millis ms) { return static_cast<double>(ms) / 1000.0; }

// FlowSpec marks absent numbers with -1; any other negative value is a bad input.
bool given(const FlowSpec& f, double value, const char* name) {
  if (value == -1) return false;
  if (value < 0 || !std::isfinite(value))
    throw InputError(f.loc, "invalid " + std::string(name) + " in flow '" + f.id + "'");
  return true;
}

void check_count(const FlowSpec& f, int64_t count) {
  if (count > kMaxVehiclesPerFlow)
    throw InputError(f.loc, "flow '" + f.id + "' would create " + std::to_string(count) + " vehicles");
}

std::vector<double> periodic(Millis begin, Millis offset, int64_t count) {
  std::vector<double> times;
  times.reserve(static_cast<size_t>(count));
  for (int64_t n = 0; n < count; ++n) times.push_back(to_seconds(begin + n * offset));
  return times;
}

std::vector<double> bernoulli(const FlowSpec& f, Millis begin, Millis end, int64_t number, double probability,
                              uint64_t seed, double step_length) {
  const Millis step = to_millis(step_length);
  if (step <= 0) throw InputError("step length must be positive for probability flow '" + f.id + "'");
  const double per_step = probability * to_seconds(step);
  const int64_t first_step = (begin + step - 1) / step;  // first step at or after begin
  int64_t last_step;                                     // exclusive
  if (end != kNoEnd) {
    last_step = end / step + (end % step != 0 ? 1 : 0);  // steps strictly before end, ceil without overflow
  } else {
    // Bounded by `number` only; refuse flows that would need absurdly many steps to reach it.
    const double expected_steps = static_cast<double>(number) / per_step;
    if (expected_steps > 1e9)
      throw InputError(f.loc, "flow '" + f.id + "' would need about " + std::to_string(expected_steps) +
                                  " steps to emit its number of vehicles");
    last_step = std::numeric_limits<int64_t>::max();
  }
  check_count(f, last_step == std::numeric_limits<int64_t>::max() ? number : last_step - first_step);
  const uint64_t stream = draw_stream(f.id);
  std::vector<double> times;
  for (int64_t k = first_step; k < last_step; ++k) {
    if (number >= 0 && static_cast<int64_t>(times.size()) >= number) break;
    if (rng_uniform_double(seed, stream, static_cast<uint64_t>(k)) < per_step)
      times.push_back(to_seconds(k * step));
  }
  return times;
}

}  // namespace

std::vector<double> flow_departures(const FlowSpec& f, uint64_t seed, double step_length) {
  const bool has_period = given(f, f.period, "period");
  const bool has_vph = given(f, f.vehs_per_hour, "vehsPerHour");
  const bool has_prob = given(f, f.probability, "probability");
  const bool has_end = given(f, f.end, "end");
  const bool has_number = given(f, static_cast<double>(f.number), "number");
  const bool has_rate = has_period || has_vph || has_prob;
  if (has_period + has_vph + has_prob > 1)
    throw InputError(f.loc, "flow '" + f.id + "' gives more than one of period, vehsPerHour and probability");
  if (has_rate && has_end && has_number)
    throw InputError(f.loc, "flow '" + f.id + "' gives both end and number together with a rate");
  if (!has_rate && !has_number)
    throw InputError(f.loc, "flow '" + f.id + "' needs one of period, vehsPerHour, probability or number");
  if (f.begin < 0 || !std::isfinite(f.begin))
    throw InputError(f.loc, "negative begin in flow '" + f.id + "'");
  if (has_vph && !(f.vehs_per_hour > 0))
    throw InputError(f.loc, "invalid vehsPerHour 0 in flow '" + f.id + "'");
  if (has_prob && !(f.probability > 0 && f.probability <= 1))
    throw InputError(f.loc,
                     "invalid probability " + std::to_string(f.probability) + " in flow '" + f.id + "'");

  const Millis begin = to_millis(f.begin);
  Millis end = kNoEnd;
  if (has_end) {
    end = to_millis(f.end);
  } else if (!has_number || !has_rate) {
    // Capped below kNoEnd (which means "no end") for a begin near the largest time, where the sum overflows.
    end = begin < kNoEnd - 1 - kDefaultDuration ? begin + kDefaultDuration : kNoEnd - 1;
  }
  if (end < begin) throw InputError(f.loc, "flow '" + f.id + "' ends before its begin");

  Millis offset = -1;
  if (has_period) offset = to_millis(f.period);
  if (has_vph) offset = to_millis(3600.0 / f.vehs_per_hour);

  if (has_prob) return bernoulli(f, begin, end, has_number ? f.number : -1, f.probability, seed, step_length);
  if (has_number) {
    if (f.number == 0) return {};
    check_count(f, f.number);
    if (offset < 0) offset = (end - begin) / f.number;
    return periodic(begin, offset, f.number);
  }
  if (offset <= 0) {
    // The clock counts whole milliseconds: a shorter period would put every vehicle at one instant.
    char given_rate[64];
    if (has_period)
      std::snprintf(given_rate, sizeof given_rate, "period %g s", f.period);
    else
      std::snprintf(given_rate, sizeof given_rate, "vehsPerHour %g (a period of %g s)", f.vehs_per_hour,
                    3600.0 / f.vehs_per_hour);
    throw InputError(
        f.loc, "flow '" + f.id + "': " + given_rate + " is shorter than LPSim's time resolution of 1 ms");
  }
  // ceil((end - begin) / offset): vehicles strictly before end, without the sum that overflows when the
  // period is near the largest time.
  const int64_t count = (end - begin) / offset + ((end - begin) % offset != 0 ? 1 : 0);
  check_count(f, count);
  return periodic(begin, offset, count);
}

}  // namespace lpsim

#pragma once
// Fixed-time traffic-light programs evaluated as a pure function of time, plus the meaning of SUMO's
// signal characters. Times are integer milliseconds (as SUMO's SUMOTime) so the phase lookup cannot drift
// over long simulations the way float seconds would. See docs/MODELS.md.
#include <stdint.h>

#include "kernels/hd.hpp"
#include "kernels/idm.hpp"

namespace lpsim {

/// One tlLogic program as plain arrays owned by the caller.
struct SignalProgramView {
  const int32_t* durations_ms;  // [num_phases] phase durations
  const char* states;           // [num_phases * num_links] row-major: states[phase * num_links + link]
  int32_t num_phases;
  int32_t num_links;
  int64_t cycle_ms;   // sum of the durations (precomputed by the loader)
  int64_t offset_ms;  // the tlLogic's offset attribute
};

/// Time into the cycle at absolute simulation time t: (t - offset) mod cycle, in [0, cycle). SUMO delays the
/// whole program by a positive offset (phase 0 starts at t = offset) and the reference is absolute time,
/// not the simulation's begin time (verified with SUMO 1.15's tlsSwitch output).
LPSIM_HD int64_t signal_time_in_cycle(const SignalProgramView& prog, int64_t t_ms) {
  if (prog.cycle_ms <= 0) return 0;
  const int64_t r = (t_ms - prog.offset_ms) % prog.cycle_ms;
  return r < 0 ? r + prog.cycle_ms : r;
}

/// Index of the phase active at time t (0 for an empty or zero-length program).
LPSIM_HD int32_t signal_phase_at(const SignalProgramView& prog, int64_t t_ms) {
  int64_t remaining = signal_time_in_cycle(prog, t_ms);
  for (int32_t i = 0; i < prog.num_phases; ++i) {
    if (remaining < prog.durations_ms[i]) return i;
    remaining -= prog.durations_ms[i];
  }
  return 0;
}

/// Time until the active phase ends [ms]: how long the current signal for every link stays as it is.
LPSIM_HD int64_t signal_time_to_switch(const SignalProgramView& prog, int64_t t_ms) {
  int64_t end = 0;
  const int64_t in_cycle = signal_time_in_cycle(prog, t_ms);
  for (int32_t i = 0; i < prog.num_phases; ++i) {
    end += prog.durations_ms[i];
    if (in_cycle < end) return end - in_cycle;
  }
  return 0;
}

/// Signal character for a link at time t. An empty program or out-of-range link reads as red ('r'): the
/// loader rejects those, and red is the only answer that cannot cause a crash if one slips through.
LPSIM_HD char signal_state_at(const SignalProgramView& prog, int64_t t_ms, int32_t link) {
  if (prog.num_phases <= 0 || link < 0 || link >= prog.num_links) return 'r';
  const int32_t phase = signal_phase_at(prog, t_ms);
  return prog.states[static_cast<int64_t>(phase) * prog.num_links + link];
}

/// 'G' green with priority, 'g' green that must yield to prioritised foes, 's' green after a full stop
/// (right-turn-on-red arrow), 'o' off and blinking (yield), 'O' off without signal (priority).
LPSIM_HD bool signal_is_green(char c) { return c == 'G' || c == 'g' || c == 's' || c == 'o' || c == 'O'; }
/// Green states that let the vehicle go without checking foes.
LPSIM_HD bool signal_has_priority(char c) { return c == 'G' || c == 'O'; }
/// Green states that must yield to foes on prioritised links (right_of_way.hpp decides).
LPSIM_HD bool signal_must_yield(char c) { return c == 'g' || c == 's' || c == 'o'; }
/// 's': stop at the line first, then proceed like 'g'.
LPSIM_HD bool signal_requires_full_stop(char c) { return c == 's'; }
/// 'r' red and 'u' red+yellow (about to turn green, still closed).
LPSIM_HD bool signal_is_red(char c) { return c == 'r' || c == 'u'; }
/// 'y' yellow ('Y' also accepted, SUMO's major-yellow spelling).
LPSIM_HD bool signal_is_yellow(char c) { return c == 'y' || c == 'Y'; }

/// Whether a vehicle `gap` metres before the stop line at `speed` must stop for signal c. Red and
/// red+yellow: always. Yellow: only if it can still stop before the line braking no harder than decel
/// (its comfortable deceleration); otherwise it passes, as SUMO does.
LPSIM_HD bool signal_must_stop(char c, float gap, float speed, float decel, float dt) {
  if (signal_is_red(c)) return true;
  if (signal_is_yellow(c)) return can_stop_before(gap, speed, decel, dt);
  return false;
}

}  // namespace lpsim

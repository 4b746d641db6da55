#pragma once
// Per-signal step: the characters of every link of every traffic light at the current time.
#include <stdint.h>

#include "kernels/hd.hpp"
#include "kernels/signal_state.hpp"

namespace lpsim {

struct SignalTable {
  uint32_t num_signals;
  const uint32_t* phase_begin;  // [num_signals+1]
  const int32_t* durations_ms;  // per phase
  const uint32_t* state_begin;  // per phase: offset of its link characters in states
  const char* states;
  const int32_t* num_links;    // per signal
  const int64_t* cycle_ms;     // per signal
  const int64_t* offset_ms;    // per signal
  const uint32_t* link_begin;  // [num_signals+1] offsets into the link-state output
};

/// A next_switch_ms entry for a signal whose link characters were never set.
constexpr int64_t kSignalNeverSet = INT64_MIN;

/// Sets the link characters of signal `s` for time `time_ms`, unless the phase they show has not ended yet:
/// next_switch_ms[s] is the time it ends (kSignalNeverSet before the first call). Phases last seconds and a
/// step is a fraction of one, so a step rewrites only the signals whose phase ends in it (on a regional
/// network tens of thousands of signals would otherwise be recomputed every step). The characters stay a
/// pure function of time as long as the times of successive calls never decrease.
LPSIM_HD void update_signal(const SignalTable& t, uint32_t s, int64_t time_ms, char* link_state,
                            int64_t* next_switch_ms) {
  if (time_ms < next_switch_ms[s]) return;
  const uint32_t p0 = t.phase_begin[s];
  const SignalProgramView prog{
      t.durations_ms + p0, nullptr,       static_cast<int32_t>(t.phase_begin[s + 1] - p0),
      t.num_links[s],      t.cycle_ms[s], t.offset_ms[s]};
  const int32_t phase = signal_phase_at(prog, time_ms);
  const char* src = t.states + t.state_begin[p0 + static_cast<uint32_t>(phase)];
  char* dst = link_state + t.link_begin[s];
  for (int32_t k = 0; k < t.num_links[s]; ++k) dst[k] = src[k];
  // A program without a positive duration never switches: 0 here, so it is set again at the next call.
  next_switch_ms[s] = time_ms + signal_time_to_switch(prog, time_ms);
}

}  // namespace lpsim

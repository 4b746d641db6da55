#pragma once
// Per-signal step: the characters of every link of every traffic light at the current time.
#include <stdint.h>

#include "kernels/actuated_signal.hpp"
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
  ActuatedTable actuated;
};

/// What a SignalTable column is indexed by: its length follows from num_signals and the begin tables.
enum class SignalExtent : uint8_t {
  kSignals,
  kSignalsPlusOne,
  kPhases,  // phase_begin[num_signals]
  kPhasesPlusOne,
  kStateChars,    // up to the end of the last phase's link characters
  kLinksPlusOne,  // link_begin: NetView's signal_link_begin, the same column
  kLoops,         // actuated.signal_det_begin[num_signals]
  kPhaseLoops     // actuated.phase_det_begin[phases]
};

/// The one list of the signal columns (as visit_net_columns): f(extent, column...) for each pointer column of
/// every table given, the actuated ones' included (num_signals is not one).
template <class F, class... Tables>
void visit_signal_columns(F&& f, Tables&... t) {
  f(SignalExtent::kSignalsPlusOne, t.phase_begin...);
  f(SignalExtent::kPhases, t.durations_ms...);
  f(SignalExtent::kPhases, t.state_begin...);
  f(SignalExtent::kStateChars, t.states...);
  f(SignalExtent::kSignals, t.num_links...);
  f(SignalExtent::kSignals, t.cycle_ms...);
  f(SignalExtent::kSignals, t.offset_ms...);
  f(SignalExtent::kLinksPlusOne, t.link_begin...);
  f(SignalExtent::kSignals, t.actuated.actuated...);
  f(SignalExtent::kSignals, t.actuated.detector_gap_ms...);
  f(SignalExtent::kPhases, t.actuated.min_ms...);
  f(SignalExtent::kPhases, t.actuated.max_ms...);
  f(SignalExtent::kPhases, t.actuated.green...);
  f(SignalExtent::kSignalsPlusOne, t.actuated.signal_det_begin...);
  f(SignalExtent::kPhasesPlusOne, t.actuated.phase_det_begin...);
  f(SignalExtent::kPhaseLoops, t.actuated.phase_det...);
  f(SignalExtent::kLoops, t.actuated.det_cell...);
  f(SignalExtent::kLoops, t.actuated.det_last_cell...);
  f(SignalExtent::kLoops, t.actuated.det_offset...);
  f(SignalExtent::kLoops, t.actuated.det_max_gap_ms...);
}
static_assert(sizeof(SignalTable) == 9 * sizeof(void*) + 12 * sizeof(void*),
              "SignalTable or ActuatedTable changed: update visit_signal_columns");

/// What an actuated signal reads besides its table: the lane map its loops lie on and when it was taken.
struct SignalInputs {
  const uint8_t* map;   // the lane map as the vehicles stand before the step
  int64_t map_time_ms;  // the time of that map
  int64_t dt_ms;        // the step length (how far a vehicle moved since the map before)
};

/// A next_switch_ms entry for a signal whose link characters were never set.
constexpr int64_t kSignalNeverSet = INT64_MIN;

LPSIM_HD void copy_phase_state(const SignalTable& t, uint32_t s, uint32_t phase, char* link_state) {
  const char* src = t.states + t.state_begin[phase];
  char* dst = link_state + t.link_begin[s];
  for (int32_t k = 0; k < t.num_links[s]; ++k) dst[k] = src[k];
}

/// An actuated signal (actuated_signal.hpp): its loops are updated every step; at the phase's scheduled end
/// the gap control extends it or the next phase starts, shown for at least its minDur. At the first call it
/// shows the phase its fixed-time plan has then, for that phase's minDur, as SUMO 1.15 starts it (measured
/// with its tlsStates output, with and without an offset and a begin time).
LPSIM_HD void update_actuated_signal(const SignalTable& t, uint32_t s, int64_t time_ms,
                                     const SignalInputs& in, char* link_state, int64_t* next_switch_ms,
                                     const ActuatedState& st) {
  const ActuatedTable& a = t.actuated;
  for (uint32_t d = a.signal_det_begin[s]; d < a.signal_det_begin[s + 1]; ++d)
    update_detector(a, in.map, d, in.map_time_ms, in.dt_ms, st.det_last_ms);
  const uint32_t p0 = t.phase_begin[s];
  const uint32_t n = t.phase_begin[s + 1] - p0;
  if (next_switch_ms[s] == kSignalNeverSet) {
    for (uint32_t d = a.signal_det_begin[s]; d < a.signal_det_begin[s + 1]; ++d)
      st.det_last_ms[d] = kNeverDetected;
    const SignalProgramView prog{t.durations_ms + p0, nullptr,       static_cast<int32_t>(n),
                                 t.num_links[s],      t.cycle_ms[s], t.offset_ms[s]};
    const uint32_t first = static_cast<uint32_t>(signal_phase_at(prog, time_ms));
    st.phase[s] = static_cast<int32_t>(first);
    st.phase_start_ms[s] = time_ms;
    copy_phase_state(t, s, p0 + first, link_state);
    next_switch_ms[s] = time_ms + actuated_first_try_ms(a, p0 + first);
    return;
  }
  if (time_ms < next_switch_ms[s]) return;
  const uint32_t p = p0 + static_cast<uint32_t>(st.phase[s]);
  const int64_t ext =
      actuated_extension_ms(a, s, p, time_ms, st.phase_start_ms[s], in.map_time_ms, st.det_last_ms);
  if (ext > 0) {
    next_switch_ms[s] = time_ms + ext;
    return;
  }
  const uint32_t next = (static_cast<uint32_t>(st.phase[s]) + 1) % n;
  st.phase[s] = static_cast<int32_t>(next);
  st.phase_start_ms[s] = time_ms;
  copy_phase_state(t, s, p0 + next, link_state);
  next_switch_ms[s] = time_ms + actuated_first_try_ms(a, p0 + next);
}

/// Sets the link characters of signal `s` for time `time_ms`, unless the phase they show has not ended yet:
/// next_switch_ms[s] is the time it ends (kSignalNeverSet before the first call). Phases last seconds and a
/// step is a fraction of one, so a step rewrites only the signals whose phase ends in it (on a regional
/// network tens of thousands of signals would otherwise be recomputed every step). A fixed-time signal's
/// characters stay a pure function of time as long as the times of successive calls never decrease; an
/// actuated one's depend on its loops, so it must be called every step.
LPSIM_HD void update_signal(const SignalTable& t, uint32_t s, int64_t time_ms, const SignalInputs& in,
                            char* link_state, int64_t* next_switch_ms, const ActuatedState& st) {
  if (t.actuated.actuated[s]) {
    update_actuated_signal(t, s, time_ms, in, link_state, next_switch_ms, st);
    return;
  }
  if (time_ms < next_switch_ms[s]) return;
  const uint32_t p0 = t.phase_begin[s];
  const SignalProgramView prog{
      t.durations_ms + p0, nullptr,       static_cast<int32_t>(t.phase_begin[s + 1] - p0),
      t.num_links[s],      t.cycle_ms[s], t.offset_ms[s]};
  const int32_t phase = signal_phase_at(prog, time_ms);
  copy_phase_state(t, s, p0 + static_cast<uint32_t>(phase), link_state);
  // A program without a positive duration never switches: 0 here, so it is set again at the next call.
  next_switch_ms[s] = time_ms + signal_time_to_switch(prog, time_ms);
}

}  // namespace lpsim

// Signal programs: phase lookup with SUMO's offset semantics, the meaning of the state characters, and the
// per-step update of every signal's link characters.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kernels/signal_state.hpp"
#include "kernels/signal_step.hpp"

namespace lpsim {
namespace {

// netgenerate's 3x3 grid, junction A1, with offset 10 s. SUMO 1.15's tlsSwitch output for this program
// starting at t = 0: phase 2 until t = 7, yellow 7..10, phase 0 from t = 10 to 52.
const int32_t kDurations[] = {42000, 3000, 42000, 3000};
const char kStates[] =
    "GggrrrGGg"
    "yyyrrryyy"
    "rrrGGgGrr"
    "rrryyyyrr";
const SignalProgramView kProg{kDurations, kStates, 4, 9, 90000, 10000};

TEST(ModelsSignal, OffsetDelaysTheProgramAgainstAbsoluteTime) {
  EXPECT_EQ(signal_time_in_cycle(kProg, 0), 80000);  // (0 - 10 s) mod 90 s
  EXPECT_EQ(signal_phase_at(kProg, 0), 2);
  EXPECT_EQ(signal_time_to_switch(kProg, 0), 7000);
  EXPECT_EQ(signal_phase_at(kProg, 6999), 2);
  EXPECT_EQ(signal_phase_at(kProg, 7000), 3);
  EXPECT_EQ(signal_phase_at(kProg, 10000), 0);
  EXPECT_EQ(signal_time_to_switch(kProg, 10000), 42000);
  EXPECT_EQ(signal_phase_at(kProg, 52000), 1);
  EXPECT_EQ(signal_phase_at(kProg, 55000), 2);
  EXPECT_EQ(signal_phase_at(kProg, 100000), 0);                  // one full cycle later
  EXPECT_EQ(signal_phase_at(kProg, 10000 + 90000LL * 1000), 0);  // a thousand cycles later, no drift
  EXPECT_EQ(signal_phase_at(kProg, -5000), 2);                   // negative times wrap too: in-cycle 75 s
}

TEST(ModelsSignal, StateForALink) {
  EXPECT_EQ(signal_state_at(kProg, 0, 3), 'G');
  EXPECT_EQ(signal_state_at(kProg, 0, 0), 'r');
  EXPECT_EQ(signal_state_at(kProg, 0, 5), 'g');
  EXPECT_EQ(signal_state_at(kProg, 8000, 3), 'y');
  EXPECT_EQ(signal_state_at(kProg, 20000, 0), 'G');
  EXPECT_EQ(signal_state_at(kProg, 20000, 1), 'g');
  // Out-of-range links and empty programs read as red.
  EXPECT_EQ(signal_state_at(kProg, 0, 9), 'r');
  EXPECT_EQ(signal_state_at(kProg, 0, -1), 'r');
  const SignalProgramView empty{nullptr, nullptr, 0, 0, 0, 0};
  EXPECT_EQ(signal_state_at(empty, 1234, 0), 'r');
  EXPECT_EQ(signal_phase_at(empty, 1234), 0);
}

TEST(ModelsSignal, ZeroOffsetStartsWithPhaseZero) {
  const SignalProgramView p{kDurations, kStates, 4, 9, 90000, 0};
  EXPECT_EQ(signal_phase_at(p, 0), 0);
  EXPECT_EQ(signal_phase_at(p, 41999), 0);
  EXPECT_EQ(signal_phase_at(p, 42000), 1);
  EXPECT_EQ(signal_phase_at(p, 89999), 3);
  EXPECT_EQ(signal_phase_at(p, 90000), 0);
}

// Three signals in one table: the 3x3 grid's program (offset 10 s), a two-link program with a zero-length
// phase and an offset beyond its cycle, and a one-phase program of zero length (never switches).
struct ThreeSignals {
  std::vector<uint32_t> phase_begin{0, 4, 7, 8};
  std::vector<int32_t> durations{42000, 3000, 42000, 3000, 5000, 0, 2500, 0};
  std::vector<uint32_t> state_begin{0, 9, 18, 27, 36, 38, 40, 42};
  // Appended, not a chain of operator+: GCC 12 at -O1 warns falsely (-Warray-bounds) on that chain here.
  std::string states = std::string(kStates).append("GrryrG").append("g");
  std::vector<int32_t> num_links{9, 2, 1};
  std::vector<int64_t> cycle{90000, 7500, 0};
  std::vector<int64_t> offset{10000, 20000, 0};
  std::vector<uint32_t> link_begin{0, 9, 11, 12};
  // Fixed-time programs only: no signal actuated, no loops.
  std::vector<uint8_t> not_actuated{0, 0, 0};
  std::vector<uint32_t> no_loops{0, 0, 0, 0};
  SignalTable table() const {
    return SignalTable{3,
                       phase_begin.data(),
                       durations.data(),
                       state_begin.data(),
                       states.data(),
                       num_links.data(),
                       cycle.data(),
                       offset.data(),
                       link_begin.data(),
                       ActuatedTable{not_actuated.data(), nullptr, nullptr, nullptr, nullptr, no_loops.data(),
                                     nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};
  }
  SignalProgramView program(uint32_t s) const {
    return SignalProgramView{durations.data() + phase_begin[s],
                             nullptr,
                             static_cast<int32_t>(phase_begin[s + 1] - phase_begin[s]),
                             num_links[s],
                             cycle[s],
                             offset[s]};
  }
  // What signal s shows on link k at time t, from the pure lookup.
  char expected(uint32_t s, int32_t k, int64_t t) const {
    const SignalProgramView p = program(s);
    return states[state_begin[phase_begin[s] + static_cast<uint32_t>(signal_phase_at(p, t))] +
                  static_cast<uint32_t>(k)];
  }
};

// A fixed-time signal reads neither the lane map nor the actuated state.
void update_fixed(const SignalTable& t, uint32_t s, int64_t time, char* links, int64_t* next) {
  update_signal(t, s, time, SignalInputs{nullptr, time, 0}, links, next, ActuatedState{});
}

TEST(ModelsSignal, StepUpdateEqualsThePureLookupAtEveryStep) {
  const ThreeSignals sig;
  const SignalTable t = sig.table();
  // Step lengths that do and do not divide the phase lengths, and a long jump.
  for (const int64_t dt : {1000, 500, 300, 7, 100000}) {
    std::vector<char> links(12, '?');
    std::vector<int64_t> next(3, kSignalNeverSet);
    int64_t mismatches = 0, steps = 0;
    for (int64_t time = -3000; time < 400000; time += dt, ++steps) {
      for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, time, links.data(), next.data());
      for (uint32_t s = 0; s < 3; ++s)
        for (int32_t k = 0; k < sig.num_links[s]; ++k)
          mismatches += links[sig.link_begin[s] + static_cast<uint32_t>(k)] != sig.expected(s, k, time);
    }
    EXPECT_EQ(mismatches, 0) << "step " << dt << " ms, " << steps << " steps";
  }
}

TEST(ModelsSignal, StepUpdateRewritesASignalOnlyWhenItsPhaseEnds) {
  const ThreeSignals sig;
  const SignalTable t = sig.table();
  std::vector<char> links(12, '?');
  std::vector<int64_t> next(3, kSignalNeverSet);
  for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, 0, links.data(), next.data());
  EXPECT_EQ(next[0], 7000);  // phase 2 of the grid's program ends at t = 7 s
  EXPECT_EQ(next[1], 2500);  // in-cycle (0 - 20 s) mod 7.5 s = 2.5 s: phase 0 ends at 5 s
  EXPECT_EQ(next[2], 0);     // no positive duration: set again at every call
  // Marks left in the output stay until the phase ends: nothing is rewritten before then.
  links[0] = 'X', links[9] = 'X', links[11] = 'X';
  for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, 2000, links.data(), next.data());
  EXPECT_EQ(links[0], 'X');
  EXPECT_EQ(links[9], 'X');
  EXPECT_EQ(links[11], 'g');  // the zero-length program: rewritten every time
  for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, 2500, links.data(), next.data());
  EXPECT_EQ(links[0], 'X');
  EXPECT_EQ(links[9], 'r');  // past the zero-length phase 1 straight to phase 2, "rG"
  EXPECT_EQ(links[10], 'G');
  EXPECT_EQ(next[1], 5000);
  for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, 6999, links.data(), next.data());
  EXPECT_EQ(links[0], 'X');
  for (uint32_t s = 0; s < 3; ++s) update_fixed(t, s, 7000, links.data(), next.data());
  EXPECT_EQ(links[0], 'r');  // yellow phase 3 of the grid's program: "rrryyyyrr"
  EXPECT_EQ(links[3], 'y');
  EXPECT_EQ(next[0], 10000);
}

TEST(ModelsSignal, CharacterClasses) {
  for (char c : {'G', 'g', 's', 'o', 'O'}) EXPECT_TRUE(signal_is_green(c)) << c;
  for (char c : {'r', 'u', 'y', 'Y'}) EXPECT_FALSE(signal_is_green(c)) << c;
  EXPECT_TRUE(signal_has_priority('G'));
  EXPECT_TRUE(signal_has_priority('O'));
  EXPECT_FALSE(signal_has_priority('g'));
  for (char c : {'g', 's', 'o'}) EXPECT_TRUE(signal_must_yield(c)) << c;
  EXPECT_FALSE(signal_must_yield('G'));
  EXPECT_TRUE(signal_requires_full_stop('s'));
  EXPECT_FALSE(signal_requires_full_stop('g'));
  EXPECT_TRUE(signal_is_red('r'));
  EXPECT_TRUE(signal_is_red('u'));
  EXPECT_FALSE(signal_is_red('y'));
  EXPECT_TRUE(signal_is_yellow('y'));
  EXPECT_TRUE(signal_is_yellow('Y'));
}

TEST(ModelsSignal, MustStopAtRedAlwaysAtYellowOnlyIfComfortable) {
  EXPECT_TRUE(signal_must_stop('r', 0.0f, 0.0f, 4.5f, 1.0f));
  EXPECT_TRUE(signal_must_stop('r', 5.0f, 20.0f, 4.5f, 1.0f));
  EXPECT_TRUE(signal_must_stop('u', 100.0f, 10.0f, 4.5f, 1.0f));
  // Yellow 50 m ahead at 10 m/s: braking at 4.5 stops within 6.5 m -> stop.
  EXPECT_TRUE(signal_must_stop('y', 50.0f, 10.0f, 4.5f, 1.0f));
  // Yellow 5 m ahead at 15 m/s: cannot stop comfortably -> go.
  EXPECT_FALSE(signal_must_stop('y', 5.0f, 15.0f, 4.5f, 1.0f));
  EXPECT_FALSE(signal_must_stop('Y', 5.0f, 15.0f, 4.5f, 0.5f));
  // Standing at the line at yellow: stays.
  EXPECT_TRUE(signal_must_stop('y', 0.0f, 0.0f, 4.5f, 1.0f));
  for (char c : {'G', 'g', 's', 'o', 'O'}) EXPECT_FALSE(signal_must_stop(c, 1.0f, 10.0f, 4.5f, 1.0f)) << c;
}

}  // namespace
}  // namespace lpsim

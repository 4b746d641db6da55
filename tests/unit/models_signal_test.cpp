// Signal programs: phase lookup with SUMO's offset semantics, and the meaning of the state characters.
#include <gtest/gtest.h>

#include "kernels/signal_state.hpp"

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

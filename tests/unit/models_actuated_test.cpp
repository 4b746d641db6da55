// Actuated signals (kernels/actuated_signal.hpp, signal_step.hpp): what an induction loop reads from the lane
// map, SUMO's gap control at a phase's scheduled end, and a whole program stepped against its loops.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kernels/lane_map.hpp"
#include "kernels/signal_step.hpp"

namespace lpsim {
namespace {

// One signal, two links, SUMO's netconvert program for a two-approach light: green 0 (minDur 5, maxDur 50),
// yellow, green 1 (minDur 5, maxDur 50), yellow. One loop per approach, on lanes of 100 cells at cells 60
// (lane 0) and 160 (lane 1); loop 0 may extend phase 0, loop 1 phase 2.
struct OneActuatedSignal {
  std::vector<uint32_t> phase_begin{0, 4};
  std::vector<int32_t> durations{42000, 3000, 42000, 3000};
  std::vector<uint32_t> state_begin{0, 2, 4, 6};
  std::string states = "GryrrGry";
  std::vector<int32_t> num_links{2};
  std::vector<int64_t> cycle{90000}, offset{0};
  std::vector<uint32_t> link_begin{0, 2};
  std::vector<uint8_t> actuated{1};
  std::vector<int32_t> detector_gap{2000};
  std::vector<int32_t> min_ms{5000, 3000, 5000, 3000}, max_ms{50000, 3000, 50000, 3000};
  std::vector<uint8_t> green{1, 0, 1, 0};
  std::vector<uint32_t> signal_det_begin{0, 2};
  std::vector<uint32_t> phase_det_begin{0, 1, 1, 2, 2}, phase_det{0, 1};
  std::vector<uint32_t> det_cell{60, 160}, det_last_cell{99, 199};
  std::vector<float> det_offset{0.5f, 0.5f};
  std::vector<int32_t> det_max_gap{3000, 3000};

  SignalTable table() const {
    const ActuatedTable a{actuated.data(),        detector_gap.data(), min_ms.data(),
                          max_ms.data(),          green.data(),        signal_det_begin.data(),
                          phase_det_begin.data(), phase_det.data(),    det_cell.data(),
                          det_last_cell.data(),   det_offset.data(),   det_max_gap.data()};
    return SignalTable{1,
                       phase_begin.data(),
                       durations.data(),
                       state_begin.data(),
                       states.data(),
                       num_links.data(),
                       cycle.data(),
                       offset.data(),
                       link_begin.data(),
                       a};
  }
};

TEST(ModelsActuated, LoopSeesAVehicleOverItOrOneThatLeftWithinTheStep) {
  const OneActuatedSignal sig;
  const ActuatedTable a = sig.table().actuated;
  std::vector<uint8_t> map(200 + kLaneMapPadding, 0);
  std::vector<int64_t> last{kNeverDetected, kNeverDetected};
  map[60] = encode_cell_speed(5.0f);  // a body over loop 0
  update_detector(a, map.data(), 0, 10000, 1000, last.data());
  EXPECT_EQ(last[0], 10000);
  // Loop 1: the nearest rear 3.5 m past it at 10 m/s crossed it 0.35 s before the map's time.
  for (int c = 164; c < 169; ++c) map[c] = encode_cell_speed(10.0f);
  update_detector(a, map.data(), 1, 10000, 1000, last.data());
  EXPECT_EQ(last[1], 9650);
  // The same rear at 3 m/s is farther than a step's drive from the loop: not a crossing in this step.
  for (int c = 164; c < 169; ++c) map[c] = encode_cell_speed(3.0f);
  update_detector(a, map.data(), 1, 11000, 1000, last.data());
  EXPECT_EQ(last[1], 9650);
  // A standing vehicle downstream never crossed in the step.
  for (int c = 164; c < 169; ++c) map[c] = encode_cell_speed(0.0f);
  update_detector(a, map.data(), 1, 12000, 1000, last.data());
  EXPECT_EQ(last[1], 9650);
}

TEST(ModelsActuated, GapControlExtendsToWholeSecondsWithinMaxDur) {
  const OneActuatedSignal sig;
  const SignalTable t = sig.table();
  const ActuatedTable& a = t.actuated;
  std::vector<int64_t> last{kNeverDetected, kNeverDetected};
  // Nothing detected: the phase ends at its minDur.
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 5000, 0, 4000, last.data()), -1);
  // Detected 0.5 s ago: extended until the vehicle is detector-gap (2 s) past the loop, rounded up so the
  // phase lasts whole seconds: 5 s + 1.5 s -> 7 s.
  last[0] = 3500;
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 5000, 0, 4000, last.data()), 2000);
  // Loop 1 does not serve phase 0.
  last[0] = kNeverDetected;
  last[1] = 3900;
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 5000, 0, 4000, last.data()), -1);
  // At least to minDur when asked early; never beyond maxDur; no extension at maxDur or past max-gap.
  last[0] = 2000;
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 3000, 0, 2000, last.data()), 2000);
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 49500, 0, 49000, last.data() /* since 47 s */), -1);
  last[0] = 49000;
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 49500, 0, 49000, last.data()), 500);
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 50000, 0, 49000, last.data()), -1);
  last[0] = 1000;
  EXPECT_EQ(actuated_extension_ms(a, 0, 0, 5000, 0, 4000, last.data()), -1);  // 3 s since: not < max-gap
  // A yellow phase is never extended.
  last[0] = 4000;
  EXPECT_EQ(actuated_extension_ms(a, 0, 1, 5000, 0, 4000, last.data()), -1);
}

TEST(ModelsActuated, GreenLastsWhileVehiclesKeepCrossingTheLoop) {
  const OneActuatedSignal sig;
  const SignalTable t = sig.table();
  std::vector<uint8_t> map(200 + kLaneMapPadding, 0);
  std::vector<char> links(2, '?');
  std::vector<int64_t> next{kSignalNeverSet};
  std::vector<int32_t> phase{-1};
  std::vector<int64_t> start{0}, last{0, 0};
  const ActuatedState st{phase.data(), start.data(), last.data()};
  // One step of 1 s at time `time`: the map is the state one second before.
  auto step = [&](int64_t time) {
    update_signal(t, 0, time, SignalInputs{map.data(), time - 1000, 1000}, links.data(), next.data(), st);
  };
  update_signal(t, 0, 0, SignalInputs{map.data(), 0, 1000}, links.data(), next.data(), st);
  EXPECT_EQ(std::string(links.begin(), links.end()), "Gr");
  EXPECT_EQ(next[0], 5000);  // the first phase, for its minDur
  // A vehicle stands on loop 0 from t = 0 to 12 s: green 0 is extended until the loop is free, then ends
  // once the extension runs out (detector-gap after the last detection, whole seconds).
  map[60] = 1;
  int64_t green_end = -1;
  for (int64_t time = 1000; time <= 60000 && green_end < 0; time += 1000) {
    if (time == 13000) map[60] = 0;
    step(time);
    if (links[0] != 'G') green_end = time;
  }
  // The last map showing it is that of 11 s (the step to 12 s reads it); the green lasts while less than
  // max-gap (3 s) has passed since, in whole seconds: it ends at 15 s.
  EXPECT_EQ(green_end, 15000);
  EXPECT_EQ(std::string(links.begin(), links.end()), "yr");
  // Nobody on either loop: the other green lasts its minDur only, and green 0 too.
  std::vector<std::pair<int64_t, std::string>> changes;
  std::string shown(links.begin(), links.end());
  for (int64_t time = 16000; time <= 40000; time += 1000) {
    step(time);
    const std::string now(links.begin(), links.end());
    if (now != shown) changes.emplace_back(time, now), shown = now;
  }
  const std::vector<std::pair<int64_t, std::string>> expected{{18000, "rG"}, {23000, "ry"}, {26000, "Gr"},
                                                              {31000, "yr"}, {34000, "rG"}, {39000, "ry"}};
  EXPECT_EQ(changes, expected);
}

}  // namespace
}  // namespace lpsim

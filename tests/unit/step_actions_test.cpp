// StepActions (app/step_actions.hpp): what a Run does between steps fires when its trigger says, at most once
// per step, on the clock it names; the begin round skips the accounts of a step. And a Run's own actions and
// one a driver adds run after each step in order.
#include "app/step_actions.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace lpsim {
namespace {

// The times an action was due at, over steps of `step` s from 0 to `last` (state time t, step end t + step).
std::vector<double> fired(StepTrigger trigger, double step, double last) {
  StepActions actions;
  std::vector<double> when;
  actions.add("a", std::move(trigger), [&](double t) { when.push_back(t); });
  actions.run_begin(0, step);
  for (int k = 1; k * step <= last + 1e-12; ++k) actions.run_due(k * step, (k + 1) * step);
  return when;
}

TEST(StepTriggerTest, EveryStepFiresOnEachStateTime) {
  EXPECT_EQ(fired(StepTrigger::every_step(), 1, 3), (std::vector<double>{0, 1, 2, 3}));
}

TEST(StepTriggerTest, EveryPeriodFiresAtItsScheduledTimes) {
  EXPECT_EQ(fired(StepTrigger::every(10, 0), 1, 25), (std::vector<double>{0, 10, 20}));
  // Steps of 0.4 s: the first state at or after each due time, reported as the due time.
  EXPECT_EQ(fired(StepTrigger::every(1, 0.5), 0.4, 2.0), (std::vector<double>{0.5, 1.5}));
  // On the step-end clock: due once the step's end reaches it (steps 0-1, 1-2, ...).
  EXPECT_EQ(fired(StepTrigger::every(2, 2, StepTrigger::Clock::StepEnd), 1, 4), (std::vector<double>{2, 4}));
}

TEST(StepTriggerTest, APeriodShorterThanTheStepFiresOncePerStep) {
  // Steps of 1 s, period 0.25 s: one firing per round (begin and 2 steps), never catching up.
  EXPECT_EQ(fired(StepTrigger::every(0.25, 0), 1, 2), (std::vector<double>{0, 0.25, 0.5}));
}

TEST(StepTriggerTest, AtFiresAtEachListedTime) {
  EXPECT_EQ(fired(StepTrigger::at({5, 7.5, 100}), 1, 20), (std::vector<double>{5, 7.5}));
  EXPECT_THROW(StepTrigger::every(0, 0), std::invalid_argument);
}

TEST(StepActionsTest, RunInOrderAndTheBeginRoundSkipsStepAccounts) {
  StepActions actions;
  std::vector<std::string> log;
  actions.add(
      "account", StepTrigger::every_step(), [&](double) { log.push_back("account"); },
      StepActions::AtBegin::Skip);
  actions.add("output", StepTrigger::every_step(), [&](double) { log.push_back("output"); });
  actions.add("checkpoint", StepTrigger::at({1}), [&](double) { log.push_back("checkpoint"); });
  actions.run_begin(0, 1);
  EXPECT_EQ(log, (std::vector<std::string>{"output"}));
  log.clear();
  actions.run_due(1, 2);
  EXPECT_EQ(log, (std::vector<std::string>{"account", "output", "checkpoint"}));
  EXPECT_EQ(actions.names(), (std::vector<std::string>{"account", "output", "checkpoint"}));
}

}  // namespace
}  // namespace lpsim

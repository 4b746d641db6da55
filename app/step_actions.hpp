#pragma once
// What a Run does between steps, each action with its trigger: the output writers, the jam recorder, and
// whatever a driver adds (a state checkpoint at given times, a remote-control command every step). The
// actions run after each step in the order they were added, on the state that step left; the first round
// runs on the state at the begin time.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace lpsim {

/// When an action is due. Times are simulated seconds on one of two clocks: the time the state shows (the
/// simulation's time(), as the FCD and summary outputs stamp it), or the end of the step that made it (as
/// edgeData intervals and SUMO's "Simulation ended at" count). A trigger fires at most once per step: one
/// that falls behind (a period shorter than the step) does not catch up.
class StepTrigger {
 public:
  enum class Clock { StateTime, StepEnd };

  /// Due after every step.
  static StepTrigger every_step();
  /// Due at `first`, first + period, first + 2 period, ... (period > 0) on `clock`.
  static StepTrigger every(double period, double first, Clock clock = Clock::StateTime);
  /// Due at each of `times` (ascending) on `clock`.
  static StepTrigger at(std::vector<double> times, Clock clock = Clock::StateTime);

  /// Whether the action is due with the clocks at these times; when it is, `*when` is the time it was due
  /// at (the scheduled time, or `state_time` for every_step) and the trigger moves to its next time.
  bool fire(double state_time, double step_end, double* when);
  /// Where the trigger is in its times (a checkpoint's; what it fires at is the caller's).
  template <class A>
  void visit_state(A& a) {
    a(next_);
    a(next_index_);
  }

 private:
  enum class Kind { EveryStep, Every, At };
  Kind kind_ = Kind::EveryStep;
  Clock clock_ = Clock::StateTime;
  double period_ = 0, next_ = 0;
  std::vector<double> times_;
  size_t next_index_ = 0;
};

class StepActions {
 public:
  /// `action(when)`: `when` is the time the trigger was due at.
  using Action = std::function<void(double when)>;
  /// Whether an action also runs on the state at the begin time, before the first step (an output of that
  /// state), or only after steps (an account of what a step did).
  enum class AtBegin { Run, Skip };

  void add(std::string name, StepTrigger trigger, Action action, AtBegin at_begin = AtBegin::Run);
  /// The round on the state at the begin time: the actions added with AtBegin::Run that are due.
  void run_begin(double state_time, double step_end);
  /// The round after a step: every action that is due, in the order they were added.
  void run_due(double state_time, double step_end);
  /// The actions' names, in order (what a run does between steps, for reports and tests).
  std::vector<std::string> names() const;
  /// The triggers' positions of the first `count` actions (a checkpoint's): a run resumed with the same
  /// actions fires them when the saved one would have.
  template <class A>
  void visit_state(A& a, size_t count) {
    uint64_t n = count;
    a(n);
    if (n != count || count > entries_.size())
      a.fail("the run's actions between steps differ from the saved run's");
    for (size_t k = 0; k < count; ++k) entries_[k].trigger.visit_state(a);
  }
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::string name;
    StepTrigger trigger;
    Action action;
    AtBegin at_begin;
  };
  void run(double state_time, double step_end, bool begin);
  std::vector<Entry> entries_;
};

}  // namespace lpsim

#include "app/step_actions.hpp"

#include <stdexcept>
#include <utility>

namespace lpsim {
namespace {

// Times are sums of step lengths in double: compare them with this slack.
constexpr double kTimeSlack = 1e-9;

}  // namespace

StepTrigger StepTrigger::every_step() { return StepTrigger{}; }

StepTrigger StepTrigger::every(double period, double first, Clock clock) {
  if (!(period > 0)) throw std::invalid_argument("StepTrigger::every: the period must be positive");
  StepTrigger t;
  t.kind_ = Kind::Every;
  t.clock_ = clock;
  t.period_ = period;
  t.next_ = first;
  return t;
}

StepTrigger StepTrigger::at(std::vector<double> times, Clock clock) {
  StepTrigger t;
  t.kind_ = Kind::At;
  t.clock_ = clock;
  t.times_ = std::move(times);
  return t;
}

bool StepTrigger::fire(double state_time, double step_end, double* when) {
  const double now = clock_ == Clock::StateTime ? state_time : step_end;
  switch (kind_) {
    case Kind::EveryStep:
      *when = now;
      return true;
    case Kind::Every:
      if (now + kTimeSlack < next_) return false;
      *when = next_;
      next_ += period_;
      return true;
    case Kind::At:
      if (next_index_ >= times_.size() || now + kTimeSlack < times_[next_index_]) return false;
      *when = times_[next_index_++];
      return true;
  }
  return false;
}

void StepActions::add(std::string name, StepTrigger trigger, Action action, AtBegin at_begin) {
  entries_.push_back(Entry{std::move(name), std::move(trigger), std::move(action), at_begin});
}

void StepActions::run_begin(double state_time, double step_end) { run(state_time, step_end, true); }

void StepActions::run_due(double state_time, double step_end) { run(state_time, step_end, false); }

void StepActions::run(double state_time, double step_end, bool begin) {
  for (Entry& e : entries_) {
    if (begin && e.at_begin == AtBegin::Skip) continue;
    double when = 0;
    if (e.trigger.fire(state_time, step_end, &when)) e.action(when);
  }
}

std::vector<std::string> StepActions::names() const {
  std::vector<std::string> out;
  for (const Entry& e : entries_) out.push_back(e.name);
  return out;
}

}  // namespace lpsim

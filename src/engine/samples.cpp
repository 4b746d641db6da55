#include "engine/samples.hpp"

#include "backends/stepper.hpp"

namespace lpsim {

void LaneCounters::resize(size_t lanes, bool emission_sums) {
  for (auto* v : {&sampled_steps, &travelled_mm, &waiting_steps, &time_loss_ms, &occupied_mm_steps, &departed,
                  &arrived, &entered, &left})
    v->assign(lanes, 0);
  for (auto& v : emission) v.assign(emission_sums ? lanes : 0, 0);
}

void LaneCounters::clear() { resize(sampled_steps.size(), !emission[0].empty()); }

}  // namespace lpsim

namespace lpsim {

LaneCounters counters_since(const LaneCounters& now, const LaneCounters& start) {
  LaneCounters d = now;
  auto sub = [](std::vector<int64_t>& a, const std::vector<int64_t>& b) {
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) a[i] -= b[i];
  };
  sub(d.sampled_steps, start.sampled_steps);
  sub(d.travelled_mm, start.travelled_mm);
  sub(d.waiting_steps, start.waiting_steps);
  sub(d.time_loss_ms, start.time_loss_ms);
  sub(d.occupied_mm_steps, start.occupied_mm_steps);
  sub(d.departed, start.departed);
  sub(d.arrived, start.arrived);
  sub(d.entered, start.entered);
  sub(d.left, start.left);
  for (int k = 0; k < kNumEmissionSums; ++k) sub(d.emission[k], start.emission[k]);
  return d;
}

std::vector<int64_t>& counter_column(LaneCounters& c, int k) {
  std::vector<int64_t>* columns[] = {&c.sampled_steps, &c.travelled_mm,      &c.waiting_steps,
                                     &c.time_loss_ms,  &c.occupied_mm_steps, &c.entered,
                                     &c.left,          &c.arrived,           &c.departed};
  static_assert(sizeof(columns) / sizeof(columns[0]) == kCountEmissionFirst);
  return k < kCountEmissionFirst ? *columns[k] : c.emission[k - kCountEmissionFirst];
}

}  // namespace lpsim

#include "engine/samples.hpp"

namespace lpsim {

void LaneCounters::resize(size_t lanes) {
  for (auto* v : {&sampled_steps, &travelled_mm, &waiting_steps, &time_loss_ms, &occupied_mm_steps, &departed,
                  &arrived, &entered, &left})
    v->assign(lanes, 0);
}

void LaneCounters::clear() { resize(sampled_steps.size()); }

}  // namespace lpsim

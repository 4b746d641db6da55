#include "engine/boundary_link.hpp"

#include <algorithm>
#include <stdexcept>

namespace lpsim {

int64_t BoundaryLink::settle_crossings(std::vector<uint32_t>& /*added*/) {
  const int64_t net = -static_cast<int64_t>(left_);
  left_ = 0;
  return net;
}

void BoundaryLink::write_foreign(int map, const std::vector<FootprintWrite>& writes) {
  if (writes.empty()) return;
  run_.stepper.write_footprints(map, writes, held_lanes_);
  std::vector<FootprintWrite>& kept = foreign_[map];
  for (const FootprintWrite& w : writes) kept.push_back(FootprintWrite{w.fp, w.length, 0});
}

void BoundaryLink::erase_foreign(int map) {
  std::vector<FootprintWrite>& kept = foreign_[map];
  if (!kept.empty()) run_.stepper.write_footprints(map, kept, held_lanes_);
  kept.clear();
}

void BoundaryLink::erase_removed(int map, const FootprintWrite& fp) {
  // A run of one part writes nothing from elsewhere: it holds every lane.
  const std::vector<uint8_t> every_lane(held_lanes_ ? 0 : run_.net.num_lanes(), 1);
  run_.stepper.write_footprints(map, {FootprintWrite{fp.fp, fp.length, 0}},
                                held_lanes_ ? held_lanes_ : every_lane.data());
}

std::vector<SampleEntry> BoundaryLink::own_running() const {
  std::vector<SampleEntry> mine;
  const HostState& s = run_.stepper.fetch(StateParts::Sample, run_.books.slots.size());
  for (uint32_t i = 0; i < s.num_active; ++i) {
    const uint32_t k = s.active[i];
    if (s.veh.status[k] == kRunning)
      mine.push_back(
          SampleEntry{s.veh.vehicle[k], s.veh.lane[k], s.veh.pos[k], s.veh.speed[k], s.veh.stop_release[k]});
  }
  return mine;
}

const std::vector<SampleEntry>& BoundaryLink::running_vehicles(uint64_t version) {
  if (sample_version_ == version) return sample_;
  sample_version_ = version;
  sample_ = own_running();
  std::sort(sample_.begin(), sample_.end(),
            [](const SampleEntry& a, const SampleEntry& b) { return a.vehicle < b.vehicle; });
  return sample_;
}

PartRequest BoundaryLink::next_request() {
  throw std::logic_error("serve_part: not a part other than part 0 of a partitioned run");
}

}  // namespace lpsim

#include "demand/demand.hpp"

#include <algorithm>

namespace lpsim {

uint64_t Demand::count(DemandSource s) const {
  return static_cast<uint64_t>(std::count(source.begin(), source.end(), s));
}

void StopTable::truncate(uint32_t n) {
  route_pos.resize(n);
  lane.resize(n);
  start_pos.resize(n);
  end_pos.resize(n);
  duration.resize(n);
  until.resize(n);
}

void StopTable::append(const StopTable& from, uint32_t first, uint32_t last) {
  auto copy = [&](auto& to, const auto& src) {
    to.insert(to.end(), src.begin() + first, src.begin() + last);
  };
  copy(route_pos, from.route_pos);
  copy(lane, from.lane);
  copy(start_pos, from.start_pos);
  copy(end_pos, from.end_pos);
  copy(duration, from.duration);
  copy(until, from.until);
}

}  // namespace lpsim

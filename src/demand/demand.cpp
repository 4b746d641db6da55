#include "demand/demand.hpp"

#include <algorithm>

namespace lpsim {

uint64_t Demand::count(DemandSource s) const {
  return static_cast<uint64_t>(std::count(source.begin(), source.end(), s));
}

}  // namespace lpsim

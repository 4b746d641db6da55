#include "net/network.hpp"

#include <algorithm>

namespace lpsim {

bool Network::connected(uint32_t from_edge, uint32_t to_edge) const {
  auto first = edge_succ.begin() + edge_succ_begin[from_edge];
  auto last = edge_succ.begin() + edge_succ_begin[from_edge + 1];
  return std::find(first, last, to_edge) != last;
}

double Network::lane_km() const {
  double metres = 0;
  for (uint32_t l = 0; l < num_lanes(); ++l)
    if (!edge_is_internal[lane_edge[l]]) metres += lane_length[l];
  return metres / 1000.0;
}

}  // namespace lpsim

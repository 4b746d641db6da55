#include "net/network.hpp"

#include <algorithm>
#include <cmath>

namespace lpsim {

bool Network::connected(uint32_t from_edge, uint32_t to_edge, uint32_t vclass) const {
  for (uint32_t i = edge_succ_begin[from_edge]; i < edge_succ_begin[from_edge + 1]; ++i)
    if (edge_succ[i] == to_edge) return (edge_succ_permissions[i] & vclass) != 0;
  return false;
}

double Network::lane_km() const {
  double metres = 0;
  for (uint32_t l = 0; l < num_lanes(); ++l)
    if (!edge_is_internal[lane_edge[l]]) metres += lane_length[l];
  return metres / 1000.0;
}

double Network::shape_segment_length(uint32_t i) const {
  return std::hypot(double(shape_x[i]) - shape_x[i - 1], double(shape_y[i]) - shape_y[i - 1]);
}

void release_name_indexes(Network& net) {
  // swap, not clear(): clear() keeps an unordered_map's bucket array
  decltype(net.edge_index)().swap(net.edge_index);
  decltype(net.lane_index_by_id)().swap(net.lane_index_by_id);
  decltype(net.junction_index)().swap(net.junction_index);
  decltype(net.signal_index)().swap(net.signal_index);
  decltype(net.left_out_lane_edge)().swap(net.left_out_lane_edge);
}

}  // namespace lpsim

#include "net/junction_foes.hpp"

#include <string>
#include <unordered_map>

namespace lpsim {

namespace {

// Junction link index of a connection with internal lanes: the position in the junction's intLanes of its
// via lane, or, for a link with an internal junction (left turns), of the second internal lane it
// continues on. intLanes lists exactly one internal lane per link, in link-index order.
int link_index_from_via(const Network& net, uint32_t conn, const std::unordered_map<std::string, int>& position) {
  const int32_t via = net.conn_via_lane[conn];
  if (via < 0) return -1;
  if (auto it = position.find(net.lane_id[static_cast<size_t>(via)]); it != position.end()) return it->second;
  for (uint32_t c = net.lane_conn_begin[via]; c < net.lane_conn_begin[via + 1]; ++c) {
    const int32_t next = net.conn_via_lane[c];
    if (next < 0) continue;
    if (auto it = position.find(net.lane_id[static_cast<size_t>(next)]); it != position.end()) return it->second;
  }
  return -1;
}

}  // namespace

void build_junction_foes(const NetSpec& spec, Network& net) {
  const uint32_t nconn = net.num_connections();
  std::vector<int32_t> link_of(nconn, -1);
  // Junction link index of every connection that leaves a normal lane.
  std::vector<std::vector<uint32_t>> by_link;  // reused per junction
  std::vector<std::vector<uint32_t>> conns_at(net.num_junctions());
  for (uint32_t c = 0; c < nconn; ++c) {
    const int32_t j = net.conn_junction[c];
    if (j < 0 || net.edge_is_internal[net.lane_edge[net.conn_from_lane[c]]]) continue;
    conns_at[static_cast<size_t>(j)].push_back(c);
  }
  std::vector<std::vector<uint32_t>> foes(nconn);
  for (const JunctionSpec& js : spec.junctions) {
    if (js.response.empty()) continue;
    auto it = net.junction_index.find(js.id);
    if (it == net.junction_index.end()) continue;
    const auto& conns = conns_at[it->second];
    by_link.assign(js.response.size(), {});
    int32_t rank = 0;
    bool by_rank = false;
    for (uint32_t c : conns)
      if (net.conn_via_lane[c] < 0) by_rank = true;
    if (by_rank) {
      // No internal lanes: rank in incLanes order, connections of one lane in file (CSR) order.
      for (const std::string& lane_id : js.inc_lanes) {
        auto li = net.lane_index_by_id.find(lane_id);
        if (li == net.lane_index_by_id.end()) continue;
        for (uint32_t c = net.lane_conn_begin[li->second]; c < net.lane_conn_begin[li->second + 1]; ++c)
          link_of[c] = rank++;
      }
    } else {
      std::unordered_map<std::string, int> position;
      for (size_t i = 0; i < js.int_lanes.size(); ++i) position.emplace(js.int_lanes[i], static_cast<int>(i));
      for (uint32_t c : conns) link_of[c] = link_index_from_via(net, c, position);
    }
    for (uint32_t c : conns)
      if (link_of[c] >= 0 && static_cast<size_t>(link_of[c]) < by_link.size())
        by_link[static_cast<size_t>(link_of[c])].push_back(c);
    for (uint32_t c : conns) {
      const int32_t k = link_of[c];
      if (k < 0 || static_cast<size_t>(k) >= js.response.size()) continue;
      const std::string& bits = js.response[static_cast<size_t>(k)];
      const size_t n = bits.size();
      for (size_t j = 0; j < n && j < by_link.size(); ++j)
        if (bits[n - 1 - j] == '1')
          for (uint32_t f : by_link[j]) foes[c].push_back(f);
    }
  }
  net.conn_foe_begin.assign(nconn + 1, 0);
  for (uint32_t c = 0; c < nconn; ++c) net.conn_foe_begin[c + 1] = net.conn_foe_begin[c] + foes[c].size();
  net.conn_foe.clear();
  net.conn_foe.reserve(net.conn_foe_begin[nconn]);
  for (auto& f : foes) net.conn_foe.insert(net.conn_foe.end(), f.begin(), f.end());
}

}  // namespace lpsim

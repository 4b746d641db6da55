#include "net/junction_foes.hpp"

#include <charconv>
#include <string_view>

namespace lpsim {

namespace {

// k of an internal lane id ":<junction>_<k>_<lane>", or -1.
int link_index_from_via(std::string_view via_lane, std::string_view junction) {
  if (via_lane.size() < junction.size() + 4 || via_lane[0] != ':') return -1;
  if (via_lane.substr(1, junction.size()) != junction || via_lane[junction.size() + 1] != '_') return -1;
  std::string_view rest = via_lane.substr(junction.size() + 2);
  int k = -1;
  auto [ptr, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), k);
  if (ec != std::errc() || ptr == rest.data() + rest.size() || *ptr != '_') return -1;
  return k;
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
      for (uint32_t c : conns)
        link_of[c] = link_index_from_via(net.lane_id[static_cast<size_t>(net.conn_via_lane[c])], js.id);
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

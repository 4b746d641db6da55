#include "net/junction_foes.hpp"

#include <string>

namespace lpsim {

namespace {

// Junction link index of a connection with internal lanes: the position in the junction's intLanes of its
// via lane, or, for a link with an internal junction (left turns), of the second internal lane it
// continues on. intLanes lists exactly one internal lane per link, in link-index order.
// `position[lane]` is that lane's position in the junction's intLanes, -1 when it is not listed.
int link_index_from_via(const Network& net, uint32_t conn, const std::vector<int32_t>& position) {
  const int32_t via = net.conn_via_lane[conn];
  if (via < 0) return -1;
  if (position[static_cast<size_t>(via)] >= 0) return position[static_cast<size_t>(via)];
  for (uint32_t c = net.lane_conn_begin[via]; c < net.lane_conn_begin[via + 1]; ++c) {
    const int32_t next = net.conn_via_lane[c];
    if (next >= 0 && position[static_cast<size_t>(next)] >= 0) return position[static_cast<size_t>(next)];
  }
  return -1;
}

// Network junction of a junction spec: the same position when the ids agree (the builder adds junctions in
// spec order), else a lookup by id; -1 when the network has no such junction.
int64_t junction_of_spec(const Network& net, size_t spec_index, const std::string& id) {
  if (spec_index < net.junction_id.size() && net.junction_id[spec_index] == id)
    return static_cast<int64_t>(spec_index);
  auto it = net.junction_index.find(id);
  return it == net.junction_index.end() ? -1 : static_cast<int64_t>(it->second);
}

}  // namespace

void build_junction_foes(const NetSpec& spec, Network& net) {
  const uint32_t nconn = net.num_connections();
  const size_t njunctions = net.num_junctions();
  std::vector<int32_t> link_of(nconn, -1);

  // Connections that leave a normal lane, grouped by junction (CSR, ascending connection index).
  std::vector<uint32_t> conns_begin(njunctions + 1, 0), conns_at;
  auto at_junction = [&](uint32_t c) {
    const int32_t j = net.conn_junction[c];
    return j >= 0 && !net.edge_is_internal[net.lane_edge[net.conn_from_lane[c]]] ? j : -1;
  };
  for (uint32_t c = 0; c < nconn; ++c)
    if (const int32_t j = at_junction(c); j >= 0) ++conns_begin[static_cast<size_t>(j) + 1];
  for (size_t j = 0; j < njunctions; ++j) conns_begin[j + 1] += conns_begin[j];
  conns_at.resize(conns_begin[njunctions]);
  {
    std::vector<uint32_t> fill(conns_begin.begin(), conns_begin.end() - 1);
    for (uint32_t c = 0; c < nconn; ++c)
      if (const int32_t j = at_junction(c); j >= 0) conns_at[fill[static_cast<size_t>(j)]++] = c;
  }

  // Each connection's foes are produced in one run (a connection belongs to one junction), so they are
  // appended to one flat list and placed in connection order at the end.
  std::vector<uint32_t> foe_flat, foe_start(nconn, 0), foe_count(nconn, 0);
  std::vector<int32_t> position(net.num_lanes(), -1);  // intLanes position per lane, reset per junction
  std::vector<uint32_t> positioned;                    // lanes whose position is set
  std::vector<uint32_t> link_begin, link_conns;        // connections by junction link index (CSR)

  for (size_t ji = 0; ji < spec.junctions.size(); ++ji) {
    const JunctionSpec& js = spec.junctions[ji];
    if (js.response.empty()) continue;
    const int64_t jn = junction_of_spec(net, ji, js.id);
    if (jn < 0) continue;
    const uint32_t* conns = conns_at.data() + conns_begin[static_cast<size_t>(jn)];
    const uint32_t nc = conns_begin[static_cast<size_t>(jn) + 1] - conns_begin[static_cast<size_t>(jn)];
    int32_t rank = 0;
    bool by_rank = false;
    for (uint32_t i = 0; i < nc; ++i)
      if (net.conn_via_lane[conns[i]] < 0) by_rank = true;
    if (by_rank) {
      // No internal lanes: rank in incLanes order, connections of one lane in file (CSR) order.
      for (const std::string& lane_id : js.inc_lanes) {
        auto li = net.lane_index_by_id.find(lane_id);
        if (li == net.lane_index_by_id.end()) continue;
        for (uint32_t c = net.lane_conn_begin[li->second]; c < net.lane_conn_begin[li->second + 1]; ++c)
          link_of[c] = rank++;
      }
    } else {
      for (size_t i = 0; i < js.int_lanes.size(); ++i) {
        auto li = net.lane_index_by_id.find(js.int_lanes[i]);
        if (li == net.lane_index_by_id.end() || position[li->second] >= 0) continue;  // first listing wins
        position[li->second] = static_cast<int32_t>(i);
        positioned.push_back(li->second);
      }
      for (uint32_t i = 0; i < nc; ++i) link_of[conns[i]] = link_index_from_via(net, conns[i], position);
      for (uint32_t l : positioned) position[l] = -1;
      positioned.clear();
    }

    const size_t links = js.response.size();
    link_begin.assign(links + 1, 0);
    for (uint32_t i = 0; i < nc; ++i)
      if (link_of[conns[i]] >= 0 && static_cast<size_t>(link_of[conns[i]]) < links)
        ++link_begin[static_cast<size_t>(link_of[conns[i]]) + 1];
    for (size_t k = 0; k < links; ++k) link_begin[k + 1] += link_begin[k];
    link_conns.resize(link_begin[links]);
    for (uint32_t i = 0; i < nc; ++i) {
      const int32_t k = link_of[conns[i]];
      if (k >= 0 && static_cast<size_t>(k) < links)
        link_conns[link_begin[static_cast<size_t>(k)]++] = conns[i];
    }
    for (size_t k = links; k > 0; --k) link_begin[k] = link_begin[k - 1];  // undo the fill's advance
    link_begin[0] = 0;

    for (uint32_t i = 0; i < nc; ++i) {
      const uint32_t c = conns[i];
      const int32_t k = link_of[c];
      if (k < 0 || static_cast<size_t>(k) >= links) continue;
      const std::string& foes = js.foes[static_cast<size_t>(k)];
      if (foes.find('1') == std::string::npos) net.conn_keep_clear[c] = 0;  // no foe: nobody to block
      const std::string& bits = js.response[static_cast<size_t>(k)];
      const size_t n = bits.size();
      foe_start[c] = static_cast<uint32_t>(foe_flat.size());
      for (size_t j = 0; j < n && j < links; ++j)
        if (bits[n - 1 - j] == '1')
          foe_flat.insert(foe_flat.end(), link_conns.begin() + link_begin[j],
                          link_conns.begin() + link_begin[j + 1]);
      foe_count[c] = static_cast<uint32_t>(foe_flat.size()) - foe_start[c];
    }
  }
  net.conn_foe_begin.assign(nconn + 1, 0);
  for (uint32_t c = 0; c < nconn; ++c) net.conn_foe_begin[c + 1] = net.conn_foe_begin[c] + foe_count[c];
  net.conn_foe.clear();
  net.conn_foe.reserve(net.conn_foe_begin[nconn]);
  for (uint32_t c = 0; c < nconn; ++c)
    net.conn_foe.insert(net.conn_foe.end(), foe_flat.begin() + foe_start[c],
                        foe_flat.begin() + foe_start[c] + foe_count[c]);
}

}  // namespace lpsim

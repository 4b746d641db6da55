#pragma once
// One vehicle's step, written once for the CPU backend and the CUDA kernels. Three passes per step:
//   approach: the first vehicle on each lane publishes where it is and which link it will take (read by
//             right-of-way checks of other vehicles in the plan pass);
//   plan:     from the previous step's lane map only, choose speed, lane change and new position; claim the
//             lanes whose start the front crosses;
//   commit:   keep the move if every claim was won (else stop at the lane end), write the footprint into the
//             next lane map, update counters.
// The hard guarantees (no shared cell, no passing a red light) come from clamping the move to the first
// occupied cell seen ahead and to mandatory stop lines, whatever the models propose.
#include <math.h>
#include <stdint.h>

#include "kernels/atomics.hpp"
#include "kernels/car_following.hpp"
#include "kernels/junction_space.hpp"
#include "kernels/lane_change.hpp"
#include "kernels/lane_counters.hpp"
#include "kernels/lane_map.hpp"
#include "kernels/right_of_way.hpp"
#include "kernels/scheduled_stop.hpp"
#include "kernels/signal_state.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

/// Everything the passes read or write, bundled so kernels take one argument.
struct StepContext {
  NetView net;
  TypeView types;
  TripView trips;
  VehicleView veh;
  PlanView plan;
  StepParams params;
  const uint8_t* map_now;    // lane map at the start of the step (read)
  uint8_t* map_next;         // lane map being built for the end of the step (written)
  const char* link_state;    // current signal character per signal link
  LaneApproach* approach;    // per lane
  uint64_t* claims;          // per lane
  uint64_t* merge_requests;  // per lane: a blocked mandatory lane changer asks followers there to open a gap
  const uint32_t* yielder_begin;  // [num_conns+1] connections that must yield to each connection (CSR)
  const uint32_t* yielder;
  // Per lane, for SUMO's --ignore-junction-blocker (null without it): the fewest consecutive steps any
  // vehicle whose front is on the junction lane has stood there, as the step began (now, read) and as it
  // ends (next, written: reset by the clear pass on the lanes fronts held two steps ago, as the lane map's
  // buffer is, then lowered by the commit pass). kNoJunctionStand where no front is.
  const uint32_t* junction_stand_now;
  uint32_t* junction_stand_next;
  EmissionView em;  // its sums are null unless an emissions output asks for them
  // Per-lane output counters, one record per lane (kernels/lane_counters.hpp; integers: order
  // independent). Null when no edgeData/laneData output asks for them.
  int64_t* lane_counts;
};

/// A vehicle on the road as the passes see it: `slot` indexes its running state (VehicleView), `id` its trip
/// (TripView), its random draws and its claims' tie-break.
struct VehicleRef {
  uint32_t slot;
  uint32_t id;
};

constexpr float kHaltingSpeed = 0.1f;      // SUMO's threshold for "waiting"
constexpr uint32_t kMergeSlots = 8;        // merge requests per lane (64 bytes: one cache line)
constexpr float kMergeSlotLength = 15.0f;  // m of lane per merge request slot, counted from the lane end
constexpr int kMaxPathHops = 8;            // lanes looked ahead beyond the current one
constexpr float kMaxLookahead = 1000.0f;
constexpr float kDecisionMargin = 10.0f;  // m beyond the stopping distance where link decisions are taken
constexpr float kFoeWindow = 1.0f;        // s of safety margin in right-of-way time windows
constexpr float kClampEps = 0.001f;

/// SUMO's impatience (MSVehicle::getImpatience with a vType impatience of 0): consecutive waiting over
/// --time-to-impatience, at most 1; 0 when impatience is off.
LPSIM_HD float impatience_of(uint32_t stopped_steps, uint32_t impatience_steps) {
  return impatience_steps == 0
             ? 0.0f
             : lp_fminf(1.0f, static_cast<float>(stopped_steps) / static_cast<float>(impatience_steps));
}

LPSIM_HD IdmParams idm_of(const StepContext& s, uint32_t type) {
  return IdmParams{s.types.accel[type], s.types.decel[type],   s.types.emergency_decel[type],
                   s.types.tau[type],   s.types.min_gap[type], s.types.delta[type],
                   s.types.sigma[type], s.types.model[type]};
}

/// Edge k of the route of vehicle v (from the whole demand's columns: for a vehicle not on the road yet).
LPSIM_HD uint32_t trip_route_edge(const StepContext& s, uint32_t v, uint32_t k) {
  return s.trips.route_edges[s.trips.route_begin[v] + k];
}

/// Edge k of the route of the vehicle in slot r.slot.
LPSIM_HD uint32_t route_edge(const StepContext& s, VehicleRef r, uint32_t k) {
  return s.trips.route_edges[s.veh.trip_route_begin[r.slot] + k];
}

/// Whether vClass mask `vclass` may use lane l.
LPSIM_HD bool lane_allows(const NetView& net, uint32_t l, uint32_t vclass) {
  return (net.lane_permissions[l] & vclass) != 0;
}

/// Whether vClass mask `vclass` may take connection c: its via lane and its target lane allow it.
LPSIM_HD bool conn_allows(const NetView& net, uint32_t c, uint32_t vclass) {
  const int32_t via = net.conn_via_lane[c];
  return lane_allows(net, net.conn_to_lane[c], vclass) &&
         (via < 0 || lane_allows(net, static_cast<uint32_t>(via), vclass));
}

/// vClass mask of the vehicle in slot r.slot.
LPSIM_HD uint32_t vclass_of(const StepContext& s, VehicleRef r) {
  return s.types.vclass_mask[s.veh.trip_type[r.slot]];
}

LPSIM_HD bool lane_has_conn_to(const NetView& net, int32_t lane, uint32_t edge, uint32_t vclass) {
  for (uint32_t c = net.lane_conn_begin[lane]; c < net.lane_conn_begin[lane + 1]; ++c)
    if (net.conn_to_edge[c] == edge && conn_allows(net, c, vclass)) return true;
  return false;
}

// Strategic lane choice looks this many edges (and at most this far) ahead along the route. Real nets split
// junction approaches into edges of a few metres or less; seeing only a few edges would hide a lane
// requirement just beyond them until the vehicle is trapped on a lane it can no longer leave.
constexpr uint32_t kBestLaneEdges = 8;
constexpr float kBestLaneDistance = 600.0f;

/// Bit k set: lane k (rank among the edge's lanes) of the route's edge rp+level can follow the route for
/// the next edges in view without a lane change (SUMO's "best lanes", limited to kBestLaneEdges), using
/// only lanes and connections that vClass mask `vclass` may use. Where no lane can, the lanes that at least
/// reach the next edge. Edges with more than 32 lanes see their first 32. A scheduled stop `stop_offset`
/// edges ahead (kNoStopAhead: none) allows only its lane (`stop_bit`) on its edge, as SUMO's best lanes
/// lead to the stop's lane.
struct BestLanes {
  uint32_t mask[kBestLaneEdges];
  uint32_t levels;  // edges in view (1 = only the current edge)
};

LPSIM_HD uint32_t lane_bit(const NetView& net, uint32_t lane) {
  const uint32_t rank = net.lane_rank[lane];
  return rank < 32 ? (1u << rank) : 0u;
}

LPSIM_HD uint32_t allowed_lane_bits(const NetView& net, uint32_t e, uint32_t vclass) {
  const uint32_t first = net.edge_first_lane[e];
  uint32_t bits = 0;
  for (uint32_t k = 0; k < net.edge_num_lanes[e] && k < 32; ++k)
    if (lane_allows(net, first + k, vclass)) bits |= 1u << k;
  return bits;
}

constexpr uint32_t kNoStopAhead = 0xFFFFFFFFu;
constexpr int32_t kNoLaneOffset = 1 << 20;

/// Lanes between the lane of rank `rank` and the nearest lane set in `mask` (0: it is set; kNoLaneOffset:
/// the mask is empty). Ranks past 32 count from lane 31.
LPSIM_HD int32_t rank_offset_to_mask(uint32_t rank, uint32_t mask) {
  const int32_t r = static_cast<int32_t>(rank < 32 ? rank : 31u);
  // Outwards from the lane itself: best_lanes asks this for every connection of every lane in view, and
  // the answer is mostly 0 or 1.
  for (int32_t d = 0; d < 32; ++d) {
    if (r - d >= 0 && (mask & (1u << (r - d)))) return d;
    if (r + d < 32 && (mask & (1u << (r + d)))) return d;
  }
  return kNoLaneOffset;
}

LPSIM_HD BestLanes best_lanes(const NetView& net, const uint32_t* route, uint32_t len, uint32_t rp,
                              uint32_t vclass, uint32_t stop_offset = kNoStopAhead, uint32_t stop_bit = 0) {
  BestLanes b{};
  // The current edge and always the next one; further edges while they start within the distance.
  float dist = 0.0f;
  uint32_t n = 1;
  while (n < kBestLaneEdges && rp + n < len && dist <= kBestLaneDistance) {
    dist += net.lane_length[net.edge_first_lane[route[rp + n]]];
    ++n;
  }
  b.levels = n;
  b.mask[n - 1] = allowed_lane_bits(net, route[rp + n - 1], vclass);
  if (stop_offset == n - 1) b.mask[n - 1] = stop_bit;
  for (int32_t i = static_cast<int32_t>(n) - 2; i >= 0; --i) {
    const uint32_t e = route[rp + static_cast<uint32_t>(i)];
    const uint32_t next = route[rp + static_cast<uint32_t>(i) + 1];
    const uint32_t first = net.edge_first_lane[e];
    // Each lane's fewest changes still to make on the next edge: 0 where it leads onto one of that edge's
    // best lanes. Where no lane does, the lanes leading nearest to one are best (SUMO's best lanes rank a
    // lane by its continuation and then by its connection's offset to the next edge's best lane), so that a
    // vehicle moves over here, not all at once on the next edge.
    uint32_t best = 0;
    int32_t best_d = kNoLaneOffset;
    for (uint32_t k = 0; k < net.edge_num_lanes[e] && k < 32; ++k) {
      if (!lane_allows(net, first + k, vclass)) continue;
      for (uint32_t c = net.lane_conn_begin[first + k]; c < net.lane_conn_begin[first + k + 1]; ++c) {
        if (net.conn_to_edge[c] != next || !conn_allows(net, c, vclass)) continue;
        const int32_t d = rank_offset_to_mask(net.lane_rank[net.conn_to_lane[c]], b.mask[i + 1]);
        if (d < best_d) best_d = d, best = 0;
        if (d == best_d) best |= 1u << k;
      }
    }
    b.mask[i] = stop_offset == static_cast<uint32_t>(i) ? stop_bit : best;
  }
  return b;
}

/// Empties slot k's caches keyed by route position (best lanes, the connection at the lane's end), which
/// also depend on its next scheduled stop.
LPSIM_HD void clear_route_caches(const VehicleView& veh, uint32_t k) {
  for (uint32_t e = 0; e < kBestLaneEntries; ++e) {
    veh.best_rp[k * kBestLaneEntries + e] = 0xFFFFFFFFu;
    veh.best_mask[k * kBestLaneEntries + e] = 0;
  }
  veh.conn_lane[k] = -1;
  veh.conn_rp[k] = 0;
  veh.conn[k] = -1;
}

/// The next scheduled stop of the vehicle in `slot` when it lies on its route edge `rp`, else -1.
LPSIM_HD int32_t stop_on_edge(const StepContext& s, uint32_t slot, uint32_t rp) {
  const uint32_t k = s.veh.next_stop[slot];
  return k < s.veh.stops_end[slot] && s.trips.stop_route_pos[k] == rp ? static_cast<int32_t>(k) : -1;
}

/// Best lanes of route edge rp of vehicle r, cached in kBestLaneEntries entries per slot, direct-mapped by
/// route position so the two edges a step mostly asks for (the current one and the next) never evict each
/// other. Only the vehicle's own thread reads or writes its entries; the value does not depend on when it
/// was computed.
LPSIM_HD uint32_t best_mask_at(const StepContext& s, VehicleRef r, uint32_t rp) {
  const uint32_t entry = r.slot * kBestLaneEntries + (rp & (kBestLaneEntries - 1u));
  if (s.veh.best_rp[entry] != rp) {
    // The next scheduled stop, if it lies on this edge or ahead (the cache is emptied when it is made).
    uint32_t stop_offset = kNoStopAhead, stop_bit = 0;
    const uint32_t k = s.veh.next_stop[r.slot];
    if (k < s.veh.stops_end[r.slot] && s.trips.stop_route_pos[k] >= rp) {
      stop_offset = s.trips.stop_route_pos[k] - rp;
      stop_bit = lane_bit(s.net, s.trips.stop_lane[k]);
    }
    s.veh.best_mask[entry] =
        best_lanes(s.net, s.trips.route_edges + s.veh.trip_route_begin[r.slot], s.veh.trip_route_size[r.slot],
                   rp, vclass_of(s, r), stop_offset, stop_bit)
            .mask[0];
    s.veh.best_rp[entry] = rp;
  }
  return s.veh.best_mask[entry];
}

/// Best lanes of the vehicle's current edge.
LPSIM_HD uint32_t current_best_mask(const StepContext& s, VehicleRef r) {
  return best_mask_at(s, r, s.veh.route_pos[r.slot]);
}

// A next edge shorter than this leaves no room to change lanes on it (real nets split junction approaches
// into edges of a few metres or less).
constexpr float kMinLaneChangeEdge = 15.0f;

/// A connection from `lane` to edge `next` onto a lane that continues to edge `after`, or -1 (for vClass
/// mask `vclass`).
LPSIM_HD int32_t conn_through(const NetView& net, int32_t lane, uint32_t next, uint32_t after,
                              uint32_t vclass) {
  for (uint32_t c = net.lane_conn_begin[lane]; c < net.lane_conn_begin[lane + 1]; ++c)
    if (net.conn_to_edge[c] == next && conn_allows(net, c, vclass) &&
        lane_has_conn_to(net, static_cast<int32_t>(net.conn_to_lane[c]), after, vclass))
      return static_cast<int32_t>(c);
  return -1;
}

/// The connection a vehicle takes at the end of `lane` to reach the route's next edge (index rp+1); prefers
/// a target lane among the next edge's best lanes. Only connections its vClass may take. -1: this lane
/// does not lead there, or only onto lanes of a short next edge that have no connection to the edge after
/// it (a trap: the vehicle waits here, where it can still change lanes, as SUMO's vehicles stop where their
/// lane's continuation ends).
LPSIM_HD int32_t choose_connection(const StepContext& s, VehicleRef r, int32_t lane, uint32_t rp) {
  const NetView& net = s.net;
  const uint32_t len = s.veh.trip_route_size[r.slot];
  int32_t first = -1;
  if (net.lane_internal[lane]) {
    // Internal lanes continue along their single link (or the one towards the route's next edge).
    for (uint32_t c = net.lane_conn_begin[lane]; c < net.lane_conn_begin[lane + 1]; ++c) {
      if (first < 0) first = static_cast<int32_t>(c);
      if (rp + 1 < len && net.conn_to_edge[c] == route_edge(s, r, rp + 1)) return static_cast<int32_t>(c);
    }
    return first;
  }
  if (rp + 1 >= len) return -1;
  const uint32_t next = route_edge(s, r, rp + 1);
  const uint32_t best = best_mask_at(s, r, rp + 1);
  const uint32_t vclass = vclass_of(s, r);
  for (uint32_t c = net.lane_conn_begin[lane]; c < net.lane_conn_begin[lane + 1]; ++c) {
    if (net.conn_to_edge[c] != next || !conn_allows(net, c, vclass)) continue;
    if (first < 0) first = static_cast<int32_t>(c);
    if (lane_bit(net, net.conn_to_lane[c]) & best) return static_cast<int32_t>(c);
  }
  if (first >= 0 && rp + 2 < len && net.lane_length[net.edge_first_lane[next]] < kMinLaneChangeEdge) {
    const uint32_t after = route_edge(s, r, rp + 2);
    const int32_t through = conn_through(net, lane, next, after, vclass);
    if (through >= 0) return through;
    // A trap only if another lane of this edge avoids it; else there is nothing better to wait for.
    const uint32_t edge = net.lane_edge[lane];
    const uint32_t l0 = net.edge_first_lane[edge];
    for (uint32_t l = l0; l < l0 + net.edge_num_lanes[edge]; ++l)
      if (lane_allows(net, l, vclass) && conn_through(net, static_cast<int32_t>(l), next, after, vclass) >= 0)
        return -1;
  }
  return first;
}

/// choose_connection at the end of the vehicle's current lane, through the slot's cache: a vehicle waiting
/// at its lane's end asks for it step after step. Only the vehicle's own thread reads or writes its entry.
LPSIM_HD int32_t current_lane_connection(const StepContext& s, VehicleRef r, int32_t lane, uint32_t rp) {
  if (s.veh.conn_lane[r.slot] != lane || s.veh.conn_rp[r.slot] != rp) {
    s.veh.conn[r.slot] = choose_connection(s, r, lane, rp);
    s.veh.conn_lane[r.slot] = lane;
    s.veh.conn_rp[r.slot] = rp;
  }
  return s.veh.conn[r.slot];
}

/// Signal character (or the connection's own state) currently governing a connection.
LPSIM_HD char link_state_of(const StepContext& s, uint32_t c) {
  const int32_t sig = s.net.conn_signal[c];
  if (sig < 0 || s.net.conn_link_index[c] < 0) return s.net.conn_state[c];
  return s.link_state[s.net.signal_link_begin[sig] + static_cast<uint32_t>(s.net.conn_link_index[c])];
}

/// The lane after a junction-internal lane (its single link), or -1.
LPSIM_HD int32_t lane_after_internal(const NetView& net, int32_t lane) {
  const uint32_t b = net.lane_conn_begin[lane];
  if (b == net.lane_conn_begin[lane + 1]) return -1;
  return net.conn_via_lane[b] >= 0 ? net.conn_via_lane[b] : static_cast<int32_t>(net.conn_to_lane[b]);
}

/// Connection c crosses its foes behind an internal junction: its via lane leads to a second internal lane
/// (SUMO's cont="1" links, e.g. left turns). Vehicles enter up to the internal junction and yield there.
LPSIM_HD bool has_internal_junction(const NetView& net, uint32_t c) {
  const int32_t via = net.conn_via_lane[c];
  if (via < 0) return false;
  const int32_t after = lane_after_internal(net, via);
  return after >= 0 && net.lane_internal[after] != 0;
}

/// Time until the last vehicle on the junction-internal lanes of connection c (its via lane and the
/// internal lanes after it, e.g. past an internal junction) has left them with its rear, accelerating at
/// accel; 0 when they are empty.
LPSIM_HD float conn_inside_clear_time(const StepContext& s, uint32_t c, float accel) {
  const NetView& net = s.net;
  int32_t chain[4];
  int32_t n = 0;
  int32_t lane = net.conn_via_lane[c];
  // A vehicle before an internal junction waits there for this vehicle's link: it is not in the way.
  if (has_internal_junction(net, c)) lane = lane_after_internal(net, lane);
  while (n < 4 && lane >= 0 && net.lane_internal[lane]) {
    chain[n++] = lane;
    lane = lane_after_internal(net, lane);
  }
  // The rear-most occupied cell on the chain belongs to the vehicle that leaves last.
  float rest = 0.0f;
  for (int32_t k = n - 1; k >= 0; --k) rest += net.lane_length[chain[k]];
  for (int32_t k = 0; k < n; ++k) {
    const int32_t lane = chain[k];
    rest -= net.lane_length[lane];
    const int32_t cells = static_cast<int32_t>(lane_cells(net, lane));
    const int32_t hit = first_occupied(s.map_now, net, lane, 0, cells - 1);
    if (hit < 0) continue;
    const float v = decode_cell_speed(s.map_now[net.lane_cell_begin[lane] + static_cast<uint32_t>(hit)]);
    const float dist = net.lane_length[lane] - static_cast<float>(hit) + rest;
    return earliest_arrival_time(dist, v, accel, lp_fmaxf(net.lane_speed[lane], 1.0f));
  }
  return 0.0f;
}

/// A vehicle that entered the junction on a link yielding to c is still inside and will not have left
/// it before this vehicle, arriving at the line in `own_arrival` seconds, gets there: a vehicle on c that
/// can still stop comfortably waits for it (SUMO's link leaders: prioritised vehicles brake for foes
/// already in the junction instead of driving through them).
LPSIM_HD bool yielder_inside(const StepContext& s, uint32_t c, float own_arrival) {
  for (uint32_t k = s.yielder_begin[c]; k < s.yielder_begin[c + 1]; ++k) {
    const uint32_t y = s.yielder[k];
    if (signal_is_red(link_state_of(s, y))) continue;  // cleared on its own green long ago or never entered
    if (conn_inside_clear_time(s, y, s.params.max_accel) > own_arrival) return true;
  }
  return false;
}

/// The link at the internal junction of connection c (a link without priority), `dist` metres ahead, whose
/// foes cannot be seen yet. As in SUMO, not after entering on a prioritised or yellow signal (the vehicle
/// is then committed to crossing).
LPSIM_HD bool unseen_at_internal_junction(const StepContext& s, uint32_t c, float dist) {
  const char entered = link_state_of(s, c);
  if (link_rule(entered) == LinkRule::Priority) return false;  // 'M', 'G', 'O' and yellow
  return foes_unseen('m', dist);
}

// Metres of a foe lane scanned for its nearest vehicle when none announced itself.
constexpr int32_t kFoeScanCells = 250;

/// SUMO's gap test against foe link f (from lane flane) for a vehicle that would pass connection c as
/// `own` (foe_blocks_passage): the foe is the first vehicle on flane, announced (LaneApproach) or, beyond
/// its reach, the nearest one found in the lane map, counted when flane has no other connection (its route
/// is not in the map). Vehicles on lanes before flane are not seen.
LPSIM_HD bool krauss_gap_blocked(const StepContext& s, uint32_t c, uint32_t f, uint32_t flane,
                                 const LinkPassage& own, const IdmParams& p, float impatience) {
  const NetView& net = s.net;
  const LaneApproach& a = s.approach[flane];
  const bool same_target = net.conn_to_lane[c] == net.conn_to_lane[f];
  // The foe's accel and decel are not in the lane map: the vehicle assumes its own, as Krauss does for
  // leaders.
  if (a.step == s.params.step) {
    if (a.conn != static_cast<int32_t>(f) || a.held) return false;
    return foe_blocks_passage(own, p.decel, AnnouncedFoe{a.dist, a.speed, p.accel, a.v_max, p.decel},
                              impatience, same_target, s.params.dt);
  }
  if (net.lane_conn_begin[flane + 1] - net.lane_conn_begin[flane] != 1) return false;
  const int32_t cells = static_cast<int32_t>(lane_cells(net, static_cast<int32_t>(flane)));
  const int32_t from = cells > kFoeScanCells ? cells - kFoeScanCells : 0;
  const int32_t hit = last_occupied(s.map_now, net, static_cast<int32_t>(flane), from, cells - 1);
  if (hit < 0) return false;
  const float v = decode_cell_speed(s.map_now[net.lane_cell_begin[flane] + static_cast<uint32_t>(hit)]);
  const float dist = lp_fmaxf(net.lane_length[flane] - static_cast<float>(hit + 1), 0.0f);
  return foe_blocks_passage(own, p.decel,
                            AnnouncedFoe{dist, v, p.accel, lp_fmaxf(net.lane_speed[flane], 1.0f), p.decel},
                            impatience, same_target, s.params.dt);
}

/// SUMO's --ignore-junction-blocker: the vehicles on junction lane `via` have all stood there at least the
/// given time (MSLink::getLeaderInfo leaves out a link leader whose waiting time reached it), so a foe
/// crossing their path no longer waits for them. Only vehicles whose front is on the lane are counted: a
/// lane holding only the tail of one that drove on is not ignored.
LPSIM_HD bool ignored_blocker(const StepContext& s, int32_t via) {
  if (s.junction_stand_now == nullptr) return false;
  const uint32_t stood = s.junction_stand_now[via];
  return stood != kNoJunctionStand && stood >= s.params.ignore_blocker_steps;
}

/// Right of way for entering connection c, `dist` metres ahead: every foe link it must yield to is either
/// closed by its signal, empty inside the junction and without an approaching vehicle that would arrive
/// before this one has cleared. Foes beyond their request horizon (the distance within which they could
/// still stop comfortably after one more step) are not considered: like SUMO, which only knows approaching
/// vehicles that announced their arrival, the foe then brakes for this vehicle (yielder_inside). Krauss
/// drivers take SUMO's own gap test instead (krauss_gap_blocked). Circular waits (right_before_left with
/// all approaches busy) are broken by letting the lowest lane index go once everyone involved stands.
LPSIM_HD bool may_enter(const StepContext& s, uint32_t c, float dist, float speed, float v0,
                        const IdmParams& p, float length, bool self_waiting, float impatience) {
  const NetView& net = s.net;
  const int32_t via = net.conn_via_lane[c];
  const uint32_t own_lane = net.conn_from_lane[c];
  // Krauss drivers stop at the line and take SUMO's gap test there; SUMO's IDM drivers creep over the line
  // (IDM's stop speed halts them about a metre short, then rolls them into the junction at 0.7 m/s) and
  // merge from inside it, which the time-window test below reproduces (docs/MODELS.md, "Junctions").
  const bool stops_at_line = is_krauss(p);
  const float via_length = via >= 0 ? net.lane_length[via] : 0.0f;
  const LinkPassage passage =
      stops_at_line ? link_passage(dist, speed, p.accel, s.params.dt, lp_fmaxf(v0, 1.0f), via_length,
                                   via >= 0 ? net.lane_speed[via] : lp_fmaxf(v0, 1.0f), length)
                    : LinkPassage{0.0f, 0.0f, 0.0f, 0.0f};
  const float own_clear =
      earliest_arrival_time(dist + (via_length + length), speed, p.accel, lp_fmaxf(v0, 1.0f));
  for (uint32_t k = net.conn_foe_begin[c]; k < net.conn_foe_begin[c + 1]; ++k) {
    const uint32_t f = net.conn_foe[k];
    const char fs = link_state_of(s, f);
    if (signal_is_red(fs)) continue;
    // A foe on its via lane blocks until its rear has passed the crossing, unless that link has an internal
    // junction: the vehicle there waits before the crossing (for links that include this one's).
    const int32_t fvia = net.conn_via_lane[f];
    int32_t inside = fvia >= 0 && !has_internal_junction(net, f)
                         ? first_occupied(s.map_now, net, fvia, 0, net.conn_foe_block_cells[k] - 1)
                         : -1;
    if (inside >= 0 && ignored_blocker(s, fvia)) inside = -1;
    const bool merge = net.conn_to_lane[c] == net.conn_to_lane[f];
    if (inside >= 0 && !(stops_at_line && merge)) return false;
    const uint32_t flane = net.conn_from_lane[f];
    const LaneApproach& a = s.approach[flane];
    if (stops_at_line) {
      LinkPassage own = passage;
      if (inside >= 0) {
        // A merging foe still in the junction is SUMO's link leader: the vehicle may follow it in once its
        // rear is ahead of where the vehicle's own front would be (minGap kept), leaving the link no faster
        // than its next step's speed (MSVehicle::adaptToLeader on a link leader).
        const float rear_to_end = net.lane_length[fvia] - static_cast<float>(inside);
        if (dist + via_length - rear_to_end - p.min_gap < 0.0f) return false;
        own = link_passage_capped(passage, lp_fmaxf(speed, 0.0f) + p.accel * s.params.dt, via_length, length);
      }
      // SUMO's gap test (see krauss_gap_blocked): every foe on the lane is announced, not only those within
      // their reach.
      if (krauss_gap_blocked(s, c, f, flane, own, p, impatience) &&
          !(self_waiting && a.step == s.params.step && a.speed < kHaltingSpeed && a.waiting > 0 &&
            own_lane < flane))
        return false;
      continue;
    }
    if (a.step != s.params.step || a.conn != static_cast<int32_t>(f) || a.held) continue;
    if (a.dist > a.reach) continue;  // not announced yet: it can still stop for this vehicle
    // The foe is expected at its current speed (as SUMO's announced arrival times), not at its fastest.
    const ApproachingFoe foe{a.dist, a.speed, 0.0f, a.speed};
    // An impatient vehicle counts on a foe that can still brake comfortably to let it go: SUMO takes such a
    // foe's arrival as if it braked, kSumoFoeStopDelay later at full impatience (MSLink::blockedByFoe).
    const float later = impatience > 0.0f && can_stop_before(a.dist, a.speed, p.decel, s.params.dt)
                            ? impatience * kSumoFoeStopDelay
                            : 0.0f;
    if (!foe_conflicts(foe, own_clear - later, kFoeWindow)) continue;
    // Deadlock breaking: both stand at their lines; the lower lane index goes first.
    if (self_waiting && a.speed < kHaltingSpeed && a.waiting > 0 && own_lane < flane) continue;
    return false;
  }
  return true;
}

// Normal-lane metres after a link over which the junction-blocking rule looks for room, in vehicle lengths
// (SUMO's CRLL_LOOK_AHEAD).
constexpr float kRoomLookAheadLengths = 5.0f;

/// The first connection from `lane` to route edge `next` that the vehicle's class may take, or -1: the way
/// on that the junction-blocking rule looks along (the lane actually taken is chosen when it gets there).
LPSIM_HD int32_t conn_onto(const NetView& net, int32_t lane, uint32_t next, uint32_t vclass) {
  for (uint32_t c = net.lane_conn_begin[lane]; c < net.lane_conn_begin[lane + 1]; ++c)
    if (net.conn_to_edge[c] == next && conn_allows(net, c, vclass)) return static_cast<int32_t>(c);
  return -1;
}

/// Link c, `dist` ahead, lets a vehicle arriving there go on (SUMO's MSLink::opened, as the
/// junction-blocking rule asks it of the links after the first): not closed, no halt required, and a
/// link without priority free of foes at the vehicle's arrival.
LPSIM_HD bool link_lets_through(const StepContext& s, uint32_t c, float dist, float speed, float v0,
                                const IdmParams& p, float length, float impatience) {
  const char st = link_state_of(s, c);
  if (signal_is_yellow(st)) return false;
  switch (link_rule(st)) {
    case LinkRule::Priority:
      return true;
    case LinkRule::Yield:
    case LinkRule::RightBeforeLeft:
      return may_enter(s, c, dist, speed, v0, p, length, false, impatience);
    default:
      return false;
  }
}

/// Fastest next speed from which braking at `decel` (Euler steps) gets down to v_lim by the time the front
/// has covered `dist` metres, and that is at most v_lim if the front would pass the boundary in this step.
LPSIM_HD float approach_speed_limit(float dist, float v_lim, float decel, float dt) {
  const float v = max_speed_within(lp_fmaxf(dist, 0.0f) + stopping_distance(v_lim, decel, dt), decel, dt);
  return v * dt > dist ? lp_fmaxf(v_lim, dist / dt) : lp_fmaxf(v, v_lim);
}

/// Lane a vehicle must move to (adjacent, towards the nearest lane leading to its next edge), or -1.
/// As mandatory_target, given the best-lane mask `good` of the lane's edge (computed once by the caller).
LPSIM_HD int32_t mandatory_target_in(const NetView& net, int32_t lane, uint32_t good,
                                     int32_t* lanes_to_cross) {
  if (lane_bit(net, static_cast<uint32_t>(lane)) & good) return -1;
  const uint32_t e = net.lane_edge[lane];
  const int32_t first_lane = static_cast<int32_t>(net.edge_first_lane[e]);
  const int32_t n = net.edge_num_lanes[e];
  int32_t best = -1, best_d = 1 << 20;
  for (int32_t k = 0; k < n && k < 32; ++k) {
    if (!(good & (1u << k))) continue;
    const int32_t d = first_lane + k > lane ? first_lane + k - lane : lane - first_lane - k;
    if (d < best_d) best_d = d, best = first_lane + k;
  }
  if (best < 0) return -1;
  *lanes_to_cross = best_d;
  return best > lane ? net.lane_left[lane] : net.lane_right[lane];
}

LPSIM_HD int32_t mandatory_target(const StepContext& s, VehicleRef r, int32_t lane, int32_t* lanes_to_cross) {
  const uint32_t rp = s.veh.route_pos[r.slot];
  if (s.net.lane_internal[lane] || rp + 1 >= s.veh.trip_route_size[r.slot]) return -1;
  const int32_t target = mandatory_target_in(s.net, lane, current_best_mask(s, r), lanes_to_cross);
  // A lane its class may not use between it and its best lanes leaves it where it is (as in SUMO).
  return target >= 0 && lane_allows(s.net, static_cast<uint32_t>(target), vclass_of(s, r)) ? target : -1;
}

// A merge request: step, the side the changer comes from (1: from the left of the target lane), its rear
// position in cm. Each lane has kMergeSlots of them, one per kMergeSlotLength metres from its end (the last
// takes the rest of the lane), so that every changer blocked along a queue gets its follower to hold back,
// as each of SUMO's blocked changers informs its own follower (MSLCM_LC2013::informFollower); an atomic max
// picks one per slot (left side first, then nearest the lane end).
LPSIM_HD uint64_t merge_key(uint32_t step, bool from_left, float rear_pos) {
  const float cm = lp_fminf(lp_fmaxf(rear_pos * 100.0f, 0.0f), 4.0e9f);
  return (static_cast<uint64_t>(step & 0xFFFFFFu) << 40) | (static_cast<uint64_t>(from_left ? 1 : 0) << 39) |
         static_cast<uint64_t>(cm);
}
LPSIM_HD float merge_rear(uint64_t key) { return static_cast<float>(key & 0x7FFFFFFFFFull) / 100.0f; }
LPSIM_HD bool merge_from_left(uint64_t key) { return ((key >> 39) & 1u) != 0; }
/// The slot of a lane of `lane_length` that a changer whose rear is at `rear_pos` beside it asks in.
LPSIM_HD uint32_t merge_slot(float lane_length, float rear_pos) {
  const float k = (lane_length - rear_pos) / kMergeSlotLength;
  return k <= 0.0f                                  ? 0u
         : k >= static_cast<float>(kMergeSlots - 1) ? kMergeSlots - 1
                                                    : static_cast<uint32_t>(k);
}
// m per lane to cross before the end of the usable distance where a blocked changer asks for a gap
constexpr float kMergeRequestZone = 30.0f;

/// Number of bytes of `f` with their high bit set, `f` having no other bits set.
LPSIM_HD int32_t count_byte_flags(uint64_t f) {
  return static_cast<int32_t>(((f >> 7) * 0x0101010101010101ull) >> 56);
}

/// Metres of a lane its vehicles take up, each with a minimum gap `gap` (SUMO's occupation of a lane): the
/// occupied cells plus one gap per run of occupied cells. Asked only for vehicles on a wrong lane, eight
/// cells at a time (the lane map has kLaneMapPadding readable bytes after its last cell).
LPSIM_HD float lane_occupation(const uint8_t* map, const NetView& net, int32_t lane, float gap) {
  const uint8_t* cells = map + net.lane_cell_begin[lane];
  const int32_t n = static_cast<int32_t>(lane_cells(net, lane));
  constexpr uint64_t kLow7 = 0x7F7F7F7F7F7F7F7Full, kHigh = 0x8080808080808080ull;
  int32_t occupied = 0, runs = 0;
  uint64_t carry = 0;  // the high bit of byte 0 set when the previous word's last cell is occupied
  for (int32_t c = 0; c < n; c += 8) {
    uint64_t w;
    memcpy(&w, cells + c, sizeof w);
    if (n - c < 8) w &= (uint64_t{1} << (8 * (n - c))) - 1;  // cells past the lane's end
    const uint64_t f = (((w & kLow7) + kLow7) | w) & kHigh;  // high bit of each occupied cell's byte
    occupied += count_byte_flags(f);
    runs += count_byte_flags(f & ~((f << 8) | carry));
    carry = f >> 56;
  }
  return static_cast<float>(occupied) + static_cast<float>(runs) * gap;
}

/// Metres a vehicle on a wrong lane can still drive before it must have changed lanes (SUMO's usableDist):
/// to the end of its lane's continuation along the route (the lanes its connections lead to, as far as they
/// lead on), less the occupation of the lane it changes to. A change need not be made on this edge when the
/// lane leads on, and the queue on the target lane makes it urgent before the changer reaches its tail. With
/// a scheduled stop on this edge: to the stop, less that occupation.
LPSIM_HD float usable_distance(const StepContext& s, VehicleRef r, int32_t lane, float pos, int32_t target,
                               float min_gap) {
  const NetView& net = s.net;
  float dist = net.lane_length[lane] - pos;
  int32_t l = lane;
  uint32_t rp = s.veh.route_pos[r.slot];
  const uint32_t len = s.veh.trip_route_size[r.slot];
  const uint32_t vclass = vclass_of(s, r);
  // A scheduled stop on this edge: its lane must be reached before the stop.
  const int32_t stop = stop_on_edge(s, r.slot, rp);
  if (stop >= 0) return s.trips.stop_end[stop] - pos - lane_occupation(s.map_now, net, target, min_gap);
  for (int h = 0; h < kMaxPathHops && dist < kMaxLookahead; ++h) {
    // Beyond the current lane, a connection that leads on along the route, found without the later edges'
    // best lanes (asking for them would evict the current edge's from the slot's two-entry cache).
    int32_t c = -1;
    if (h == 0)
      c = current_lane_connection(s, r, l, rp);
    else if (rp + 2 < len)
      c = conn_through(net, l, route_edge(s, r, rp + 1), route_edge(s, r, rp + 2), vclass);
    if (h > 0 && c < 0) c = conn_onto(net, l, route_edge(s, r, rp + 1), vclass);
    if (c < 0) break;
    int32_t nxt =
        net.conn_via_lane[c] >= 0 ? net.conn_via_lane[c] : static_cast<int32_t>(net.conn_to_lane[c]);
    while (nxt >= 0 && net.lane_internal[nxt]) {
      dist += net.lane_length[nxt];
      const uint32_t cb = net.lane_conn_begin[nxt];
      nxt = cb < net.lane_conn_begin[nxt + 1]
                ? (net.conn_via_lane[cb] >= 0 ? net.conn_via_lane[cb]
                                              : static_cast<int32_t>(net.conn_to_lane[cb]))
                : -1;
    }
    if (nxt < 0) break;
    ++rp;
    l = nxt;
    dist += net.lane_length[l];
    if (rp + 1 >= len) break;
  }
  return dist - lane_occupation(s.map_now, net, target, min_gap);
}

/// Approach pass: the first vehicle on its lane (nothing ahead until the lane end) publishes itself, and
/// a slow vehicle on a wrong lane whose usable distance is short asks the follower on the target lane to
/// open a gap (as SUMO's cooperative lane changing does), so queues cannot lock it out forever.
LPSIM_HD void approach_vehicle(StepContext& s, uint32_t i, uint32_t slot) {
  const VehicleRef r{slot, s.veh.vehicle[slot]};
  if (s.veh.status[slot] != kRunning) return;
  const int32_t lane = s.veh.lane[slot];
  const float pos = s.veh.pos[slot];
  int32_t to_cross = 0;
  // Only slow vehicles can be stuck on a wrong lane (the cheap test first).
  const int32_t target = s.veh.speed[slot] < 2.0f ? mandatory_target(s, r, lane, &to_cross) : -1;
  const float rear = pos - s.types.length[s.veh.trip_type[slot]];
  if (target >= 0 && rear > 0.0f &&
      usable_distance(s, r, lane, pos, target, idm_of(s, s.veh.trip_type[slot]).min_gap) <
          kMergeRequestZone * static_cast<float>(to_cross)) {
    // target is this lane's right neighbour when this lane is on its left.
    const bool from_left = target == s.net.lane_right[lane];
    atomic_max_u64(&s.merge_requests[static_cast<uint32_t>(target) * kMergeSlots +
                                     merge_slot(s.net.lane_length[target], rear)],
                   merge_key(s.params.step, from_left, rear));
  }
  // A vehicle farther from the lane end than its reach is ignored by foes (may_enter): it need not publish,
  // which also spares scanning the rest of long lanes for every vehicle.
  const float dist = s.net.lane_length[lane] - pos;
  const float reach = lookahead_distance(idm_of(s, s.veh.trip_type[slot]), s.veh.speed[slot], s.params.dt);
  s.plan.lookahead[i] = reach;
  if (dist > reach) return;
  const int32_t cells = static_cast<int32_t>(lane_cells(s.net, lane));
  const int32_t from = static_cast<int32_t>(cell_of(s.net, lane, pos)) + 1;
  if (from < cells && first_occupied(s.map_now, s.net, lane, from, cells - 1) >= 0) return;
  LaneApproach a;
  a.step = s.params.step;
  a.conn = current_lane_connection(s, r, lane, s.veh.route_pos[slot]);
  a.dist = dist;
  a.speed = s.veh.speed[slot];
  a.waiting = s.veh.stopped_steps[slot];
  a.held = s.veh.held_at_line[slot] != 0 && a.speed < kHaltingSpeed ? 1u : 0u;
  a.reach = reach;
  const uint32_t type = s.veh.trip_type[slot];
  a.v_max =
      desired_speed(lane_speed_for(s.net, lane, s.types.vclass_mask[type]), s.veh.trip_speed_factor[slot],
                    s.types.max_speed[type], s.types.desired_max_speed[type]);
  s.approach[lane] = a;
}

/// Lane-change target: a neighbouring lane `target` of the current one. Returns true and tightens the
/// speed/leader bounds when the change is safe and wanted.
struct LaneChangeResult {
  bool change;
  float speed_cap;   // max next speed behind the target lane's leader
  float leader_gap;  // distance to the first occupied cell ahead on the target lane (1e30: none)
  bool near_start;   // the changer's rear is within reach of vehicles entering the target lane this step
  bool tail_behind;  // its rear is still on the lanes before: the front changes, the tail stays there
};

/// A mandatory change (to_cross > 0: lanes still to cross) takes its urgency from the usable distance, found
/// only once the cheap tests let the change through to gap acceptance.
LPSIM_HD LaneChangeResult try_lane_change(const StepContext& s, VehicleRef me, int32_t lane, int32_t target,
                                          int32_t to_cross, float cand_here, float own_leader_gap,
                                          float own_leader_speed, bool own_has_leader) {
  LaneChangeResult r{false, 0.0f, 1e30f, false, false};
  const NetView& net = s.net;
  const uint32_t type = s.veh.trip_type[me.slot];
  const IdmParams p = idm_of(s, type);
  const float length = s.types.length[type];
  const float pos = s.veh.pos[me.slot];
  const float speed = s.veh.speed[me.slot];
  const float dt = s.params.dt;
  const float rear = pos - length;
  // Vehicles about to enter the target lane from upstream are not visible here: keep clear of its start.
  // Vehicles entering the target lane this step do not see the changer: near the start it claims the lane
  // entry with the lowest priority, so any entrant wins and the changer then stays in its lane.
  const float upstream_reach = (net.lane_speed[target] * 1.5f + s.params.max_accel * dt) * dt + p.min_gap;
  // A rear still on the lanes before: only a mandatory change on a lane too short for the body to be on it
  // ever (real nets split junction approaches into edges of a few metres), where SUMO changes the front's
  // lane and leaves the back on the lanes before (its further lanes).
  r.tail_behind = rear <= 0.0f;
  if (r.tail_behind && !(to_cross > 0 && net.lane_length[lane] < length)) return r;
  r.near_start = rear < upstream_reach;
  // Never cross the end while changing; one standing at the very end (inserted there) may change.
  if (cand_here > 0.0f && pos + cand_here * dt > net.lane_length[target] - kClampEps) return r;
  const int32_t cells = static_cast<int32_t>(lane_cells(net, target));
  const int32_t rear_cell = r.tail_behind ? 0 : static_cast<int32_t>(cell_of(net, target, rear));
  const int32_t front_cell = static_cast<int32_t>(cell_of(net, target, pos));
  if (first_occupied(s.map_now, net, target, rear_cell, front_cell) >= 0) return r;
  const float v0 =
      desired_speed(lane_speed_for(net, target, s.types.vclass_mask[type]), s.veh.trip_speed_factor[me.slot],
                    s.types.max_speed[type], s.types.desired_max_speed[type]);
  const float look = lookahead_distance(p, speed, dt);
  LcNeighbor lead = lc_no_neighbor();
  int32_t last = front_cell + 1 + metres_as_cells(look);
  if (last > cells - 1) last = cells - 1;
  const int32_t lc =
      front_cell + 1 <= last ? first_occupied(s.map_now, net, target, front_cell + 1, last) : -1;
  if (lc >= 0) {
    lead = LcNeighbor{true, static_cast<float>(lc) - pos,
                      decode_cell_speed(s.map_now[net.lane_cell_begin[target] + static_cast<uint32_t>(lc)]),
                      v0, p};
    lead.idm.emergency_decel = s.params.max_emergency_decel;
  }
  LcNeighbor lag = lc_no_neighbor();
  int32_t back_first = rear_cell - 1 - metres_as_cells(lookahead_distance(p, net.lane_speed[target], dt));
  if (back_first < 0) back_first = 0;
  const int32_t gc =
      rear_cell - 1 >= back_first ? last_occupied(s.map_now, net, target, back_first, rear_cell - 1) : -1;
  if (gc >= 0) {
    const float lag_speed =
        decode_cell_speed(s.map_now[net.lane_cell_begin[target] + static_cast<uint32_t>(gc)]) + 0.25f;
    // Its desired speed is not in the lane map either: at least the speed it drives. Taking the changer's
    // own made a faster follower seem to brake down to it, so a slow vehicle (a truck, a bicycle) never
    // changed in ahead of faster traffic however far behind.
    lag = LcNeighbor{true, rear - static_cast<float>(gc + 1), lag_speed, lp_fmaxf(v0, lag_speed), p};
    // The lag does not see the changer this step: it must not be able to reach the changer's rear.
    if (lag.gap <= (lag_speed + s.params.max_accel * dt) * dt + 0.5f) return r;
  }
  const LaneChangeParams lcp = lane_change_default_params();
  bool ok;
  if (to_cross > 0) {
    const float usable = usable_distance(s, me, lane, pos, target, p.min_gap);
    ok = lc_gaps_acceptable(p, speed, v0, lead, lag, mandatory_lc_urgency(usable, to_cross, speed, lcp), lcp,
                            dt);
  } else {
    LcNeighbor cur_lead = lc_no_neighbor();
    if (own_has_leader) cur_lead = LcNeighbor{true, own_leader_gap, own_leader_speed, v0, p};
    const float bias = target == net.lane_left[lane] ? 0.1f : 0.0f;  // mild keep-right preference
    ok = discretionary_change_wanted(p, speed, v0, length, cur_lead, lc_no_neighbor(), lead, lag, bias, lcp,
                                     dt);
  }
  if (!ok) return r;
  r.change = true;
  r.speed_cap = lead.present ? cf_follow_speed(p, speed, v0, lead.gap, lead.speed,
                                               s.params.max_emergency_decel, dt, s.params.substeps)
                             : 1e30f;
  r.leader_gap = lead.present ? lead.gap : 1e30f;
  return r;
}

/// Two vehicles standing side by side at their lanes' ends, each needing the other's lane, swap lanes
/// (as SUMO lets them): both see the same two merge requests and the same cells, so both decide alike.
/// Returns true when this vehicle swaps into `target`.
LPSIM_HD bool swap_with_neighbour(const StepContext& s, VehicleRef r, int32_t lane, int32_t target) {
  const NetView& net = s.net;
  const uint32_t step = s.params.step & 0xFFFFFFu;
  const float length = s.types.length[s.veh.trip_type[r.slot]];
  const float pos = s.veh.pos[r.slot];
  const float my_rear = pos - length;
  // Both stand at their lanes' ends: their requests are in the slots nearest the ends.
  const uint64_t mine = s.merge_requests[static_cast<uint32_t>(target) * kMergeSlots +
                                         merge_slot(net.lane_length[target], my_rear)];
  const uint64_t theirs = s.merge_requests[static_cast<uint32_t>(lane) * kMergeSlots];
  if ((mine >> 40) != step || (theirs >> 40) != step) return false;
  const bool target_is_right = target == net.lane_right[lane];
  if (mine != merge_key(s.params.step, target_is_right, my_rear)) return false;  // another request won
  // Theirs must come from the target lane's side of this lane.
  if (merge_from_left(theirs) != !target_is_right) return false;
  const float their_rear = merge_rear(theirs);
  // Their body: the occupied run on target ending at target's last cell (they stand at its end, as this
  // vehicle does at its own: the caller checked the same condition from its own cells) and starting at their
  // rear's cell, after a free cell.
  const int32_t front_cell = static_cast<int32_t>(lane_cells(net, target)) - 1;
  const int32_t their_rear_cell = static_cast<int32_t>(cell_of(net, target, their_rear));
  const uint8_t* t_cells = s.map_now + net.lane_cell_begin[target];
  if (t_cells[front_cell] == 0 || decode_cell_speed(t_cells[front_cell]) > 0.0f) return false;
  for (int32_t c = their_rear_cell; c <= front_cell; ++c)
    if (t_cells[c] == 0) return false;
  if (their_rear_cell > 0 && t_cells[their_rear_cell - 1] != 0) return false;
  // My body must fit on target below their run, and theirs on my lane below mine.
  const int32_t my_rear_cell = static_cast<int32_t>(cell_of(net, target, my_rear));
  if (my_rear_cell < their_rear_cell &&
      first_occupied(s.map_now, net, target, my_rear_cell, their_rear_cell - 1) >= 0)
    return false;
  const int32_t my_rear_cell_here = static_cast<int32_t>(cell_of(net, lane, my_rear));
  const int32_t their_rear_cell_here = static_cast<int32_t>(cell_of(net, lane, their_rear));
  if (their_rear_cell_here < my_rear_cell_here &&
      first_occupied(s.map_now, net, lane, their_rear_cell_here, my_rear_cell_here - 1) >= 0)
    return false;
  return my_rear > 0.0f && their_rear > 0.0f;
}

/// The vehicle the plan pass works on, as it stands at the start of the step: read once, handed to each
/// step of the plan.
struct PlanInput {
  VehicleRef r;
  uint32_t i;  // its position in this step's active list (where its plan goes)
  // By reference: the IDM functions left as calls take the parameters by address, and a PlanInput holding
  // them by value would then live in memory as a whole, every field stored there too (seen with callgrind).
  const IdmParams& p;
  float length;
  float speed_factor;
  float max_speed;
  float desired_max_speed;
  float dt;
  int32_t lane;
  float pos;
  float speed;
  uint32_t rp;          // route position
  uint32_t route_size;  // edges in the route
  float v0;             // desired speed on the current lane
  bool waiting;         // stopped in the last step (halt rules, deadlock breaking)
  float impatience;     // 0 to 1: its consecutive waiting over --time-to-impatience (SUMO's impatience)
};

LPSIM_HD_INLINED PlanInput read_plan_input(const StepContext& s, VehicleRef r, uint32_t i, uint32_t type,
                                           const IdmParams& p) {
  const uint32_t slot = r.slot;
  const int32_t lane = s.veh.lane[slot];
  const float speed_factor = s.veh.trip_speed_factor[slot];
  const float max_speed = s.types.max_speed[type];
  const float desired_max_speed = s.types.desired_max_speed[type];
  return PlanInput{.r = r,
                   .i = i,
                   .p = p,
                   .length = s.types.length[type],
                   .speed_factor = speed_factor,
                   .max_speed = max_speed,
                   .desired_max_speed = desired_max_speed,
                   .dt = s.params.dt,
                   .lane = lane,
                   .pos = s.veh.pos[slot],
                   .speed = s.veh.speed[slot],
                   .rp = s.veh.route_pos[slot],
                   .route_size = s.veh.trip_route_size[slot],
                   .v0 = desired_speed(lane_speed_for(s.net, lane, s.types.vclass_mask[type]), speed_factor,
                                       max_speed, desired_max_speed),
                   .waiting = s.veh.stopped_steps[slot] > 0,
                   .impatience = impatience_of(s.veh.stopped_steps[slot], s.params.impatience_steps)};
}

/// Where the plan puts the vehicle at the end of the step.
struct PlannedMove {
  float speed;
  int32_t lane;  // lane of the front
  float pos;
  int32_t prev;
  int32_t prev2;
  uint32_t rp;  // route position
};

/// The plan entries every vehicle gets, running or not: no lane-entry claims, no arrival.
LPSIM_HD_INLINED void write_no_claims(PlanView& out, uint32_t i) {
  out.claim_lane0[i] = -1;
  out.claim_lane1[i] = -1;
  out.arrives[i] = 0;
  out.claim_prio[i] = 1;
}

/// The move's plan entries (kept by the commit pass if every claim is won).
LPSIM_HD_INLINED void write_planned_move(PlanView& out, uint32_t i, const PlannedMove& m) {
  out.new_speed[i] = m.speed;
  out.new_lane[i] = m.lane;
  out.new_pos[i] = m.pos;
  out.new_prev[i] = m.prev;
  out.new_prev2[i] = m.prev2;
  out.new_rp[i] = m.rp;
}

/// Stuck side by side at the lane end with a vehicle that needs this lane: swap, standing still. Returns
/// true when the vehicle swaps; its whole plan is written then.
LPSIM_HD_INLINED bool plan_swap_at_lane_end(StepContext& s, const PlanInput& in) {
  const NetView& net = s.net;
  // The same test both vehicles of a swap apply to each other (from the lane map): standing in the last cell.
  if (!(encodes_as_standing(in.speed) & (cell_of(net, in.lane, in.pos) == lane_cells(net, in.lane) - 1)))
    return false;
  int32_t to_cross = 0;
  const int32_t target = mandatory_target(s, in.r, in.lane, &to_cross);
  if (target < 0 || !swap_with_neighbour(s, in.r, in.lane, target)) return false;
  s.veh.held_at_line[in.r.slot] = 0;
  s.veh.limit_reason[in.r.slot] = kSwap;
  PlanView& out = s.plan;
  write_planned_move(out, in.i, PlannedMove{0.0f, target, in.pos, -1, -1, in.rp});
  out.stop_lane[in.i] = target;
  out.stop_pos[in.i] = in.pos;
  out.first_rp[in.i] = in.rp;
  return true;
}

/// The lanes beyond the current one that the path walk passed into (PathBounds::hops of them): the lanes
/// the move may enter. Apart from PathBounds so that indexing the lanes does not keep the bounds in memory.
struct PathAhead {
  int32_t lane[kMaxPathHops];
  uint32_t rp[kMaxPathHops];  // route position once the front is on lane[h]
};

/// What the path walk found ahead: the bounds on the next speed and move, and what set them.
struct PathBounds {
  float cand;             // speed bound, the free-road speed included
  float hard_limit;       // the front must stay short of this distance (occupied cell / closed line)
  uint8_t reason;         // StopReason
  bool stop_at_own_line;  // the plan stops at the end of the lane the vehicle is on
  bool has_leader;        // the walk ended at an occupied cell: the leader's gap and speed below
  float leader_gap;
  float leader_speed;
  int32_t hops;  // lanes of the PathAhead passed into
};

/// Distance to a lane's end within which the link there is decided on (right of way, room behind it).
/// Computed where a link decision comes up, which most plans (a leader ahead on the lane) never reach.
LPSIM_HD_INLINED float decision_distance(const PlanInput& in) {
  return stopping_distance(in.speed, in.p.decel, in.dt) + in.speed * in.dt + kDecisionMargin;
}

/// Connection by which the vehicle entered the junction-internal lane it is on from a normal lane (-1: none,
/// or not on an internal lane).
LPSIM_HD_INLINED int32_t entry_connection(const StepContext& s, const PlanInput& in) {
  const NetView& net = s.net;
  int32_t entry_conn = -1;
  if (net.lane_internal[in.lane] && s.veh.prev[in.r.slot] >= 0 && !net.lane_internal[s.veh.prev[in.r.slot]]) {
    const int32_t pl = s.veh.prev[in.r.slot];
    for (uint32_t c = net.lane_conn_begin[pl]; c < net.lane_conn_begin[pl + 1]; ++c)
      if (net.conn_via_lane[c] == in.lane) entry_conn = static_cast<int32_t>(c);
  }
  return entry_conn;
}

/// First occupied cell of path lane `lane`, which starts `lane_start` ahead of the front, within the walk's
/// budget (-1: none). On the vehicle's own lane the search starts past its front cell.
LPSIM_HD_INLINED int32_t first_occupied_ahead(const StepContext& s, const PlanInput& in, int32_t lane,
                                              float lane_start, float budget) {
  const int32_t cells = static_cast<int32_t>(lane_cells(s.net, lane));
  const int32_t first = lane == in.lane ? static_cast<int32_t>(cell_of(s.net, lane, in.pos)) + 1 : 0;
  int32_t last = static_cast<int32_t>(budget - lane_start);
  if (last > cells - 1) last = cells - 1;
  return first <= last ? first_occupied(s.map_now, s.net, lane, first, last) : -1;
}

/// Bounds speed and move behind the vehicle in cell `hit` of path lane `lane` (starting `lane_start` ahead).
LPSIM_HD_INLINED void follow_leader_at(const StepContext& s, const PlanInput& in, int32_t lane,
                                       float lane_start, int32_t hit, PathBounds& b, float* free_speed) {
  const float gap = lane_start + static_cast<float>(hit);
  const float vl = decode_cell_speed(s.map_now[s.net.lane_cell_begin[lane] + static_cast<uint32_t>(hit)]);
  b.cand = lp_fminf(b.cand, cf_follow_speed(in.p, in.speed, in.v0, gap, vl, s.params.max_emergency_decel,
                                            in.dt, s.params.substeps, free_speed));
  b.hard_limit = lp_fminf(b.hard_limit, gap - kClampEps);
  b.reason = kLeader;
  b.has_leader = true;
  b.leader_gap = gap;
  b.leader_speed = vl;
}

/// Bounds the speed to stop at a line `end_dist` ahead.
LPSIM_HD_INLINED void stop_at(const StepContext& s, const PlanInput& in, float end_dist, PathBounds& b,
                              float* free_speed) {
  b.cand =
      lp_fminf(b.cand, cf_stop_speed(in.p, in.speed, in.v0, end_dist, in.dt, s.params.substeps, free_speed));
}

/// The route's way after a link, as the junction-blocking rule looks along it: the normal lanes reached
/// (each through the internal lanes of the link before it) and the link at each one's end. Found lane by
/// lane as the rule asks for them (most decisions end at the first lane), as far as the vehicle's own
/// look-ahead and that of a vehicle on its last lane reach.
struct RoomPath {
  int32_t n;
  bool ended;              // no lane after lane[n - 1] belongs to the path
  int32_t next_link;       // link into the next lane to find
  uint32_t rp;             // route position of lane[n - 1] (of the lane before the first link when n == 0)
  float normal, internal;  // lengths of the normal lanes found and of the internal lanes before them
  int32_t entry[kMaxPathHops];  // link into lane[k] (its internal lanes come first)
  int32_t lane[kMaxPathHops];
  int32_t exit[kMaxPathHops];  // link at lane[k]'s end on the route, -1: the route ends there (or a dead end)
  float internal_len[kMaxPathHops];  // length of entry[k]'s internal lanes
};

/// Normal lane behind a link's internal lanes.
LPSIM_HD int32_t lane_after_link(const NetView& net, uint32_t c) {
  int32_t lane = net.conn_via_lane[c] >= 0 ? net.conn_via_lane[c] : static_cast<int32_t>(net.conn_to_lane[c]);
  while (lane >= 0 && net.lane_internal[lane]) lane = lane_after_internal(net, lane);
  return lane;
}

/// The path after link c at the end of the lane with route position rp, no lane found yet.
LPSIM_HD RoomPath room_path_after(uint32_t c, uint32_t rp) {
  RoomPath p{};
  p.next_link = static_cast<int32_t>(c);
  p.rp = rp;
  return p;
}

/// Finds the path's lanes up to lane k; false when the path has no lane k.
LPSIM_HD bool room_path_has(const StepContext& s, const PlanInput& in, RoomPath& p, int32_t k) {
  const NetView& net = s.net;
  while (p.n <= k) {
    if (p.ended || p.n >= kMaxPathHops || p.next_link < 0) return false;
    const int32_t link = p.next_link;
    const int32_t lane = lane_after_link(net, static_cast<uint32_t>(link));
    if (lane < 0) {
      p.ended = true;
      return false;
    }
    float inside = 0.0f;
    for (int32_t l = net.conn_via_lane[link]; l >= 0 && net.lane_internal[l]; l = lane_after_internal(net, l))
      inside += net.lane_length[l];
    ++p.rp;
    const int32_t next = p.rp + 1 < in.route_size
                             ? conn_onto(net, lane, route_edge(s, in.r, p.rp + 1), vclass_of(s, in.r))
                             : -1;
    p.entry[p.n] = link;
    p.lane[p.n] = lane;
    p.exit[p.n] = next;
    p.internal_len[p.n] = inside;
    ++p.n;
    p.normal += net.lane_length[lane];
    p.internal += inside;
    p.ended = p.normal > 2.0f * lp_fmaxf(kRoomLookAheadLengths * in.length, in.length + p.internal);
    p.next_link = next;
  }
  return true;
}

/// A vehicle on path lane k will have to wait at a link it looks ahead to (SUMO's "have to wait on next
/// link"): one without priority, or a yellow or red signal, within the look-ahead of kRoomLookAheadLengths
/// vehicle lengths of normal lane after its own (our route stands in for its route).
LPSIM_HD bool waits_ahead(const StepContext& s, const PlanInput& in, RoomPath& p, int32_t k) {
  float normal = 0.0f, internal = 0.0f;
  for (int32_t j = k; room_path_has(s, in, p, j); ++j) {
    if (p.exit[j] < 0) return false;
    const char st = link_state_of(s, static_cast<uint32_t>(p.exit[j]));
    if (link_rule(st) != LinkRule::Priority || signal_is_yellow(st)) return true;
    if (!room_path_has(s, in, p, j + 1)) return false;
    normal += s.net.lane_length[p.lane[j + 1]];
    internal += p.internal_len[j + 1];
    if (normal > lp_fmaxf(kRoomLookAheadLengths * in.length, in.length + internal)) break;
  }
  return false;
}

/// SUMO's junction-blocking rule (MSVehicle::checkRewindLinkLanes) for link c at the end of the lane the
/// vehicle reaches `end_dist` ahead with route position `rp`: a link with foes is not entered when the room
/// after it is less than the vehicle's length and gap, the room being what the lanes after the link hold
/// (the internal lanes' vehicles count against it, each normal lane gives what it holds before a standing
/// vehicle) up to the first lane whose last vehicle stands or will have to wait, or the first link without
/// priority that does not let the vehicle through. When nothing stops within the look-ahead (a signal the
/// vehicle will stop at ends it, or kRoomLookAheadLengths vehicle lengths of normal lane), the vehicle
/// enters and follows whoever is ahead.
LPSIM_HD bool junction_exit_blocked(const StepContext& s, const PlanInput& in, uint32_t c, uint32_t rp,
                                    float end_dist) {
  const NetView& net = s.net;
  if (!net.conn_keep_clear[c]) return false;
  RoomPath p = room_path_after(c, rp);
  const float gap = in.p.min_gap, need = in.length + gap;
  float space = 0.0f, seen_internal = 0.0f, seen_normal = 0.0f, dist = end_dist;
  for (int32_t k = 0; room_path_has(s, in, p, k); ++k) {
    // Inside a junction the vehicles there count against the room; a link without foes lets its internal
    // lanes' free metres count as well.
    const bool keep_clear = net.conn_keep_clear[p.entry[k]] != 0;
    for (int32_t l = net.conn_via_lane[p.entry[k]]; l >= 0 && net.lane_internal[l];
         l = lane_after_internal(net, l)) {
      const LaneRoom r = room_on_lane(s.map_now, net, l, gap, !keep_clear);
      space += keep_clear ? r.space - net.lane_length[l] : r.space;
      if (r.standing) return space < need;
    }
    seen_internal += p.internal_len[k];
    dist += p.internal_len[k];
    const int32_t lane = p.lane[k];
    const LaneRoom r = room_on_lane(s.map_now, net, lane, gap, true);
    // An empty lane shorter than the vehicle cannot hold it (SUMO adds its length only when longer).
    if (!r.empty || net.lane_length[lane] > in.length) space += r.space;
    if (r.standing) return space < need;
    // A last vehicle that is slow (SUMO: slower than its decel per second) or will have to wait further on
    // ends the room with this lane, as a standing one does.
    if (!r.empty && (r.last_speed < in.p.decel || waits_ahead(s, in, p, k))) return space < need;
    seen_normal += net.lane_length[lane];
    dist += net.lane_length[lane];
    if (seen_normal > lp_fmaxf(kRoomLookAheadLengths * in.length, in.length + seen_internal)) return false;
    if (p.exit[k] < 0) return false;
    // SUMO's look-ahead ends at a signal the vehicle will stop at; unlike a link it may not pass yet, that
    // signal does not end the room (MSVehicle::checkRewindLinkLanes never asks whether its last link opens).
    if (signal_must_stop(link_state_of(s, static_cast<uint32_t>(p.exit[k])), dist, in.speed, in.p.decel,
                         in.dt))
      return false;
    if (!link_lets_through(s, static_cast<uint32_t>(p.exit[k]), dist, in.speed, in.v0, in.p, in.length,
                           in.impatience))
      return space < need;
  }
  return false;
}

/// Why the vehicle stops at the end of the normal lane `end_dist` ahead, whose link `c` shows `st`: a
/// StopReason, kFree when it may go on.
LPSIM_HD_INLINED uint8_t link_stop_reason(const StepContext& s, const PlanInput& in, uint32_t c, char st,
                                          uint32_t rp, float end_dist) {
  if (signal_must_stop(st, end_dist, in.speed, in.p.decel, in.dt) || link_rule(st) == LinkRule::Closed)
    return kSignal;
  if (end_dist <= decision_distance(in)) {
    const LinkRule rule = link_rule(st);
    const bool needs_halt = rule == LinkRule::StopThenYield || rule == LinkRule::AllwayStop;
    if (needs_halt && !(in.waiting && end_dist < 1.0f)) return kHaltRule;
    if (junction_exit_blocked(s, in, c, rp, end_dist)) return kNoRoom;
    // Links with an internal junction yield at it, inside the junction (SUMO's waiting position).
    if (!has_internal_junction(s.net, c) &&
        !may_enter(s, c, end_dist, in.speed, in.v0, in.p, in.length, in.waiting, in.impatience))
      return kYield;
    if (can_stop_before(end_dist, in.speed, in.p.decel, in.dt) &&
        yielder_inside(s, c, in.speed > kHaltingSpeed ? end_dist / in.speed : 0.0f))
      return kYield;
  }
  // Too far to see the foes of a link without priority: plan to stop at it while that is still possible.
  // A link with an internal junction is entered freely; its foes are seen at the internal junction.
  if (foes_unseen(st, end_dist) && !has_internal_junction(s.net, c) &&
      can_stop_before(end_dist, in.speed, in.p.decel, in.dt))
    return kYield;
  return kFree;
}

/// Stop at the line of a link showing `st`, `end_dist` ahead, for the reason link_stop_reason gave.
LPSIM_HD_INLINED void stop_at_link(const StepContext& s, const PlanInput& in, char st, float end_dist,
                                   PathBounds& b, float* free_speed) {
  stop_at(s, in, end_dist, b, free_speed);
  if (signal_is_red(st) || link_rule(st) == LinkRule::Closed || signal_is_yellow(st))
    b.hard_limit = lp_fminf(b.hard_limit, end_dist - kClampEps);  // never pass a closed line
  // A yield decision taken in time is also a hard line (the vehicle could stop for it).
  else if (can_stop_before(end_dist, in.speed, in.p.emergency_decel, in.dt))
    b.hard_limit = lp_fminf(b.hard_limit, end_dist - kClampEps);
}

/// At the internal junction at the end of the internal lane `lane` (`end_dist` ahead), entered by link
/// `entry_conn` (-1: not entered from a normal lane): wait for the prioritised foes of the link entered, or
/// until they can be seen.
LPSIM_HD_INLINED bool must_wait_at_internal_junction(const StepContext& s, const PlanInput& in,
                                                     int32_t entry_conn, int32_t lane, float end_dist) {
  return entry_conn >= 0 && s.net.conn_via_lane[entry_conn] == lane &&
         has_internal_junction(s.net, static_cast<uint32_t>(entry_conn)) &&
         ((unseen_at_internal_junction(s, static_cast<uint32_t>(entry_conn), end_dist) &&
           can_stop_before(end_dist, in.speed, in.p.decel, in.dt)) ||
          (end_dist <= decision_distance(in) &&
           !may_enter(s, static_cast<uint32_t>(entry_conn), end_dist, in.speed, in.v0, in.p, in.length,
                      in.waiting, in.impatience)));
}

/// The free-road speed joins the bounds found along the path. A free speed (never negative) cannot lower a
/// candidate of 0 or less: not computed then.
LPSIM_HD_INLINED void join_free_speed(const StepContext& s, const PlanInput& in, PathBounds& b,
                                      float free_speed) {
  if (b.cand > 0.0f) {
    if (free_speed < 0.0f) free_speed = cf_free_speed(in.p, in.speed, in.v0, in.dt, s.params.substeps);
    b.cand = lp_fminf(free_speed, b.cand);
  }
}

/// Distance from the front to where the vehicle's next scheduled stop makes it stand, when the stop lies on
/// path lane `lane` (at route position `rp`, starting `lane_start` ahead), or -1: the stop's end on the
/// stop's lane, and the same place on another lane of its edge, where it waits to change onto the stop's
/// lane (as SUMO's vehicles do not drive past their stop).
LPSIM_HD_INLINED float scheduled_stop_distance(const StepContext& s, const PlanInput& in, int32_t lane,
                                               uint32_t rp, float lane_start) {
  const int32_t stop = stop_on_edge(s, in.r.slot, rp);
  if (stop < 0 || s.net.lane_internal[lane]) return -1.0f;
  return lp_fmaxf(lane_start + s.trips.stop_end[stop], 0.0f);
}

/// Walk the path ahead: current lane, then the lanes the route leads through, up to the budget. Bounds the
/// speed by the leader, a wrong lane's end, the links' signals and right of way, and internal junctions, and
/// records in `path` the lanes passed into.
LPSIM_HD_INLINED PathBounds walk_path_ahead(const StepContext& s, const PlanInput& in, float budget,
                                            PathAhead& path) {
  const NetView& net = s.net;
  // Speed bounds found along the path; the free-road speed joins them after the walk. It is computed with
  // the first IDM interaction on the path (one loop for both: see idm_interaction_speed), else on its own.
  // min is exact, so the result equals taking the free speed first: an approach limit skipped here because
  // v_lim >= cand is at least v_lim, and so could not have lowered the minimum either.
  PathBounds b{1e30f, 1e30f, kFree, false, false, 0.0f, 0.0f, 0};
  float free_speed = -1.0f;
  int32_t cur = in.lane;
  float cur_start = -in.pos;
  uint32_t cur_rp = in.rp;
  // Connection by which the path entered the junction-internal lane `cur` from a normal lane (-1: none).
  int32_t entry_conn = entry_connection(s, in);
  for (;;) {
    const int32_t hit = first_occupied_ahead(s, in, cur, cur_start, budget);
    const float stop_dist = scheduled_stop_distance(s, in, cur, cur_rp, cur_start);
    if (stop_dist >= 0.0f && (hit < 0 || cur_start + static_cast<float>(hit) > stop_dist)) {
      stop_at(s, in, stop_dist, b, &free_speed);
      b.hard_limit = lp_fminf(b.hard_limit, stop_dist);
      b.reason =
          cur == static_cast<int32_t>(s.trips.stop_lane[s.veh.next_stop[in.r.slot]]) ? kStop : kWrongLane;
      break;
    }
    if (hit >= 0) {
      follow_leader_at(s, in, cur, cur_start, hit, b, &free_speed);
      break;
    }
    const float end_dist = cur_start + net.lane_length[cur];
    if (end_dist > budget || b.hops == kMaxPathHops) break;
    const bool normal = !net.lane_internal[cur];
    if (normal && cur_rp + 1 >= in.route_size)
      break;  // the route ends on this lane: arrival, no boundary to pass
    // At the current lane's end through the slot's cache (filled by the approach pass where it published).
    const int32_t c =
        b.hops > 0 ? choose_connection(s, in.r, cur, cur_rp) : current_lane_connection(s, in.r, cur, cur_rp);
    if (c < 0) {  // wrong lane for the route (or a dead end): the lane end is a wall until a lane change
      stop_at(s, in, end_dist, b, &free_speed);
      b.hard_limit = lp_fminf(b.hard_limit, end_dist - kClampEps);
      b.reason = kWrongLane;
      b.stop_at_own_line = b.hops == 0;
      break;
    }
    if (normal) {
      const char st = link_state_of(s, static_cast<uint32_t>(c));
      const uint8_t reason = link_stop_reason(s, in, static_cast<uint32_t>(c), st, cur_rp, end_dist);
      if (reason != kFree) {
        stop_at_link(s, in, st, end_dist, b, &free_speed);
        b.reason = reason;
        b.stop_at_own_line = b.hops == 0;
        break;
      }
    } else if (must_wait_at_internal_junction(s, in, entry_conn, cur, end_dist)) {
      stop_at(s, in, end_dist, b, &free_speed);
      if (can_stop_before(end_dist, in.speed, in.p.emergency_decel, in.dt))
        b.hard_limit = lp_fminf(b.hard_limit, end_dist - kClampEps);
      b.reason = kYield;
      break;
    }
    const int32_t via = net.conn_via_lane[c];
    const int32_t nxt = via >= 0 ? via : static_cast<int32_t>(net.conn_to_lane[c]);
    const float v_lim = desired_speed(lane_speed_for(net, nxt, vclass_of(s, in.r)), in.speed_factor,
                                      in.max_speed, in.desired_max_speed);
    if (v_lim < b.cand) b.cand = lp_fminf(b.cand, approach_speed_limit(end_dist, v_lim, in.p.decel, in.dt));
    path.lane[b.hops] = nxt;
    ++b.hops;
    if (!net.lane_internal[nxt]) ++cur_rp;
    entry_conn = normal && via >= 0 ? c : -1;
    path.rp[b.hops - 1] = cur_rp;
    cur = nxt;
    cur_start = end_dist;
  }
  join_free_speed(s, in, b, free_speed);
  return b;
}

/// Open a gap for the nearest blocked lane changer waiting beside this lane ahead of us.
LPSIM_HD_INLINED void open_gap_for_merge(const StepContext& s, const PlanInput& in, float budget,
                                         PathBounds& b) {
  if (s.net.lane_internal[in.lane]) return;
  const uint64_t* mr = s.merge_requests + static_cast<uint32_t>(in.lane) * kMergeSlots;
  const uint32_t step = s.params.step & 0xFFFFFFu;
  // Stop a minimum gap (plus room for the changer's lag check) short of the changer's rear. A vehicle
  // already closer than that drives on past it; the gap then opens behind it.
  const float lag_reach = (0.25f + s.params.max_accel * in.dt) * in.dt + 0.5f;  // the changer's lag check
  const float margin = lp_fmaxf(in.p.min_gap, lag_reach) + 1.5f;                // + cell rounding
  float gap = budget;
  for (uint32_t k = 0; k < kMergeSlots; ++k) {
    if ((mr[k] >> 40) != step) continue;
    const float g = merge_rear(mr[k]) - in.pos - margin;
    if (g > 0.0f && g < gap) gap = g;
  }
  if (gap < budget) {
    const float vs = cf_stop_speed(in.p, in.speed, in.v0, gap, in.dt, s.params.substeps);
    if (vs < b.cand) b.cand = vs, b.reason = kMergeGap;
  }
}

/// A vehicle that must change lanes soon and finds the target lane's vehicle beside it, one it cannot
/// overtake before the lane ends, slows to drop in behind it (SUMO's informLeader for a blocked strategic
/// change) instead of running on beside the target queue to its lane's end, where it would stand and block
/// its own lane's through traffic. Once slow it asks for a gap (approach_vehicle). "Soon": its usable
/// distance is within the mandatory zone.
LPSIM_HD_INLINED void fall_behind_target_leader(const StepContext& s, const PlanInput& in, PathBounds& b) {
  const NetView& net = s.net;
  if (net.lane_internal[in.lane] || in.rp + 1 >= in.route_size) return;
  if (lane_bit(net, static_cast<uint32_t>(in.lane)) & current_best_mask(s, in.r)) return;
  int32_t to_cross = 0;
  const int32_t target = mandatory_target(s, in.r, in.lane, &to_cross);
  const float rear = in.pos - in.length;
  if (target < 0 || rear <= 0.0f) return;
  const int32_t rear_cell = static_cast<int32_t>(cell_of(net, target, rear));
  const int32_t front_cell = static_cast<int32_t>(cell_of(net, target, in.pos));
  const int32_t hit = first_occupied(s.map_now, net, target, rear_cell, front_cell);
  if (hit < 0) return;
  const float gap = static_cast<float>(hit) - in.pos;  // <= 0: the target lane's vehicle is beside it
  if (gap > 0.0f) return;
  if (usable_distance(s, in.r, in.lane, in.pos, target, in.p.min_gap) >
      mandatory_lc_zone(to_cross, in.speed, lane_change_default_params()))
    return;
  const float dt = in.dt;
  const float vl = decode_cell_speed(s.map_now[net.lane_cell_begin[target] + static_cast<uint32_t>(hit)]);
  const float left = net.lane_length[in.lane] - in.pos;
  const float remaining_s = left / lp_fmaxf(in.speed, 1.0f);
  // The other vehicle's type is not in the lane map: its length and gaps are taken to be the changer's own.
  if (lc_can_overtake(in.speed, vl, gap, in.length + in.p.min_gap, in.length,
                      cf_secure_gap(in.p, vl, in.speed, dt), left,
                      stopping_distance(in.speed, in.p.decel, dt), remaining_s))
    return;
  // Measured: braking towards a stop beside it lets more changers in than matching its speed less the
  // overlap (docs/VALIDATION.md): the slow changer asks for a gap, and the queue beside moves past.
  const float v = lc_fall_behind_speed(in.speed, 0.0f, in.p.decel, remaining_s, dt);
  if (v < b.cand) b.cand = v, b.reason = kWrongLane;
}

/// A lane change to try this step: to `target` (-1: none), mandatory (toward the route's lanes, with
/// to_cross > 0 lanes still to cross) or not (to_cross 0).
struct LaneChangeAttempt {
  int32_t target;
  int32_t to_cross;
};

/// Lane changes on normal lanes only, left on even steps and right on odd ones, so that no lane receives
/// changers from both sides in one step.
LPSIM_HD_INLINED LaneChangeAttempt lane_change_attempt(const StepContext& s, const PlanInput& in) {
  const NetView& net = s.net;
  const LaneChangeAttempt none{-1, 0};
  const bool last_edge_here = in.rp + 1 >= in.route_size;
  // A scheduled stop on this edge: its lane must be reached before the stop, even on the route's last edge.
  if (net.lane_internal[in.lane] || (last_edge_here && stop_on_edge(s, in.r.slot, in.rp) < 0)) return none;
  const bool left_step = (s.params.step & 1u) == 0;
  const int32_t target = left_step ? net.lane_left[in.lane] : net.lane_right[in.lane];
  // Never onto a lane the vehicle's class may not use (a car beside a bus lane).
  if (target < 0 || !lane_allows(net, static_cast<uint32_t>(target), vclass_of(s, in.r))) return none;
  const uint32_t good = current_best_mask(s, in.r);
  const bool here_good = (lane_bit(net, static_cast<uint32_t>(in.lane)) & good) != 0;
  const bool target_good = (lane_bit(net, static_cast<uint32_t>(target)) & good) != 0;
  int32_t to_cross = 0;
  if (!here_good && mandatory_target_in(net, in.lane, good, &to_cross) == target)
    return LaneChangeAttempt{target, to_cross};
  if (here_good && target_good && !last_edge_here &&
      lc_attempt_allowed(s.params.seed, in.r.id, s.params.step, 0.5f))
    return LaneChangeAttempt{target, 0};
  return none;
}

/// The speed and lane the move starts from, with the limits on how far it may go.
struct MovePlan {
  float speed;
  int32_t lane;       // the current lane, or the lane changed to
  float hard_limit;   // the front must stay short of this distance
  int32_t hops;       // path lanes the move may pass into
  bool change_claim;  // the lane change claims the target lane's entry (the changer's rear is near its start)
  bool tail_behind;   // the lane change moves the front only: the tail stays on the lanes before
};

/// Changes lanes where the attempt is safe and wanted, bounding speed and move on the target lane.
LPSIM_HD_INLINED void plan_lane_change(const StepContext& s, const PlanInput& in, const PathBounds& b,
                                       MovePlan& m) {
  const LaneChangeAttempt attempt = lane_change_attempt(s, in);
  if (attempt.target < 0) return;
  const int32_t target = attempt.target;
  const LaneChangeResult lc = try_lane_change(s, in.r, in.lane, target, attempt.to_cross, m.speed,
                                              b.leader_gap, b.leader_speed, b.has_leader);
  if (!lc.change) return;
  m.lane = target;
  m.change_claim = lc.near_start;
  m.tail_behind = lc.tail_behind;
  m.speed = cf_finalize_speed(in.p, in.speed, lp_fminf(b.cand, lc.speed_cap), in.dt, s.params.seed, in.r.id,
                              s.params.step);
  m.hard_limit = lp_fminf(m.hard_limit, lc.leader_gap - kClampEps);
  if (in.rp + 1 < in.route_size &&
      !lane_has_conn_to(s.net, target, route_edge(s, in.r, in.rp + 1), vclass_of(s, in.r))) {
    const float end_dist = s.net.lane_length[target] - in.pos;
    m.speed = lp_fminf(
        m.speed, lp_fmaxf(0.0f, cf_stop_speed(in.p, in.speed, in.v0, end_dist, in.dt, s.params.substeps)));
    m.hard_limit = lp_fminf(m.hard_limit, end_dist - kClampEps);
  }
  m.hops = 0;  // the change step never crosses the lane end (checked in try_lane_change)
}

/// Move, clamped to the hard limit, into the path lanes ahead; claims the lanes whose start the front
/// crosses (and a lane change's target near its start) and writes where to stop if a claim is lost.
LPSIM_HD_INLINED PlannedMove move_clamped_to_hard_limit(StepContext& s, const PlanInput& in,
                                                        const PathAhead& path, const MovePlan& m) {
  const NetView& net = s.net;
  PlanView& out = s.plan;
  const uint32_t i = in.i;
  const uint32_t v = in.r.id;
  const float dt = in.dt;
  float advance = m.speed * dt;
  if (advance > m.hard_limit) advance = lp_fmaxf(0.0f, m.hard_limit);
  float new_speed = advance / dt;
  float npos = in.pos + advance;
  int32_t nlane = m.lane, nprev = s.veh.prev[in.r.slot], nprev2 = s.veh.prev2[in.r.slot];
  if (m.lane != in.lane && !m.tail_behind) {
    nprev = -1;  // a lane change moves the whole body across
    nprev2 = -1;
  }
  out.stop_lane[i] = m.lane;
  out.stop_pos[i] = npos;
  int32_t claims = 0;
  if (m.change_claim) {  // lowest priority; losing it means staying in the old lane at the same position
    out.claim_prio[i] = 0;
    out.claim_lane0[i] = m.lane;
    out.stop_lane[i] = in.lane;
    out.stop_pos[i] = npos + kClampEps;
    atomic_max_u64(&s.claims[m.lane], claim_key(s.params.step, 0, v));
  }
  uint32_t nrp = in.rp;
  out.first_rp[i] = in.rp;
  for (int32_t h = 0; h < m.hops && npos > net.lane_length[nlane]; ++h) {
    if (claims == 2) {  // at most two lane entries per step: stop at the end of the second lane
      npos = net.lane_length[nlane];
      break;
    }
    if (claims == 0) {
      out.stop_lane[i] = nlane;
      out.stop_pos[i] = net.lane_length[nlane];
    }
    npos -= net.lane_length[nlane];
    nprev2 = nprev;
    nprev = nlane;
    nlane = path.lane[h];
    nrp = path.rp[h];
    if (claims == 0)
      out.claim_lane0[i] = nlane, out.first_rp[i] = nrp;
    else
      out.claim_lane1[i] = nlane;
    ++claims;
    atomic_max_u64(&s.claims[nlane], claim_key(s.params.step, 1, v));
  }
  if (npos > net.lane_length[nlane]) npos = net.lane_length[nlane];
  new_speed = lp_fminf(new_speed, advance / dt);
  return PlannedMove{new_speed, nlane, npos, nprev, nprev2, nrp};
}

/// Arrival: on the route's last edge, at its arrival position (default: the lane's end), with no scheduled
/// stop left to make there (SUMO's MSVehicle::hasArrived: a stop at the lane's end is made before arriving).
LPSIM_HD_INLINED bool reaches_arrival(const StepContext& s, const PlanInput& in, const PlannedMove& m) {
  const NetView& net = s.net;
  if (net.lane_internal[m.lane] || m.rp + 1 < in.route_size) return false;
  if (s.veh.next_stop[in.r.slot] < s.veh.stops_end[in.r.slot]) return false;
  const uint32_t v = in.r.id;
  float arrival = net.lane_length[m.lane];
  if (s.trips.arrival_pos_kind[v] == 0) {  // ArrivalPos::Given; negative counts from the end
    const float a = s.trips.arrival_pos[v];
    arrival = a < 0.0f ? net.lane_length[m.lane] + a : a;
    if (arrival > net.lane_length[m.lane]) arrival = net.lane_length[m.lane];
  }
  return m.pos >= arrival - kClampEps;
}

/// The stop made (or dropped): the vehicle in `slot` goes on to its next one, to whose lane its cached best
/// lanes must now lead.
LPSIM_HD_INLINED void go_on_to_next_stop(const VehicleView& veh, uint32_t slot) {
  ++veh.next_stop[slot];
  clear_route_caches(veh, slot);
}

/// A vehicle standing out a scheduled stop keeps its place (its whole plan is written: true). Once its
/// stop is over it goes on towards the next one; a stop it can no longer make (its edge behind it, or its
/// place passed) is dropped.
LPSIM_HD_INLINED bool stand_at_scheduled_stop(StepContext& s, const PlanInput& in) {
  const VehicleView& veh = s.veh;
  const uint32_t slot = in.r.slot;
  const uint32_t release = veh.stop_release[slot];
  if (release != 0) {
    if (s.params.step < release) {
      veh.held_at_line[slot] = 1;  // it will not enter a junction now: foes need not wait for it
      veh.limit_reason[slot] = kStop;
      write_planned_move(s.plan, in.i,
                         PlannedMove{0.0f, in.lane, in.pos, veh.prev[slot], veh.prev2[slot], in.rp});
      s.plan.stop_lane[in.i] = in.lane;
      s.plan.stop_pos[in.i] = in.pos;
      s.plan.first_rp[in.i] = in.rp;
      return true;
    }
    veh.stop_release[slot] = 0;
    go_on_to_next_stop(veh, slot);
  }
  while (veh.next_stop[slot] < veh.stops_end[slot] && !s.net.lane_internal[in.lane]) {
    const uint32_t k = veh.next_stop[slot];
    const uint32_t rp = s.trips.stop_route_pos[k];
    if (rp > in.rp || (rp == in.rp && in.pos <= s.trips.stop_end[k] + kStopReachTolerance)) break;
    go_on_to_next_stop(veh, slot);
  }
  return false;
}

/// Plan pass for the vehicle in `slot`, `i` its position in this step's active list (where its plan goes).
/// Every plan entry the commit pass reads is written here in every step.
LPSIM_HD void plan_vehicle(StepContext& s, uint32_t i, uint32_t slot) {
  const VehicleRef r{slot, s.veh.vehicle[slot]};
  write_no_claims(s.plan, i);
  if (s.veh.status[slot] != kRunning) return;
  const uint32_t type = s.veh.trip_type[slot];
  const IdmParams p = idm_of(s, type);
  const PlanInput in = read_plan_input(s, r, i, type, p);
  if (stand_at_scheduled_stop(s, in)) return;
  if (plan_swap_at_lane_end(s, in)) return;
  const float budget = lp_fminf(s.plan.lookahead[i] + in.p.min_gap, kMaxLookahead);
  PathAhead path;
  PathBounds bounds = walk_path_ahead(s, in, budget, path);
  // A vehicle that stops at its own lane's end (red, full next lane, yielding, wrong lane) will not enter the
  // junction now: foes need not yield to it (SUMO's approaching vehicles that will not pass).
  s.veh.held_at_line[slot] = bounds.stop_at_own_line ? 1 : 0;
  open_gap_for_merge(s, in, budget, bounds);
  fall_behind_target_leader(s, in, bounds);
  s.veh.limit_reason[slot] = bounds.reason;
  MovePlan move{cf_finalize_speed(in.p, in.speed, bounds.cand, in.dt, s.params.seed, r.id, s.params.step),
                in.lane,
                bounds.hard_limit,
                bounds.hops,
                false,
                false};
  plan_lane_change(s, in, bounds, move);
  const PlannedMove planned = move_clamped_to_hard_limit(s, in, path, move);
  if (reaches_arrival(s, in, planned)) s.plan.arrives[i] = 1;
  write_planned_move(s.plan, i, planned);
}

/// Clears the footprint a vehicle had one step ago from the buffer that is about to be written.
LPSIM_HD void clear_old_footprint(StepContext& s, uint32_t /*i*/, uint32_t slot) {
  const Footprint fp{s.veh.old_lane[slot], s.veh.old_prev[slot], s.veh.old_prev2[slot], s.veh.old_pos[slot]};
  apply_footprint(s.map_next, s.net, fp, s.types.length[s.veh.trip_type[slot]], 0);
  if (s.junction_stand_next != nullptr && fp.lane >= 0 && s.net.lane_internal[fp.lane])
    atomic_store_u32(&s.junction_stand_next[fp.lane], kNoJunctionStand);
}

/// No vehicle stood ahead of a front at `pos` on `lane` as the step began. SUMO teleports only the first
/// vehicle of a lane (MSLane::executeMovements): the ones behind it keep waiting, and once it is gone they
/// usually move up instead of teleporting in the same step.
/// The vehicle in `slot`, at route position rp on `lane`, has stood long enough to teleport if it is the
/// lane's first: --time-to-teleport, or --time-to-teleport.highways on a lane faster than its minimum speed
/// that does not lead to the route's next edge (SUMO's "wrong lane" on a highway, MSLane::executeMovements).
LPSIM_HD bool teleport_due(const StepContext& s, uint32_t slot, uint32_t rp, int32_t lane) {
  const uint32_t stopped = s.veh.stopped_steps[slot];
  const StepParams& p = s.params;
  if (p.teleport_steps > 0 && stopped >= p.teleport_steps) return true;
  if (p.highway_teleport_steps == 0 || stopped < p.highway_teleport_steps) return false;
  const NetView& net = s.net;
  if (net.lane_internal[lane] || net.lane_speed[lane] <= p.highway_min_speed) return false;
  if (rp + 1 >= s.veh.trip_route_size[slot]) return false;
  const VehicleRef r{slot, s.veh.vehicle[slot]};
  return !lane_has_conn_to(net, lane, route_edge(s, r, rp + 1), vclass_of(s, r));
}

LPSIM_HD bool first_on_lane(const StepContext& s, int32_t lane, float pos) {
  const int32_t last = static_cast<int32_t>(lane_cells(s.net, lane)) - 1;
  const int32_t front = static_cast<int32_t>(cell_of(s.net, lane, pos));
  return front >= last || first_occupied(s.map_now, s.net, lane, front + 1, last) < 0;
}

/// The vehicle in `slot` ends the step standing at its next scheduled stop (on its lane, within its
/// stretch, below SUMO's halting speed): it stands there until the stop's release step.
LPSIM_HD_INLINED bool begin_scheduled_stop(const StepContext& s, uint32_t slot, uint32_t rp, int32_t lane,
                                           float pos, float speed, float length) {
  const int32_t k = stop_on_edge(s, slot, rp);
  if (k < 0 || lane != static_cast<int32_t>(s.trips.stop_lane[k]) || speed >= kHaltingSpeed) return false;
  if (!stop_reached(pos, length, s.trips.stop_start[k], s.trips.stop_end[k])) return false;
  s.veh.stop_release[slot] =
      stop_release_step(s.params.step, s.trips.stop_duration_steps[k], s.trips.stop_until_step[k]);
  return true;
}

/// Commit pass for the vehicle in `slot` (its plan at `i`): settle claims, write the new footprint, update
/// counters.
LPSIM_HD_INLINED void commit_vehicle(StepContext& s, uint32_t i, uint32_t slot) {
  const uint32_t v = s.veh.vehicle[slot];
  VehicleView& veh = s.veh;
  // The footprint at the start of this step becomes "one step ago" (cleared two buffers later).
  veh.old_lane[slot] = veh.status[slot] == kRunning ? veh.lane[slot] : -1;
  veh.old_prev[slot] = veh.prev[slot];
  veh.old_prev2[slot] = veh.prev2[slot];
  veh.old_pos[slot] = veh.pos[slot];
  if (veh.status[slot] != kRunning) return;
  // Standing at a scheduled stop through this step (its plan kept it there).
  const bool stood_at_stop = veh.stop_release[slot] > s.params.step;
  const NetView& net = s.net;
  PlanView& plan = s.plan;
  const uint32_t type = s.veh.trip_type[slot];
  const float length = s.types.length[type];
  const float dt = s.params.dt;
  const int32_t lane = veh.lane[slot];
  const float pos = veh.pos[slot];

  int32_t nlane = plan.new_lane[i], nprev = plan.new_prev[i], nprev2 = plan.new_prev2[i];
  float npos = plan.new_pos[i], nspeed = plan.new_speed[i];
  bool arrives = plan.arrives[i] != 0;
  const uint64_t key = claim_key(s.params.step, plan.claim_prio[i], v);
  const int32_t c0 = plan.claim_lane0[i], c1 = plan.claim_lane1[i];
  const bool lost0 = c0 >= 0 && s.claims[c0] != key;
  const bool lost1 = c1 >= 0 && s.claims[c1] != key;
  if (lost0 || lost1) {
    arrives = false;
    if (lost0) {  // stay on the lane before the first claimed one, at its end
      nlane = plan.stop_lane[i];
      npos = plan.stop_pos[i] - kClampEps;
      if (nlane == lane) {
        nprev = veh.prev[slot];
        nprev2 = veh.prev2[slot];
      } else {
        nprev = lane;
        nprev2 = veh.prev[slot];
      }
    } else {  // keep the first lane entered, stop at its end
      nprev2 = veh.prev[slot];
      nprev = lane;
      nlane = c0;
      npos = net.lane_length[c0] - kClampEps;
    }
    if (nlane == lane && npos < pos) npos = pos;
  }
  // Distance driven this step along the path.
  float driven;
  if (nlane == lane)
    driven = npos - pos;
  else if (nprev == lane)
    driven = net.lane_length[lane] - pos + npos;
  else if (nprev2 == lane && nprev >= 0)
    driven = net.lane_length[lane] - pos + net.lane_length[nprev] + npos;
  else
    driven = npos - pos;  // lane change: longitudinal advance only
  if (driven < 0.0f) driven = 0.0f;
  nspeed = driven / dt;
  if (nspeed > plan.new_speed[i]) nspeed = plan.new_speed[i];

  // Route position follows the front over every normal edge it entered (as planned, or up to the fallback).
  const uint32_t rp = lost0 ? veh.route_pos[slot] : (lost1 ? plan.first_rp[i] : plan.new_rp[i]);
  veh.route_pos[slot] = rp;

  // Standing at a scheduled stop at the end of this step (reached in it, or stood through it): as in SUMO,
  // neither waiting nor losing time.
  const bool at_stop =
      stood_at_stop || (!arrives && begin_scheduled_stop(s, slot, rp, nlane, npos, nspeed, length));

  // Per-vehicle counters (tripinfo).
  const float v0 =
      desired_speed(lane_speed_for(net, nlane, s.types.vclass_mask[type]), veh.trip_speed_factor[slot],
                    s.types.max_speed[type], s.types.desired_max_speed[type]);
  // Time lost this step against the desired speed [s]; no loss where the desired speed is 0.
  const float lost = v0 > 0.0f ? dt * lp_fmaxf(0.0f, (v0 - nspeed) / v0) : 0.0f;
  veh.route_length[slot] += driven;
  veh.time_loss[slot] += at_stop ? 0.0f : lost;
  veh.stop_steps[slot] += at_stop ? 1u : 0u;
  // Counted without branches: whether a vehicle halts in a step is hard to predict.
  const uint32_t halting = (nspeed < kHaltingSpeed ? 1u : 0u) & (at_stop ? 0u : 1u);
  veh.waiting_count[slot] += halting & (veh.stopped_steps[slot] == 0 ? 1u : 0u);
  veh.stopped_steps[slot] = halting * (veh.stopped_steps[slot] + 1u);
  veh.waiting_steps[slot] += halting;
  veh.lane_change_dir[slot] = nlane != lane && net.lane_edge[nlane] == net.lane_edge[lane]
                                  ? (nlane == net.lane_left[lane] ? 1 : 2)
                                  : 0;

  // Per-lane counters (edgeData/laneData), attributed to the lane of the front bumper. The front passed
  // lane -> c0 -> c1 (the claims kept); each change of edge leaves a normal lane / enters a normal lane.
  // Absent (null) when no edgeData/laneData output is requested: five atomics per vehicle saved.
  int64_t* const counts = s.lane_counts;
  if (counts != nullptr) {
    int32_t chain[3] = {lane, -1, -1};
    int32_t links = 0;
    if (c0 >= 0 && !lost0) chain[++links] = c0;
    if (c1 >= 0 && !lost0 && !lost1) chain[++links] = c1;
    for (int32_t k = 0; k < links; ++k) {
      const int32_t a = chain[k], b = chain[k + 1];
      if (net.lane_edge[a] == net.lane_edge[b]) continue;  // a lane change (claimed near a lane start)
      if (!net.lane_internal[a]) count_on_lane(counts, a, kCountLeft, 1);
      if (!net.lane_internal[b]) count_on_lane(counts, b, kCountEntered, 1);
    }
    count_on_lane(counts, nlane, kCountSampledSteps, 1);
    count_on_lane(counts, nlane, kCountTravelledMm, static_cast<int64_t>(driven * 1000.0f + 0.5f));
    if (nspeed < kHaltingSpeed) count_on_lane(counts, nlane, kCountWaitingSteps, 1);
    if (v0 > 0.0f)
      count_on_lane(counts, nlane, kCountTimeLossMs, static_cast<int64_t>(lost * 1000.0f + 0.5f));
    count_on_lane(
        counts, nlane, kCountOccupiedMmSteps,
        static_cast<int64_t>(lp_fminf(length, lp_fminf(npos, net.lane_length[nlane])) * 1000.0f + 0.5f));
  }

  if (arrives) {
    if (counts != nullptr) count_on_lane(counts, nlane, kCountArrived, 1);
    veh.status[slot] = kArrived;
    veh.arrival_step[slot] = s.params.step + 1;
    veh.lane[slot] = nlane;
    veh.pos[slot] = npos;
    veh.speed[slot] = nspeed;
    return;  // no footprint: it left the network
  }
  if (teleport_due(s, slot, rp, nlane) && first_on_lane(s, nlane, npos)) {
    veh.status[slot] = kTeleporting;  // the host moves it on along its route
    veh.lane[slot] = nlane;
    veh.pos[slot] = npos;
    veh.speed[slot] = 0.0f;
    return;
  }
  veh.lane[slot] = nlane;
  veh.pos[slot] = npos;
  veh.prev[slot] = nprev;
  veh.prev2[slot] = nprev2;
  veh.speed[slot] = nspeed;
  apply_footprint(s.map_next, net, Footprint{nlane, nprev, nprev2, npos}, length, encode_cell_speed(nspeed));
  if (s.junction_stand_next != nullptr && net.lane_internal[nlane])
    atomic_min_u32(&s.junction_stand_next[nlane], veh.stopped_steps[slot]);
}

// --- After the passes: which vehicles left the road this step, and which stay in the active list. ---

enum : uint32_t { kEndNone = 0, kEndArrived = 1, kEndTeleport = 2 };

/// The vehicle in `slot` arrived in the step just done (steps_done counts it), or started a teleport in it
/// (its clock ran out: a teleport already handed to the host has its clock reset).
LPSIM_HD uint32_t step_end_kind(const VehicleView& veh, uint32_t slot, uint32_t steps_done,
                                uint32_t teleport_steps) {
  if (veh.status[slot] == kArrived && veh.arrival_step[slot] == steps_done) return kEndArrived;
  if (veh.status[slot] == kTeleporting && teleport_steps > 0 && veh.stopped_steps[slot] >= teleport_steps)
    return kEndTeleport;
  return kEndNone;
}

/// Running vehicles stay in the active list, and those that left the road this step for one more step: the
/// next step's clear pass removes their footprint. A slot not kept is free again after this step, which is
/// exactly one step after its vehicle's end (the host relies on this to recycle slots).
LPSIM_HD bool stays_active(const VehicleView& veh, uint32_t slot) {
  return veh.status[slot] == kRunning || veh.old_lane[slot] >= 0;
}

/// What the host needs of a vehicle that arrived or started a teleport (trip record, route position).
LPSIM_HD VehicleEnd vehicle_end(const VehicleView& veh, uint32_t slot, uint32_t kind) {
  return VehicleEnd{veh.vehicle[slot],
                    slot,
                    kind,
                    veh.lane[slot],
                    veh.pos[slot],
                    veh.speed[slot],
                    veh.route_length[slot],
                    veh.time_loss[slot],
                    veh.route_pos[slot],
                    veh.waiting_steps[slot],
                    veh.waiting_count[slot],
                    veh.limit_reason[slot],
                    veh.next_stop[slot],
                    veh.stop_steps[slot]};
}

/// The host's decision for a teleporting vehicle: its trip ends (past the end of its route), or it waits to
/// re-enter at the next edge of its route (the host queues it; the slot only waits to be cleared).
LPSIM_HD void apply_teleport_move(const VehicleView& veh, const TeleportMove& m, uint32_t steps_done) {
  if (m.ends_trip) {
    veh.status[m.slot] = kArrived;
    veh.arrival_step[m.slot] = steps_done;
  } else {
    veh.stopped_steps[m.slot] = 0;
  }
}

/// A vehicle takes a free slot after its insertion: its state starts from where it was placed, with no
/// earlier footprint, and the trip counters it carries over.
LPSIM_HD void activate_slot(const VehicleView& veh, const TripView& trips, const SlotInit& in) {
  const uint32_t k = in.slot;
  veh.status[k] = kRunning;
  veh.vehicle[k] = in.vehicle;
  veh.trip_type[k] = trips.type[in.vehicle];
  veh.trip_speed_factor[k] = trips.speed_factor[in.vehicle];
  veh.trip_route_begin[k] = trips.route_begin[in.vehicle];
  veh.trip_route_size[k] = trips.route_length[in.vehicle];
  veh.route_pos[k] = in.route_pos;
  veh.speed[k] = in.speed;
  veh.lane[k] = in.lane;
  veh.prev[k] = -1;
  veh.prev2[k] = -1;
  veh.pos[k] = in.pos;
  veh.old_lane[k] = -1;
  veh.old_prev[k] = -1;
  veh.old_prev2[k] = -1;
  veh.old_pos[k] = 0.0f;
  veh.stopped_steps[k] = 0;
  veh.waiting_steps[k] = in.waiting_steps;
  veh.waiting_count[k] = in.waiting_count;
  veh.time_loss[k] = in.time_loss;
  veh.route_length[k] = in.route_length;
  veh.arrival_step[k] = 0;
  veh.lane_change_dir[k] = 0;
  veh.held_at_line[k] = 0;
  veh.limit_reason[k] = 0;
  veh.next_stop[k] = in.next_stop;
  veh.stops_end[k] = in.stops_end;
  veh.stop_release[k] = 0;
  veh.stop_steps[k] = in.stop_steps;
  veh.emission_speed[k] = in.speed;
  veh.emission_flags[k] = kEmissionFlagsOnEntry;
  clear_route_caches(veh, k);
}

/// A running vehicle takes a new route: the slot's copy of the trip's route fields follows it, and the caches
/// keyed by route position (best lanes, the connection at the lane's end) are emptied, as their positions
/// now count along another route.
LPSIM_HD void set_slot_route(const VehicleView& veh, const SlotRoute& r) {
  const uint32_t k = r.slot;
  veh.trip_route_begin[k] = r.route_begin;
  veh.trip_route_size[k] = r.route_size;
  veh.route_pos[k] = r.route_pos;
  // Its stops were placed along the old route: a new one drops those not yet made.
  veh.next_stop[k] = veh.stops_end[k];
  veh.stop_release[k] = 0;
  clear_route_caches(veh, k);
}

}  // namespace lpsim

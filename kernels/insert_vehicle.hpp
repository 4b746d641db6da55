#pragma once
// Insertion of departing and teleported vehicles, written once for both backends. Waiting vehicles queue per
// edge (first in, first out); each step the host hands over the head of every non-empty queue as a batch, and
// one call per edge inserts from the head until a vehicle does not fit. An insertion writes only cells of the
// edge's own lanes, so edges are independent: the CPU loops over them, the GPU runs one thread per edge, and
// the result does not depend on the order.
#include <stdint.h>

#include "kernels/rng.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

// SUMO's depart attributes as the demand stores them (src/core/demand_spec.hpp's enums, checked there).
constexpr uint8_t kDepartLaneGiven = 0, kDepartLaneFirst = 1, kDepartLaneRandom = 2, kDepartLaneFree = 3,
                  kDepartLaneAllowed = 4, kDepartLaneBest = 5;
constexpr uint8_t kDepartPosGiven = 0, kDepartPosBase = 1, kDepartPosRandom = 2, kDepartPosFree = 3,
                  kDepartPosRandomFree = 4, kDepartPosLast = 5, kDepartPosStop = 6;
constexpr uint8_t kDepartSpeedGiven = 0, kDepartSpeedZero = 1, kDepartSpeedRandom = 2, kDepartSpeedMax = 3,
                  kDepartSpeedDesired = 4, kDepartSpeedLimit = 5, kDepartSpeedLast = 6, kDepartSpeedAvg = 7;

// Salt for departure draws (random lane / position / speed), apart from every other use of the RNG.
constexpr uint64_t kDepartRngSalt = 0x4445504152545F31ull;
// Entries of one edge's queue offered per step. More than this many insertions on one edge in one step would
// need that many free places on its lanes at once; the rest wait a step (both backends alike).
constexpr uint32_t kMaxInsertPerEdge = 16;
// Entry flag: a vehicle re-entering, not departing: after a teleport (best free lane, at the lane start,
// speed 0) or handed back by a co-simulated SUMO (its lane, position and speed there).
constexpr uint32_t kInsertTeleported = 0x80000000u;

/// Per-vehicle depart attributes (read-only).
struct DepartView {
  const uint8_t* lane_kind;
  const int8_t* lane;  // DepartLane::Given: rank among the edge's lanes
  const uint8_t* pos_kind;
  const float* pos;
  const uint8_t* speed_kind;
  const float* speed;
};

/// The one list of the depart columns, all per trip (as visit_type_columns): f(column...) for each, of every
/// view given.
template <class F, class... Views>
void visit_depart_columns(F&& f, Views&... d) {
  f(d.lane_kind...);
  f(d.lane...);
  f(d.pos_kind...);
  f(d.pos...);
  f(d.speed_kind...);
  f(d.speed...);
}
static_assert(sizeof(DepartView) == 6 * sizeof(void*), "DepartView changed: update visit_depart_columns");

/// One step's queue heads, one slot per edge with waiting vehicles. Entries are tried in queue order, and
/// any of them may go in while one before it waits (as SUMO tries every pending vehicle): out_lane is -1
/// for an entry not inserted.
struct InsertBatch {
  uint32_t num_slots;
  const uint32_t* edge;       // [num_slots]
  const uint32_t* begin;      // [num_slots+1] into entry
  const uint32_t* entry;      // vehicle index, | kInsertTeleported
  const uint32_t* route_pos;  // [entries] route position it enters at (0 for a departure)
  // [entries] the speed a re-entering vehicle asks for (lowered to fit the traffic): 0 after a teleport, its
  // speed for one handed back by a co-simulated SUMO; departures ignore it.
  const float* enter_speed;
  // [entries] the lane a re-entering vehicle must take (a handed-back vehicle's lane in SUMO, chosen there
  // for its route); -1: the best free lane (after a teleport). Departures ignore it.
  const int32_t* enter_lane;
  // [entries] where a re-entering vehicle's front is to be (a handed-back vehicle continuing where SUMO had
  // it), tried before the lane start; -1: at the lane start (after a teleport). Departures ignore it.
  const float* enter_pos;
  uint32_t* inserted;  // out [num_slots]: entries of the slot inserted
  int32_t* out_lane;   // out [entries]: where an inserted vehicle was placed
  float* out_pos;
  float* out_speed;
};

struct InsertParams {
  float dt;  // s, as the config gives it
  uint64_t seed;
  uint32_t step;              // steps done: SUMO draws a random depart lane anew at each try
  float max_emergency_decel;  // hardest any leader may brake
  float min_decel;            // softest braking of any type (how a follower is assumed to react)
  int64_t* cnt_departed;      // per lane; null: not counted
  int64_t* lane_counts;       // the lane records (kernels/lane_counters.hpp); null: not counted
};

/// The cells a body `length` metres long with its front at `pos` covers on lane l: [rear, front].
struct BodyCells {
  int32_t rear, front;
};
LPSIM_HD BodyCells body_cells(const NetView& net, int32_t l, float pos, float length) {
  return BodyCells{static_cast<int32_t>(cell_of(net, l, pos - length)),
                   static_cast<int32_t>(cell_of(net, l, pos))};
}

/// What the insertion reads of one lane from the lane map: one scan, made when a departure is first tried
/// there in a step and made again after a vehicle was placed on it.
struct LaneScan {
  float occupied;     // cells covered by bodies (metres)
  uint32_t vehicles;  // runs of occupied cells
  float speed_sum;    // their speeds
  int32_t
      last_rear;  // first occupied cell from the lane start: the rear of the most upstream vehicle; -1: none
  int32_t last_front;  // the last cell of that vehicle
  float last_speed;
};

LPSIM_HD LaneScan scan_lane(const uint8_t* map, const NetView& net, int32_t l) {
  LaneScan r{0.0f, 0u, 0.0f, -1, -1, 0.0f};
  const uint8_t* cells = map + net.lane_cell_begin[l];
  const int32_t n = static_cast<int32_t>(lane_cells(net, l));
  int32_t c = first_occupied(map, net, l, 0, n - 1);
  while (c >= 0) {
    int32_t e = c;
    while (e + 1 < n && cells[e + 1] != 0) ++e;
    const float v = decode_cell_speed(cells[c]);
    if (r.last_rear < 0) {
      r.last_rear = c;
      r.last_front = e;
      r.last_speed = v;
    }
    r.occupied += static_cast<float>(e - c + 1);
    ++r.vehicles;
    r.speed_sum += v;
    c = e + 1 < n ? first_occupied(map, net, l, e + 1, n - 1) : -1;
  }
  return r;
}

/// A departure's speed as SUMO 1.15 chooses it on lane l (MSLane::getDepartSpeed), and whether the
/// insertion may lower it to fit the traffic (patch) or must wait instead.
struct DepartSpeedChoice {
  float speed;
  bool patch;
};
LPSIM_HD DepartSpeedChoice depart_speed(const StepContext& s, const DepartView& d, uint64_t seed, uint32_t v,
                                        uint32_t step, uint32_t l, const LaneScan& sc) {
  const uint32_t type = s.trips.type[v];
  const float lane_limit = lane_speed_for(s.net, l, s.types.vclass_mask[type]);
  const float v0 = desired_speed(lane_limit, s.trips.speed_factor[v], s.types.max_speed[type],
                                 s.types.desired_max_speed[type]);
  switch (d.speed_kind[v]) {
    case kDepartSpeedGiven:
      return {d.speed[v], false};
    case kDepartSpeedRandom:
      return {v0 * static_cast<float>(rng_uniform_double(seed, v, (uint64_t{step} << 8) | 2u)), true};
    case kDepartSpeedMax:
      return {v0, true};
    case kDepartSpeedDesired:
      return {v0, false};
    case kDepartSpeedLimit:
      return {s.trips.speed_factor[v] > 0.0f ? v0 / s.trips.speed_factor[v] : v0, false};
    case kDepartSpeedLast:  // the last vehicle's speed; an empty lane: as max
      return sc.last_rear < 0 ? DepartSpeedChoice{v0, true}
                              : DepartSpeedChoice{lp_fminf(v0, sc.last_speed), false};
    case kDepartSpeedAvg:  // the lane's mean speed; an empty lane: its limit
      return sc.vehicles == 0
                 ? DepartSpeedChoice{lp_fminf(v0, lane_limit), true}
                 : DepartSpeedChoice{lp_fminf(v0, sc.speed_sum / static_cast<float>(sc.vehicles)), false};
    default:  // 0
      return {0.0f, false};
  }
}

/// SUMO's isInsertionSuccess on one lane, for a vehicle whose front would be at `pos`: the body's cells
/// must be free; the leader ahead on the lane (at any distance) must leave at least minGap, and the speed
/// must not exceed the insertion speed of its car-following model behind it (lowered when patch, else the
/// insertion fails); the follower behind must have its secure gap to the new vehicle. The speed is then
/// capped by the ballistic safe speed LPSim's step keeps to every leader. Returns the speed, or -1 for no.
LPSIM_HD float insertion_check(const StepContext& s, const InsertParams& p, const uint8_t* map, uint32_t v,
                               int32_t l, float pos, float speed, bool patch) {
  const NetView& net = s.net;
  const uint32_t type = s.trips.type[v];
  const float length = s.types.length[type];
  const IdmParams ip = idm_of(s, type);
  const float v0 = desired_speed(lane_speed_for(net, l, s.types.vclass_mask[type]), s.trips.speed_factor[v],
                                 s.types.max_speed[type], s.types.desired_max_speed[type]);
  const BodyCells body = body_cells(net, l, pos, length);
  if (first_occupied(map, net, l, body.rear, body.front) >= 0) return -1.0f;
  const int32_t cells = static_cast<int32_t>(lane_cells(net, l));
  const int32_t ahead = body.front + 1 < cells ? first_occupied(map, net, l, body.front + 1, cells - 1) : -1;
  if (ahead >= 0) {
    // The map keeps the leader's rear to the metre and its speed to the quarter m/s below: SUMO's exact
    // values lie on average half a cell and an eighth of a m/s above.
    const float gap = static_cast<float>(ahead) + 0.5f - pos;
    const float vl = decode_cell_speed(map[net.lane_cell_begin[l] + static_cast<uint32_t>(ahead)]) + 0.125f;
    if (gap < ip.min_gap) return -1.0f;
    // The insertion's context carries no step parameters: SUMO's IDM sub-steps for the step length (the
    // IDM's insertion speed; Krauss has no sub-steps).
    const float ns = cf_insertion_speed(ip, speed, v0, gap, vl, p.dt, idm_default_substeps(p.dt));
    if (ns < speed) {
      if (!patch && speed > 0.0f) return -1.0f;
      speed = ns;
    }
  }
  if (body.rear > 0) {
    const int32_t reach = body.rear - 1 - metres_as_cells(lookahead_distance(ip, net.lane_speed[l], p.dt));
    const int32_t lag = last_occupied(map, net, l, reach > 0 ? reach : 0, body.rear - 1);
    if (lag >= 0) {
      // The follower's front: the middle of its front cell, as the leader's rear above.
      const float gap = (pos - length) - (static_cast<float>(lag) + 0.5f) - ip.min_gap;
      const float vf = decode_cell_speed(map[net.lane_cell_begin[l] + static_cast<uint32_t>(lag)]);
      if (gap < 0.0f || gap < cf_secure_gap(ip, vf, speed, p.dt)) return -1.0f;
    }
  }
  return speed;
}

/// Front position of a body `length` long placed at the lane start (SUMO's base position).
LPSIM_HD float base_pos(float lane_len, float length) { return lp_fminf(lane_len, length + 0.1f); }

/// Tries departure v on lane l with SUMO's departPos rules (MSLane::insertVehicle): base, given and random
/// at one position; last just behind the lane's most upstream vehicle, at the secure gap for the speed;
/// free at the lane start, else in the first gap from upstream wide enough for the secure gaps to both
/// neighbours (random_free: one random position first). Places it and returns true on success.
LPSIM_HD bool try_depart_on_lane(const StepContext& s, const DepartView& d, const InsertParams& p,
                                 uint8_t* map, uint32_t v, int32_t l, const LaneScan& sc, float* out_pos,
                                 float* out_speed) {
  const NetView& net = s.net;
  const uint32_t type = s.trips.type[v];
  const float length = s.types.length[type], min_gap = s.types.min_gap[type];
  const float lane_len = net.lane_length[l];
  const uint64_t seed = p.seed ^ kDepartRngSalt;
  const DepartSpeedChoice ds = depart_speed(s, d, seed, v, p.step, static_cast<uint32_t>(l), sc);
  const uint8_t pk = d.pos_kind[v];
  float pos = base_pos(lane_len, length);
  float speed = -1.0f;
  if (pk == kDepartPosGiven) {  // negative values were made absolute by the builder
    pos = lp_fmaxf(length, lp_fminf(lane_len, d.pos[v]));
    speed = insertion_check(s, p, map, v, l, pos, ds.speed, ds.patch);
  } else if (pk == kDepartPosRandom || pk == kDepartPosRandomFree) {
    pos = lp_fminf(lane_len,
                   length + static_cast<float>(rng_uniform_double(seed, v, (uint64_t{p.step} << 8) | 1u)) *
                                lp_fmaxf(0.0f, lane_len - length));
    speed = insertion_check(s, p, map, v, l, pos, ds.speed, ds.patch);
  } else if (pk == kDepartPosLast) {
    if (sc.last_rear < 0) {
      pos = lp_fmaxf(length, lane_len - 0.1f);
    } else {
      // SUMO's lastInsertion: its secure gap plus minGap behind the lane's last vehicle. LPSim's step moves
      // a vehicle at most up to its leader's rear as the step began, so a vehicle that is to keep the
      // depart speed needs that step's distance too (a faster leader makes the secure gap 0).
      const IdmParams ip = idm_of(s, type);
      const float need =
          lp_fmaxf(cf_secure_gap(ip, ds.speed, sc.last_speed, p.dt) + min_gap, ds.speed * p.dt) + 0.1f;
      if (static_cast<float>(sc.last_rear) < need) return false;
      pos = lp_fmaxf(base_pos(lane_len, length),
                     lp_fminf(lane_len - 0.1f, static_cast<float>(sc.last_rear) - need));
    }
    speed = insertion_check(s, p, map, v, l, pos, ds.speed, ds.patch);
  } else if (pk != kDepartPosFree) {  // base
    speed = insertion_check(s, p, map, v, l, pos, ds.speed, ds.patch);
  }
  if (speed < 0.0f && (pk == kDepartPosFree || pk == kDepartPosRandomFree)) {
    // SUMO's freeInsertion: at the lane start with an adaptable speed when the lane is empty or its
    // front-most vehicle (as SUMO 1.15 looks at it) leaves the secure gap at its own speed; else gap by gap
    // from upstream, where the follower's secure gap is taken to the new vehicle standing (its speed before
    // it is inserted), as SUMO does.
    const IdmParams ip = idm_of(s, type);
    const uint8_t* cells = map + net.lane_cell_begin[l];
    const int32_t n = static_cast<int32_t>(lane_cells(net, l));
    pos = base_pos(lane_len, length);
    bool at_start = sc.last_rear < 0;
    if (!at_start) {
      int32_t rear = last_occupied(map, net, l, 0, n - 1);
      const float vl = decode_cell_speed(cells[rear]);
      while (rear > 0 && cells[rear - 1] != 0) --rear;
      at_start = static_cast<float>(rear) >= cf_secure_gap(ip, vl, vl, p.dt) + min_gap;
    }
    if (at_start) speed = insertion_check(s, p, map, v, l, pos, ds.speed, true);
    int32_t c = sc.last_rear;
    while (speed < 0.0f && c >= 0) {
      int32_t e = c;
      while (e + 1 < n && cells[e + 1] != 0) ++e;
      const float vf = decode_cell_speed(cells[c]);
      const int32_t next = e + 1 < n ? first_occupied(map, net, l, e + 1, n - 1) : -1;
      float sp = ds.speed, front_max = lane_len;
      if (next >= 0) {
        const float vl = decode_cell_speed(cells[next]);
        sp = lp_fminf(vl, ds.speed);
        front_max = static_cast<float>(next) - (cf_secure_gap(ip, sp, vl, p.dt) + min_gap);
      }
      // The follower's front lies within its front cell: its middle, as for leaders.
      const float back_min =
          static_cast<float>(e) + 0.5f + min_gap + cf_secure_gap(ip, vf, 0.0f, p.dt) + length;
      if (front_max > 0.0f && back_min + 0.1f < front_max && back_min + 0.1f <= lane_len) {
        pos = back_min + 0.1f;
        speed = insertion_check(s, p, map, v, l, pos, sp, true);
      }
      c = next;
    }
  }
  if (speed < 0.0f) return false;
  apply_footprint(map, net, Footprint{l, -1, -1, pos}, length, encode_cell_speed(speed));
  *out_pos = pos;
  *out_speed = speed;
  return true;
}

/// SUMO's getFreeLane among the lanes of `mask` (bits by rank): the least occupied (lengths with minGap),
/// unless some lane leaves more room than the others between `bound` and the front of its most upstream
/// vehicle (an empty lane: its end), which is then taken. -1 when the mask is empty.
LPSIM_HD int32_t free_lane(const NetView& net, uint32_t first, uint32_t nlanes, uint64_t mask,
                           const LaneScan* scans, float min_gap, float bound) {
  int32_t res = -1, by_gap = -1;
  float least = 3.0e38f, largest = 0.0f;
  for (uint32_t k = 0; k < nlanes; ++k) {
    if (!((mask >> k) & 1u)) continue;
    const LaneScan& sc = scans[k];
    const float occ = sc.occupied + static_cast<float>(sc.vehicles) * min_gap;
    if (occ < least) {
      least = occ;
      res = static_cast<int32_t>(first + k);
    }
    const float last = sc.last_rear < 0 ? net.lane_length[first + k] : static_cast<float>(sc.last_front + 1);
    if (last - bound > largest) {
      largest = last - bound;
      by_gap = static_cast<int32_t>(first + k);
    }
  }
  return by_gap >= 0 ? by_gap : res;
}

/// Lanes an edge's insertion looks at (SUMO's 64-bit masks); lanes beyond are not used for departures.
constexpr uint32_t kMaxInsertLanes = 64;

/// Tries to put a teleported (or handed-back) vehicle back on the road on route edge `rp`: on `lane_wanted`
/// if >= 0, else best lanes first, then the others its class may use; with its front at `pos_wanted` if >= 0,
/// else (or where that has no room) at the lane start; at up to `speed_wanted` (lowered to fit). Returns
/// false, changing nothing, when none has room.
LPSIM_HD bool try_reenter(const StepContext& s, const InsertParams& p, uint8_t* map, uint32_t v, uint32_t rp,
                          float speed_wanted, int32_t lane_wanted, float pos_wanted, int32_t* out_lane,
                          float* out_pos, float* out_speed) {
  const NetView& net = s.net;
  const uint32_t e = trip_route_edge(s, v, rp);
  const uint32_t first = net.edge_first_lane[e], nlanes = net.edge_num_lanes[e];
  const uint32_t type = s.trips.type[v];
  const float length = s.types.length[type];
  const uint32_t vclass = s.types.vclass_mask[type];
  const uint32_t best =
      best_lanes(net, s.trips.route_edges + s.trips.route_begin[v], s.trips.route_length[v], rp, vclass)
          .mask[0];
  // Where it is wanted first, then (no room there) at the lane start, as after a teleport.
  for (int at_start = pos_wanted < 0.0f ? 1 : 0; at_start < 2; ++at_start)
    for (int pass = 0; pass < 2; ++pass) {
      for (uint32_t l = first; l < first + nlanes; ++l) {
        if (((lane_bit(net, l) & best) != 0) != (pass == 0) || !lane_allows(net, l, vclass)) continue;
        if (lane_wanted >= 0 && static_cast<int32_t>(l) != lane_wanted) continue;
        const int32_t li = static_cast<int32_t>(l);
        const float start = base_pos(net.lane_length[l], length);
        const float pos = at_start ? start : lp_fmaxf(start, lp_fminf(pos_wanted, net.lane_length[l]));
        const float speed = insertion_check(s, p, map, v, li, pos, speed_wanted, true);
        if (speed < 0.0f) continue;
        apply_footprint(map, net, Footprint{li, -1, -1, pos}, length, encode_cell_speed(speed));
        if (p.lane_counts != nullptr) count_on_lane(p.lane_counts, li, kCountEntered, 1);
        *out_lane = li;
        *out_pos = pos;
        *out_speed = speed;
        return true;
      }
    }
  return false;
}

/// One step's insertions on one edge, as SUMO's MSEdge::insertVehicle does them: every offered vehicle in
/// queue order picks one lane by its departLane (given, first, random anew at each try, free or best: the
/// least occupied of the lanes it may take) and is tried there only; a lane where a vehicle failed in this
/// step takes no other departure in this step, and a vehicle whose lane has failed waits while later ones
/// may still go in on other lanes. Teleported vehicles re-enter apart from that (SUMO's vehicle transfer).
LPSIM_HD void insert_queue_head(const StepContext& s, const DepartView& d, const InsertParams& p,
                                uint8_t* map, const InsertBatch& b, uint32_t slot) {
  const NetView& net = s.net;
  const uint32_t e = b.edge[slot];
  const uint32_t first = net.edge_first_lane[e];
  const uint32_t nlanes = net.edge_num_lanes[e] < kMaxInsertLanes ? net.edge_num_lanes[e] : kMaxInsertLanes;
  const uint64_t all = nlanes >= 64 ? ~uint64_t{0} : (uint64_t{1} << nlanes) - 1u;
  uint64_t failed = 0, scanned = 0;
  LaneScan scans[kMaxInsertLanes];
  const uint64_t seed = p.seed ^ kDepartRngSalt;
  uint32_t n = 0;
  for (uint32_t i = b.begin[slot]; i < b.begin[slot + 1]; ++i) {
    b.out_lane[i] = -1;
    const uint32_t entry = b.entry[i];
    const uint32_t v = entry & ~kInsertTeleported;
    if (entry & kInsertTeleported) {
      if (try_reenter(s, p, map, v, b.route_pos[i], b.enter_speed[i], b.enter_lane[i], b.enter_pos[i],
                      &b.out_lane[i], &b.out_pos[i], &b.out_speed[i])) {
        ++n;
        scanned = 0;
      }
      continue;
    }
    if ((failed & all) == all) continue;
    const uint32_t type = s.trips.type[v];
    const uint8_t kind = d.lane_kind[v];
    // Only lanes the vehicle's class may use, as SUMO inserts (all of them on most edges).
    const uint32_t vclass = s.types.vclass_mask[type];
    uint64_t allowed = 0;
    uint32_t num_allowed = 0;
    for (uint32_t k = 0; k < nlanes; ++k)
      if (lane_allows(net, first + k, vclass)) allowed |= uint64_t{1} << k, ++num_allowed;
    if (allowed == 0) continue;  // routes are checked per class: not expected
    uint64_t mask = 0;
    int32_t lane = -1;
    if (kind == kDepartLaneGiven) {
      if (d.lane[v] >= 0 && static_cast<uint32_t>(d.lane[v]) < nlanes && ((allowed >> d.lane[v]) & 1u))
        lane = static_cast<int32_t>(first + static_cast<uint32_t>(d.lane[v]));
    } else if (kind == kDepartLaneRandom) {
      // The draw picks the k-th allowed lane (the k-th lane where every lane is allowed).
      uint32_t pick = static_cast<uint32_t>(rng_bits(seed, v, uint64_t{p.step} << 8) % num_allowed);
      for (uint32_t k = 0; k < nlanes && lane < 0; ++k)
        if (((allowed >> k) & 1u) && pick-- == 0) lane = static_cast<int32_t>(first + k);
    } else if (kind == kDepartLaneFree || kind == kDepartLaneAllowed) {
      mask = allowed;
    } else if (kind == kDepartLaneBest) {
      const uint32_t best =
          best_lanes(net, s.trips.route_edges + s.trips.route_begin[v], s.trips.route_length[v], 0, vclass)
              .mask[0];
      for (uint32_t k = 0; k < nlanes && k < 32; ++k)
        if (lane_bit(net, first + k) & best) mask |= uint64_t{1} << k;
      mask &= allowed;
      if (mask == 0) mask = allowed;
    } else {  // first: the first lane the class may use
      for (uint32_t k = 0; k < nlanes && lane < 0; ++k)
        if ((allowed >> k) & 1u) lane = static_cast<int32_t>(first + k);
    }
    if (mask != 0) {
      for (uint32_t k = 0; k < nlanes; ++k)
        if (((mask >> k) & 1u) && !((scanned >> k) & 1u)) {
          scans[k] = scan_lane(map, net, static_cast<int32_t>(first + k));
          scanned |= uint64_t{1} << k;
        }
      const uint8_t pk = d.pos_kind[v];
      const float bound = pk == kDepartPosLast ? 0.0f : pk == kDepartPosGiven ? d.pos[v] : 3.0e38f;
      lane = free_lane(net, first, nlanes, mask, scans, s.types.min_gap[type], bound);
    }
    if (lane < 0) continue;
    const uint32_t k = static_cast<uint32_t>(lane) - first;
    if ((failed >> k) & 1u) continue;
    if (!((scanned >> k) & 1u)) {
      scans[k] = scan_lane(map, net, lane);
      scanned |= uint64_t{1} << k;
    }
    if (try_depart_on_lane(s, d, p, map, v, lane, scans[k], &b.out_pos[i], &b.out_speed[i])) {
      b.out_lane[i] = lane;
      if (p.cnt_departed != nullptr) atomic_add_i64(&p.cnt_departed[lane], 1);
      scanned &= ~(uint64_t{1} << k);
      ++n;
    } else {
      failed |= uint64_t{1} << k;
    }
  }
  b.inserted[slot] = n;
}

}  // namespace lpsim

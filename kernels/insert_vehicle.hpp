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
                  kDepartPosRandomFree = 4;
constexpr uint8_t kDepartSpeedGiven = 0, kDepartSpeedZero = 1, kDepartSpeedRandom = 2, kDepartSpeedMax = 3,
                  kDepartSpeedDesired = 4, kDepartSpeedLimit = 5, kDepartSpeedLast = 6, kDepartSpeedAvg = 7;

// Salt for departure draws (random lane / position / speed), apart from every other use of the RNG.
constexpr uint64_t kDepartRngSalt = 0x4445504152545F31ull;
// Entries of one edge's queue offered per step. More than this many insertions on one edge in one step would
// need that many free places on its lanes at once; the rest wait a step (both backends alike).
constexpr uint32_t kMaxInsertPerEdge = 16;
// Entry flag: a teleported vehicle re-entering (best free lane, at the lane start, speed 0, not a departure).
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

/// One step's queue heads, one slot per edge with waiting vehicles.
struct InsertBatch {
  uint32_t num_slots;
  const uint32_t* edge;       // [num_slots]
  const uint32_t* begin;      // [num_slots+1] into entry
  const uint32_t* entry;      // vehicle index, | kInsertTeleported
  const uint32_t* route_pos;  // [entries] route position it enters at (0 for a departure)
  uint32_t* inserted;         // out [num_slots]: entries inserted from the slot's head
  int32_t* out_lane;          // out [entries]: where an inserted vehicle was placed
  float* out_pos;
  float* out_speed;
};

struct InsertParams {
  float dt;  // s, as the config gives it
  uint64_t seed;
  float max_emergency_decel;  // hardest any leader may brake
  float min_decel;            // softest braking of any type (how a follower is assumed to react)
  int64_t* cnt_departed;      // per lane; null: not counted
  int64_t* cnt_entered;
};

/// Whether a queued vehicle is placed at the start of its lane (teleported, or departPos base or free): its
/// body then covers the lane's first cell, so that no second such vehicle fits on that lane in the same
/// step. An edge takes at most one of them per lane and step, and the host offers none beyond that.
LPSIM_HD bool inserts_at_lane_start(uint8_t pos_kind, bool teleported) {
  return teleported ||
         (pos_kind != kDepartPosGiven && pos_kind != kDepartPosRandom && pos_kind != kDepartPosRandomFree);
}

/// Where on lane l vehicle v's front would be placed (its departPos; teleported: at the lane start).
LPSIM_HD float insert_pos(const NetView& net, const DepartView& d, uint64_t seed, uint32_t v, bool teleported,
                          uint32_t l, float length) {
  const float lane_len = net.lane_length[l];
  const uint8_t pk = d.pos_kind[v];
  if (inserts_at_lane_start(pk, teleported)) return lp_fminf(lane_len, length + 0.1f);
  if (pk == kDepartPosGiven) {  // negative values were made absolute by the builder
    const float given = d.pos[v];
    return given < 0.0f ? 0.0f : (lane_len < given ? lane_len : given);
  }
  // random or random_free
  return lp_fminf(lane_len, length + static_cast<float>(rng_uniform_double(seed, v, 1)) *
                                         lp_fmaxf(0.0f, lane_len - length));
}

/// The cells a body `length` metres long with its front at `pos` covers on lane l: [rear, front].
struct BodyCells {
  int32_t rear, front;
};
LPSIM_HD BodyCells body_cells(const NetView& net, int32_t l, float pos, float length) {
  return BodyCells{static_cast<int32_t>(cell_of(net, l, pos - length)),
                   static_cast<int32_t>(cell_of(net, l, pos))};
}

/// Tries to put vehicle v (entry flags included) on the road at the start of route edge `rp`, writing its
/// footprint into `map` and where it was placed into the out_ values (the host then gives it a slot).
/// Returns false, changing nothing, when no candidate lane has room.
LPSIM_HD bool try_insert_vehicle(const StepContext& s, const DepartView& d, const InsertParams& p,
                                 uint8_t* map, uint32_t entry, uint32_t rp, int32_t* out_lane, float* out_pos,
                                 float* out_speed) {
  const uint32_t v = entry & ~kInsertTeleported;
  const bool teleported = (entry & kInsertTeleported) != 0;
  const NetView& net = s.net;
  const uint32_t e = trip_route_edge(s, v, rp);
  const uint32_t first = net.edge_first_lane[e], nlanes = net.edge_num_lanes[e];
  const uint32_t type = s.trips.type[v];
  const float length = s.types.length[type], min_gap = s.types.min_gap[type];
  const uint64_t seed = p.seed ^ kDepartRngSalt;

  // Candidate lanes in the order they are tried: only lanes the vehicle's class may use, as SUMO inserts.
  const uint32_t vclass = s.types.vclass[type];
  uint32_t candidates[64];
  uint32_t nc = 0;
  const uint8_t kind = teleported ? kDepartLaneBest : d.lane_kind[v];
  if (kind == kDepartLaneGiven) {  // the demand builder maps SUMO's index to the rank among the edge's lanes
    if (d.lane[v] >= 0 && static_cast<uint32_t>(d.lane[v]) < nlanes &&
        lane_allows(net, first + static_cast<uint32_t>(d.lane[v]), vclass))
      candidates[nc++] = first + static_cast<uint32_t>(d.lane[v]);
  } else if (kind == kDepartLaneRandom) {
    // The draw picks among the allowed lanes (all of them on most edges: then the k-th lane as before).
    uint32_t allowed = 0;
    for (uint32_t l = first; l < first + nlanes; ++l) allowed += lane_allows(net, l, vclass) ? 1u : 0u;
    if (allowed > 0) {
      uint32_t k = static_cast<uint32_t>(rng_bits(seed, v, 0) % allowed);
      for (uint32_t l = first; l < first + nlanes; ++l)
        if (lane_allows(net, l, vclass) && k-- == 0) {
          candidates[nc++] = l;
          break;
        }
    }
  } else if (kind == kDepartLaneBest || kind == kDepartLaneFree) {
    // Every candidate is a lane of the edge, and one whose body cells are taken is skipped: where no lane has
    // room (most retries on a congested day) the answer is no without the route walk of the best lanes.
    bool any_room = false;
    for (uint32_t l = first; l < first + nlanes && !any_room; ++l) {
      if (!lane_allows(net, l, vclass)) continue;
      const int32_t li = static_cast<int32_t>(l);
      const BodyCells body = body_cells(net, li, insert_pos(net, d, seed, v, teleported, l, length), length);
      any_room = first_occupied(map, net, li, body.rear, body.front) < 0;
    }
    if (!any_room) return false;
    // Best, as SUMO: only lanes that lead on along the route (wait for one otherwise). Free and teleported
    // vehicles: those first, then the others. (Best lanes are lanes the class may use.)
    const uint32_t best =
        best_lanes(net, s.trips.route_edges + s.trips.route_begin[v], s.trips.route_length[v], rp, vclass)
            .mask[0];
    for (uint32_t l = first; l < first + nlanes && nc < 64; ++l)
      if (lane_bit(net, l) & best) candidates[nc++] = l;
    if (kind == kDepartLaneFree || teleported)
      for (uint32_t l = first; l < first + nlanes && nc < 64; ++l)
        if (!(lane_bit(net, l) & best) && lane_allows(net, l, vclass)) candidates[nc++] = l;
  }
  if (nc == 0)  // first (and the fallback of the others): the first lane the class may use
    for (uint32_t l = first; l < first + nlanes && nc == 0; ++l)
      if (lane_allows(net, l, vclass)) candidates[nc++] = l;
  if (nc == 0) return false;  // no lane of this edge admits the class (routes are checked: not expected)

  const IdmParams ip = idm_of(s, type);
  for (uint32_t k = 0; k < nc; ++k) {
    const uint32_t l = candidates[k];
    const int32_t li = static_cast<int32_t>(l);
    const float pos = insert_pos(net, d, seed, v, teleported, l, length);
    const float v0 = desired_speed(net.lane_speed[l], s.trips.speed_factor[v], s.types.max_speed[type]);
    float speed = 0;
    bool speed_given = false;
    if (!teleported) {
      const uint8_t sk = d.speed_kind[v];
      if (sk == kDepartSpeedGiven) {
        speed = d.speed[v];
        speed_given = true;
      } else if (sk == kDepartSpeedMax || sk == kDepartSpeedDesired || sk == kDepartSpeedLimit ||
                 sk == kDepartSpeedAvg || sk == kDepartSpeedLast) {
        speed = v0;
      } else if (sk == kDepartSpeedRandom) {
        speed = v0 * static_cast<float>(rng_uniform_double(seed, v, 2));
      }
    }
    // Body cells must be free.
    const BodyCells body = body_cells(net, li, pos, length);
    if (first_occupied(map, net, li, body.rear, body.front) >= 0) continue;
    // Leader ahead: the inserted vehicle must be able to follow it safely.
    const int32_t cells = static_cast<int32_t>(lane_cells(net, li));
    const int32_t look = body.front + 1 + metres_as_cells(lookahead_distance(ip, speed, p.dt) + min_gap);
    const int32_t ahead = body.front + 1 < cells ? first_occupied(map, net, li, body.front + 1,
                                                                  look < cells - 1 ? look : cells - 1)
                                                 : -1;
    if (ahead >= 0) {
      const float gap = static_cast<float>(ahead) - pos;
      const float vl = decode_cell_speed(map[net.lane_cell_begin[l] + static_cast<uint32_t>(ahead)]);
      if (gap < min_gap) continue;
      const float safe = safe_speed(gap, vl, p.max_emergency_decel, ip.decel, p.dt);
      if (speed > safe) {
        if (speed_given) continue;
        speed = safe;
      }
    }
    // Follower behind: it must be able to stay safe behind the new vehicle.
    if (body.rear > 0) {
      const int32_t reach = body.rear - 1 - metres_as_cells(lookahead_distance(ip, net.lane_speed[l], p.dt));
      const int32_t lag = last_occupied(map, net, li, reach > 0 ? reach : 0, body.rear - 1);
      if (lag >= 0) {
        const float gap = (pos - length) - static_cast<float>(lag + 1);
        const float vl = decode_cell_speed(map[net.lane_cell_begin[l] + static_cast<uint32_t>(lag)]) + 0.25f;
        if (gap <= 0 || lp_fmaxf(0.0f, vl - p.min_decel * p.dt) >
                            safe_speed(gap, speed, p.max_emergency_decel, p.min_decel, p.dt))
          continue;
      }
    }
    apply_footprint(map, net, Footprint{li, -1, -1, pos}, length, encode_cell_speed(speed));
    int64_t* counter = teleported ? p.cnt_entered : p.cnt_departed;
    if (counter != nullptr) atomic_add_i64(&counter[l], 1);
    *out_lane = li;
    *out_pos = pos;
    *out_speed = speed;
    return true;
  }
  return false;
}

/// Inserts the head of one slot's queue until a vehicle does not fit.
LPSIM_HD void insert_queue_head(const StepContext& s, const DepartView& d, const InsertParams& p,
                                uint8_t* map, const InsertBatch& b, uint32_t slot) {
  uint32_t n = 0;
  for (uint32_t i = b.begin[slot]; i < b.begin[slot + 1]; ++i, ++n)
    if (!try_insert_vehicle(s, d, p, map, b.entry[i], b.route_pos[i], &b.out_lane[i], &b.out_pos[i],
                            &b.out_speed[i]))
      break;
  b.inserted[slot] = n;
}

}  // namespace lpsim

#pragma once
// A co-simulation's boundary (outside_link.cpp): the lanes another simulator (SUMO) drives, as another part
// would. Its vehicles there are written into the lane map like another part's footprints, so that this
// simulation's vehicles queue behind them and enter only where there is room; a vehicle whose front reaches
// such a lane leaves at the end of that step, like a vehicle driving into another part, and is handed to the
// other side; the other side hands vehicles back to queue at an edge this simulation drives.
#include <cstdint>
#include <vector>

#include "engine/boundary_link.hpp"

namespace lpsim {

/// Where a vehicle's front at `pos` on a lane `lane_length` long gets to in `seconds` at `speed`, as it
/// drives on while it waits to be handed over: short of the lane's end only (beyond it lies a junction it has
/// not been let through), else where it is (at most the lane's end). Both directions of a co-simulation's
/// hand-over place a vehicle so.
template <class T>
T position_driven_on(T pos, T speed, T seconds, T lane_length) {
  const T at = std::max(T{0}, pos);
  const T on = at + std::max(T{0}, speed) * seconds;
  return on < lane_length ? on : std::min(at, lane_length);
}

class OutsideLink final : public BoundaryLink {
 public:
  /// `outside_lanes`: 1 per lane of the network that the other simulator drives (outlives the link).
  /// `step_length`: s, the step the hand-backs drive on in.
  OutsideLink(const LinkScope& run, const std::vector<uint8_t>& outside_lanes, double step_length);

  void before_writing(int map) override;
  void after_end_of_step(int map) override;
  bool queues_at(uint32_t edge) const override { return !outside_edge(edge); }
  bool takes_departure(uint32_t v, uint32_t edge) override;
  bool takes_reentry(const VehicleEnd& end, uint32_t rp, uint32_t edge) override;

  /// The lanes the other simulator drives, 1 per lane of the network.
  const std::vector<uint8_t>& outside_lanes() const { return outside_; }
  /// Edge `edge` is driven by the other simulator.
  bool outside_edge(uint32_t edge) const;

  /// A vehicle that left for an outside lane: where and how fast it was at the end of the step; or (lane -1,
  /// pos and speed 0) one that enters the other simulator off the road: due to depart on an outside edge
  /// (route_pos 0), or teleported to one (route_pos: that edge's).
  struct HandOut {
    uint32_t vehicle = 0;
    int32_t lane = -1;  // the outside lane its front is on
    float pos = 0, speed = 0;
    uint32_t route_pos = 0;  // of the lane's edge in its route
  };
  /// The vehicles that left for outside lanes in the last step: those off the road (departures in the order
  /// they were due, teleports in vehicle order), then those that drove there, in vehicle order. Their ledger
  /// status is kMigrated from then on (not running, not arrived: the other simulator has them).
  const std::vector<HandOut>& hand_outs() const { return hand_outs_; }
  /// Vehicles handed out so far.
  uint64_t handed_out() const { return handed_out_; }

  /// The other simulator's vehicles on outside lanes as they are at the end of the next step (the caller
  /// has stepped it already): the lane map the next step writes holds them before its insertions, and the
  /// step after reads them (the room after a junction, leaders). Kept for the following steps until the
  /// next call replaces them.
  struct OutsideVehicle {
    int32_t lane = 0;
    float pos = 0, length = 0, speed = 0;  // front position, m
  };
  void mirror_outside_vehicles(const std::vector<OutsideVehicle>& vehicles);

  /// A handed-out vehicle v comes back at route position `route_pos` (an edge this simulation drives), its
  /// front at `pos` on `lane` (one of the edge's; -1: its best free lane) at `speed` at the run's time: it
  /// queues there to re-enter in the next step where it would have driven to in it (at the lane start when
  /// there is no room there, as a teleported vehicle does), at up to `speed`, carrying the counters it left
  /// with (the other simulator reports its piece of the trip itself, up to `pos`). std::invalid_argument,
  /// naming it, when it was not handed out, the edge is driven outside or the lane is not the edge's.
  void take_back(uint32_t v, uint32_t route_pos, int32_t lane, float pos, float speed);
  /// Whether edge `edge` takes one more vehicle back now: fewer are queued to enter there than it has lanes
  /// (the insertion then finds room at a lane start, or the queue holds the next one in the other simulator).
  bool has_entry_room(uint32_t edge) const;

 private:
  const std::vector<uint8_t>& outside_;
  double step_length_;
  std::vector<uint8_t> all_lanes_;          // the lane map's writes reach every lane
  std::vector<HandOut> departing_outside_;  // due to depart on an outside edge, for the next hand_outs()
  std::vector<FootprintWrite> mirror_;      // mirror_outside_vehicles(): written into each map steps write
  std::vector<HandOut> hand_outs_;
  uint64_t handed_out_ = 0;
};

}  // namespace lpsim

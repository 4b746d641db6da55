#pragma once
// One part's link to the other parts of a partitioned run (part_link.cpp): whom it exchanges with, the
// rounds at the step's points where their states meet (docs/ARCHITECTURE.md, "Partitions"), what a step
// hands on between its rounds, and, in part 0, the run's totals gathered from every part.
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "engine/boundary_link.hpp"
#include "partition/part_plan.hpp"
#include "transport/transport.hpp"

namespace lpsim {

/// A teleported vehicle that re-enters at an edge's queue, handed to the edge's owner.
struct TeleportHandOver {
  VehicleEnd end;
  uint32_t route_pos = 0;  // where it re-enters
  uint32_t edge = 0;
  DepartRecord departure;
};

/// A vehicle inserted in a step: its place in the order one part inserts (edge << 32 | entry of the batch,
/// the batch listing edges ascending) and its insertion delay.
struct DepartDelay {
  uint64_t order;
  double delay;
};

/// What a part's link carries from one step to the next besides the footprints it has to erase: a piece of
/// its state (the link's visit_state writes the erasures, then this).
struct PartLinkCarry {
  // Footprints of the last insertions on lanes others hold, by part, until they are sent.
  std::map<int, std::vector<FootprintWrite>> inserted;
  PartStats stats;  // this part's, cumulative
  // Part 0: each part's stats as of its last report, and the run's totals.
  std::vector<PartStats> part_stats;
  RunCounts counts;
  std::vector<TeleportEvent> teleport_events;
  std::vector<TripRecord> finished;
  double depart_delay_sum = 0, travel_time_sum = 0;
  bool all_idle = false;  // no part has a vehicle on the road or waiting to be inserted

  template <class A>
  void visit_state(A& a) {
    auto n = static_cast<uint32_t>(inserted.size());
    a(n);
    if constexpr (A::kReads) {
      inserted.clear();
      for (uint32_t i = 0; i < n; ++i) {
        int32_t part = 0;
        a(part);
        a(inserted[part]);
      }
    } else {
      for (auto& [part, writes] : inserted) {
        auto p = static_cast<int32_t>(part);
        a(p);
        a(writes);
      }
    }
    a(stats);
    a(part_stats);
    a(counts);
    a(teleport_events);
    a(finished);
    a(depart_delay_sum);
    a(travel_time_sum);
    a(all_idle);
  }
};

/// The parts that hold a lane `plan`'s part holds, ascending (those it exchanges with).
std::vector<int> part_neighbours(const PartPlan& plan);

class PartLink final : public BoundaryLink {
 public:
  /// `pending_signal`: the signal this part's process received and has not acted on (0: none), reported to
  /// part 0 with every step.
  PartLink(const LinkScope& run, const PartPlan& plan, Transport& transport,
           std::function<int()> pending_signal);

  void begin_step() override;
  void after_signals() override;
  void after_approach(uint32_t step, int read_map) override;
  void after_plan(uint32_t step) override;
  void after_end_of_step(int map) override;
  void after_insertion(int map) override;
  int64_t settle_crossings(std::vector<uint32_t>& added) override;
  void count_step(double seconds) override;
  void report() override;

  bool owns_edge(uint32_t edge) const override { return plan_.edge_owner[edge] == plan_.part; }
  bool takes_departure(uint32_t v, uint32_t edge) override;
  bool takes_reentry(const VehicleEnd& end, uint32_t rp, uint32_t edge) override;
  bool records_departures() const override { return true; }
  void departed(uint64_t order, double delay) override { departures_.push_back(DepartDelay{order, delay}); }

  int parts() const override { return plan_.parts; }
  bool leads() const override { return plan_.part == 0; }
  bool idle() const override { return carry_.all_idle; }
  const RunCounts& counts() const override { return carry_.counts; }
  std::vector<TripRecord> take_finished() override;
  const std::vector<TeleportEvent>& teleport_events() const override { return carry_.teleport_events; }
  double depart_delay_sum() const override { return carry_.depart_delay_sum; }
  double travel_time_sum() const override { return carry_.travel_time_sum; }
  std::vector<PartStats> part_stats() const override { return carry_.part_stats; }
  int signal() const override { return signal_; }
  const std::vector<SampleEntry>& running_vehicles(uint64_t version) override;

  void request(PartRequest what) override;
  PartRequest next_request() override;
  std::vector<Bytes> gather(const Bytes& mine, const char* what) override;
  std::vector<Bytes> allgather(const Bytes& mine, const char* what) override;
  Bytes broadcast(const Bytes& root, const char* what) override;
  Bytes scatter(const std::vector<Bytes>& each, const char* what) override;

  void erase_removed(int map, const FootprintWrite& fp) override;

  void save_state(StateOut& a, int map) override { visit_state(a, map); }
  void load_state(StateIn& a, int map) override { visit_state(a, map); }

 private:
  /// One round with the transport, timed and counted in carry_.stats (exchange: a round of the step; else a
  /// request or a gather for the outputs).
  std::vector<Bytes> round(const std::vector<int>& to, const std::vector<Bytes>& send,
                           const std::vector<int>& from, const char* what, bool exchange);
  std::vector<int> others() const;
  template <class A>
  void visit_state(A& a, int map);

  const PartPlan& plan_;
  Transport& transport_;
  std::function<int()> pending_signal_;
  std::vector<int> neighbours_;        // the parts that hold a lane this one holds, ascending
  std::vector<int32_t> neighbour_at_;  // per part: its place in neighbours_ (-1: none)
  // The actuated signals this part runs that others read, and the parts that read them; the parts whose
  // signals this one reads.
  std::vector<uint32_t> signals_sent_;
  std::vector<int> signal_readers_, signal_owners_;
  bool signal_round_ = false;  // some part runs an actuated signal another reads (the same in every part)
  // Some actuated signal reads a loop on a lane its part does not own: insertions go in a round of their own
  // before the next step's signals (the same in every part).
  bool insertion_round_ = false;
  std::vector<uint32_t> owned_shared_;  // its lanes that other parts hold too, ascending
  // Per lane: 1 where this part alone holds it (it owns it then), so a vehicle all on such lanes concerns no
  // other part.
  std::vector<uint8_t> alone_;
  PartLinkCarry carry_;

  // Handed on within a step.
  std::vector<TeleportHandOver> teleports_;  // this step's teleports, whoever owns their re-entry edge
  std::vector<uint32_t> adopted_;            // slots taken by vehicles that drove in from other parts
  std::vector<DepartDelay> departures_;      // the step's insertions
  // The step's footprints for each neighbour (by place in neighbours_), kept between steps with their room.
  std::vector<std::vector<FootprintWrite>> footprints_out_;

  int signal_ = 0;  // the first signal a part reported
};

}  // namespace lpsim

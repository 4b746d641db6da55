#pragma once
// The co-simulation: a Run of the whole scenario in which the corridor's lanes are driven by SUMO (a
// SumoLink), vehicles handed across the boundary both ways. Each coupling period LPSim steps first; the
// vehicles whose front reached a corridor lane (or whose trip starts on one) are added to SUMO where and as
// fast as they were, at SUMO's first step from then on; SUMO then steps the same period, up to the state
// LPSim is at; a SUMO vehicle that reached an edge outside the corridor is taken back by LPSim (queued to
// re-enter where it drives to in LPSim's next step, on its lane at its speed) when LPSim has room there, else
// held in SUMO; and SUMO's vehicles on corridor lanes are mirrored into LPSim's lane map, so that LPSim's
// traffic queues behind them. A vehicle leaves one side only when the other holds it (SUMO's pending
// vehicles stand in LPSim's lane map at their entry); every vehicle is at each moment in exactly one place.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "app/run.hpp"
#include "engine/outside_link.hpp"
#include "sumo_bridge/sumo_link.hpp"

namespace lpsim {

struct CosimOptions {
  SumoMode mode = SumoMode::Libsumo;
  std::string sumo_binary = "sumo";    // over TraCI: the program (a path, or looked up on PATH)
  std::vector<std::string> sumo_args;  // passed to SUMO after those the co-simulation sets
  double answer_timeout_s = 300;       // over TraCI: a SUMO that does not answer a call within this is killed
};

/// InputError for a scenario a co-simulation cannot run: one without its SUMO files (a snapshot, a CSV
/// network), with an emissions edgeData/laneData, or asking for unfinished trips in the tripinfo. Called
/// before any output exists.
void refuse_what_cosim_cannot_run(const Scenario& sc, const ConfigSpec& config);

/// 1 for each lane of the corridor's edges, 0 elsewhere (SimulationOptions::outside_lanes).
std::vector<uint8_t> corridor_lanes(const Network& net, const std::vector<uint32_t>& corridor_edges);

class Cosimulation {
 public:
  /// Starts SUMO on `run`'s scenario (its network, its route files for their vTypes at --scale 0 so that SUMO
  /// loads no vehicle of its own, its additional files), at the run's begin time and step length, with
  /// options.sumo_args last. SUMO drives the run's outside lanes (SimulationOptions::outside_lanes, the
  /// corridor's lanes: corridor_lanes()); std::invalid_argument for a run without. A SumoError when SUMO does
  /// not start; an InputError when SUMO's step length (from sumo_args) is not a whole number of milliseconds.
  Cosimulation(Run& run, const CosimOptions& options);
  ~Cosimulation();
  Cosimulation(const Cosimulation&) = delete;
  Cosimulation& operator=(const Cosimulation&) = delete;

  /// One coupling period: LPSim's steps, the hand-overs into SUMO, SUMO's steps, the hand-overs out of it
  /// and the mirror of SUMO's corridor vehicles. A SumoError when SUMO refuses a call or dies.
  void step();
  /// The run's end condition, and without an end time: nothing left in SUMO either.
  bool done() const;
  /// Closes SUMO (its outputs are written), completes the tripinfo of each trip SUMO drove part of from
  /// SUMO's own, finishes the Run, and puts SUMO's entries of the corridor's edges into each edgeData and
  /// laneData output. Later calls do nothing.
  void finish();
  /// Ends SUMO without completing anything (a run stopped by a fault or a signal); the Run is finished.
  void abandon();

  /// Where every loaded vehicle is: exactly one of these.
  struct Census {
    uint64_t loaded = 0;
    uint64_t in_lpsim = 0;     // not yet departed, waiting, running or queued to re-enter in LPSim
    uint64_t in_sumo = 0;      // running in SUMO
    uint64_t in_handover = 0;  // added to SUMO and not yet inserted (pending)
    uint64_t arrived = 0;      // in either
  };
  /// The census by LPSim's ledger and the bridge's account, each checked against the other and against
  /// SUMO's own counts: std::logic_error naming the disagreement (a vehicle lost or in two places).
  Census census() const;

  struct Report {
    double period = 0;  // s
    uint64_t into_sumo = 0, out_of_sumo = 0, arrived_in_sumo = 0;
    uint64_t held = 0;  // times a vehicle was held in SUMO because LPSim had no room to take it back
    double longest_boundary_wait = 0;  // s: pending in SUMO, or held at the corridor's exit
    uint64_t in_handover_at_end = 0;   // pending in SUMO or held in it at the end
    double handover_seconds = 0;       // wall time spent handing over and mirroring
    double sumo_seconds = 0;           // wall time in SUMO's steps
  };
  const Report& report() const { return report_; }
  SumoLink& sumo() { return *sumo_; }

 private:
  struct InSumo {
    uint32_t vehicle = 0;
    uint32_t route_pos = 0;   // of the first edge of the route SUMO was given, in the trip's route
    int32_t entry_lane = -1;  // LPSim lane it was added on (-1: departing there)
    float entry_pos = 0;
    bool pending = true, held = false;
    double since = 0;  // when it was added, or held
  };

  void hand_into_sumo(const OutsideLink::HandOut& h);
  static bool departs_in_sumo(const InSumo& s);  // its trip starts in SUMO (LPSim never inserted it)
  bool due_in_sumo(const InSumo& s) const;
  void count_sumo_departure(uint32_t v, double now);
  double depart_time(uint32_t v) const;  // its trip's departure, on either side
  Run::OutsideCounts outside_counts() const;
  void after_sumo_step();
  // Vehicle `it` ended its route in SUMO's step at `now` (s): it leaves the bridge's account.
  void arrived_in_sumo(std::unordered_map<std::string, InSumo>::iterator it, double now);
  bool corridor_edge(uint32_t e) const;
  int32_t lpsim_lane(uint32_t edge, int sumo_index) const;
  void take_back_or_hold(const std::string& id, InSumo& s, uint32_t edge, const SumoVehicle& q);
  // `after_failure`: SUMO ended abnormally, its tripinfo may be cut off, and a trip is merged only when every
  // visit it made to SUMO has its piece there.
  void merge_tripinfo(bool after_failure);
  void merge_edge_data() const;

  Run& run_;
  const Network& net_;
  OutsideLink& boundary_;  // the run's boundary with SUMO: the corridor's lanes
  CosimOptions options_;
  // A file of this run's that goes with it (also when the constructor fails).
  struct ScratchFile {
    std::string path;  // empty: none
    ScratchFile() = default;
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;
    ~ScratchFile();
  };
  std::string sumo_tripinfo_;     // SUMO's tripinfo (merged into the run's at the end), before its prefix
  ScratchFile scratch_tripinfo_;  // SUMO's tripinfo when the run writes none
  ScratchFile mean_data_file_;    // the additional file defining SUMO's side of edgeData/laneData outputs
  std::unique_ptr<SumoLink> sumo_;
  int64_t period_ms_ = 0, sumo_step_ms_ = 0;
  int64_t begin_ms_ = 0;      // both clocks' begin
  int64_t next_sumo_ms_ = 0;  // SUMO's next step: the state after it is the one LPSim's clock calls this
  std::unordered_map<std::string, InSumo> in_sumo_;
  std::unordered_set<std::string> removed_since_step_;  // SUMO may list a removal among the step's arrivals
  std::vector<uint8_t> visited_;  // per vehicle: the times it was handed into SUMO (255: as many or more)
  std::unordered_map<uint32_t, TripRecord> held_trips_;  // ended in LPSim after a visit: merged at finish()
  std::unordered_map<uint32_t, double>
      driven_between_;  // m, per vehicle: waiting for SUMO's step to insert it
  uint64_t arrived_in_sumo_ = 0;
  Run::OutsideCounts outside_;                        // SUMO's departures and arrivals so far
  std::unordered_map<uint32_t, double> sumo_depart_;  // when SUMO inserted the trips that depart there
  uint64_t pending_ = 0;                              // of in_sumo_
  std::vector<OutsideLink::OutsideVehicle> mirror_;
  Report report_;
  bool finished_ = false;
};

}  // namespace lpsim

#pragma once
// One run of a scenario with its SUMO outputs, stepped by a driver: `lpsim run` steps it to the end, a
// co-simulation or an assignment loop step it in chunks and read the Simulation between them. Whatever the
// chunks, the outputs are those of one uninterrupted run.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "app/jam_report.hpp"
#include "app/scenario.hpp"
#include "app/step_actions.hpp"
#include "converters/fcd_writer.hpp"
#include "converters/mean_data_writer.hpp"
#include "converters/statistic_writer.hpp"
#include "converters/summary_writer.hpp"
#include "converters/tripinfo_writer.hpp"
#include "core/config_spec.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

class Run {
 public:
  /// Sums over the trips that ended (s, route length in m), the most vehicles running at once and the
  /// teleports by cause: what the final report and the statistic output print.
  struct Totals {
    uint64_t trips = 0;
    double duration = 0, route_length = 0, waiting = 0, time_loss = 0, depart_delay = 0;
    double speed = 0;  // sum of each trip's route length / duration
    uint64_t peak_running = 0;
    uint64_t teleports_jam = 0, teleports_yield = 0, teleports_wrong_lane = 0;
  };

  /// Builds the simulation of `scenario` at its begin time, opens the outputs `config` asks for (FCD,
  /// tripinfo, summary, statistic, edgeData/laneData, and the scenario's own edgeData/laneData definitions;
  /// LPSim's jam report with --jam-report)
  /// and writes the state at the begin time. With config.load_state it resumes instead: the simulation,
  /// the totals, the open intervals and the actions' triggers as that state file has them, each output
  /// continued where the saved run had written it to (InputError when the file is not a state of this
  /// scenario and options). With config.save_state_* it writes state files after the steps due. The Run owns
  /// the scenario; its demand becomes the simulation's trip table (move a scenario in, so that a large demand
  /// is not copied). Run sets options.lane_counters and options.emission_sums itself: on exactly when an
  /// edgeData/laneData output needs them (the engine skips their atomics, and its emissions pass, otherwise).
  Run(Scenario scenario, const ConfigSpec& config, SimulationOptions options);
  /// Whether a run of `scenario` with `outputs` counts per lane (what Run sets options.lane_counters to), and
  /// whether it sums emissions per lane (options.emission_sums): the other parts of a partitioned run, which
  /// build their simulations without a Run, count alike. An InputError when an emissions output is
  /// requested and a vehicle type has an emission class of a model LPSim does not implement.
  static bool needs_lane_counters(const Scenario& scenario, const OutputSpec& outputs);
  static bool needs_emission_sums(const Scenario& scenario, const OutputSpec& outputs);
  /// Whether `config` saves or loads a state (--save-state.*, --load-state).
  static bool keeps_states(const ConfigSpec& config);
  /// Without finish(), the writers close their files but the open edgeData/laneData intervals and the
  /// statistics are lost.
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  /// One step, whether or not done(), then the actions due after it (actions()): teleport warnings (unless
  /// --no-warnings) and totals, the jam recorder, the outputs, and those a driver added. When an
  /// edgeData/laneData interval closes, every output is flushed to its file (so a killed run keeps what was
  /// written up to there). std::logic_error after finish().
  void step();
  /// Adds an action to run after each step its trigger makes due, after the Run's own (a checkpoint at
  /// given times, a remote-control command every step): from the next step on.
  void add_action(std::string name, StepTrigger trigger, StepActions::Action action);
  const StepActions& actions() const { return actions_; }
  /// Steps while the next step would end at or before `t` and the run is not done(): never past t, and a
  /// no-op when t is less than a step ahead.
  void step_until(double t);
  /// The end condition of `lpsim run`. With an end time: once one more step would end after it, so that, as
  /// in SUMO, the step samples run to end - step and edgeData intervals and end_time() to the end (when the
  /// end lies a whole number of steps after the begin).
  /// Without one: once the simulation is finished().
  bool done() const;
  /// Writes the open edgeData/laneData intervals (up to end_time()) and the statistics, and closes every
  /// output. Later calls do nothing. Write failures raise InputError. An interrupted run calls it too: its
  /// outputs then end where it stopped, as SUMO's do.
  void finish();
  /// Saves the run's state now, between steps, as --save-state.prefix_TIME suffix, and returns the file's
  /// name (what --save-state.on-signal does when a signal stops the run, before finish()).
  std::string save_state_now();

  /// The time SUMO reports for the same run ("Simulation ended at time"): the end of the last step. The
  /// simulation's clock shows when that step's state holds, as SUMO's outputs do (its state at time t is the
  /// one after its step t), while SUMO's clock has already moved on by one step.
  double end_time() const { return sim_.time() + sim_.step_length(); }

  /// Trips that end from now on and for which `hold` returns true are not written nor counted: the caller
  /// writes them later with write_trip() (a co-simulation completes the trips that SUMO drove part of).
  void hold_trips(std::function<bool(const TripRecord&)> hold) { hold_trip_ = std::move(hold); }
  /// Writes a trip's tripinfo line and counts it in the totals. std::logic_error after finish().
  void write_trip(const TripRecord& r);

  /// The vehicles another simulator drives for this run (a co-simulation's SUMO), as of now: its insertions
  /// of trips that depart there, those on its roads or about to be, those waiting to depart there, its
  /// arrivals, and the sums of its arrivals' trip durations and its insertions' delays.
  struct OutsideCounts {
    uint64_t inserted = 0, running = 0, waiting = 0, arrived = 0;
    double travel_time_sum = 0, depart_delay_sum = 0;
  };
  /// From now on the summary, the statistics and the report count both sides: `outside` is asked for the
  /// other side's counts each time they are written.
  void count_outside(std::function<OutsideCounts()> outside) { outside_ = std::move(outside); }
  /// The simulation's counts, with the other side's added (count_outside).
  Simulation::Counts counts() const;

  Simulation& simulation() { return sim_; }
  const Simulation& simulation() const { return sim_; }
  const Totals& totals() const { return totals_; }
  const ConfigSpec& config() const { return config_; }
  const Scenario& scenario() const { return scenario_; }
  /// The options the simulation runs with (lane_counters and emission_sums as Run set them).
  const SimulationOptions& options() const { return options_; }

 private:
  // One edgeData/laneData definition: its writer, its interval and the cumulative counters at the
  // interval's start (the simulation's counters only ever grow; an interval is the difference).
  struct MeanDataOutput {
    MeanDataSpec spec;
    std::unique_ptr<MeanDataWriter> writer;
    double interval_begin = 0;
    LaneCounters at_begin;
  };

  static std::vector<MeanDataOutput> mean_data_outputs(const Scenario& scenario, const OutputSpec& outputs);
  static SimulationOptions counting_lanes(SimulationOptions options,
                                          const std::vector<MeanDataOutput>& outputs);
  /// The trips the simulation runs, which may grow while it runs (the writers name their vehicles).
  const Demand& demand() const { return sim_.demand(); }
  /// `continue_at`: where each output a resumed run continues (output_sizes()'s order, continued_outputs()
  /// of them), else null.
  void open_outputs(const std::vector<int64_t>* continue_at);
  /// How many outputs a resumed run continues: those of output_sizes(), known before they are opened.
  size_t continued_outputs() const;
  void add_own_actions();
  void write_summary_row();
  void write_unfinished_trips();
  void warn_teleports() const;
  void close_interval(MeanDataOutput& m, double until);
  void flush_outputs();
  // Checkpoints (--save-state.*, --load-state).
  void add_state_saves();
  void save_state(const std::string& path);
  void resume(const std::string& path);
  std::vector<int64_t> output_sizes();
  template <class A>
  void visit_state(A& a);
  RunStatistics statistics() const;

  Scenario scenario_;  // its demand moved into sim_
  ConfigSpec config_;
  std::vector<MeanDataOutput> mean_data_;  // before options_: they decide the lane counters
  SimulationOptions options_;
  uint64_t digest_;  // of the scenario and options: what a state file must have been saved from
  Simulation sim_;
  std::unique_ptr<FcdWriter> fcd_;
  std::unique_ptr<TripinfoWriter> tripinfo_;
  std::unique_ptr<SummaryWriter> summary_;
  std::unique_ptr<StatisticWriter> statistic_;
  std::unique_ptr<JamRecorder> jam_;  // only with --jam-report: without it a step does no work for it
  FcdFrame frame_;
  StepActions actions_;
  bool interval_closed_ = false;  // since the last flush
  Totals totals_;
  double depart_delay_waiting_ = -1;  // the statistic's departDelayWaiting (write-undeparted)
  std::function<bool(const TripRecord&)> hold_trip_;
  std::function<OutsideCounts()> outside_;
  bool closed_ = false;
  size_t own_actions_ = 0;      // the actions whose triggers a state keeps: all but the state saves
  size_t next_state_file_ = 0;  // of config_.save_state_files
};

/// The SUMO-like report `lpsim run` prints at the end: end time and reason, performance (wall_seconds since
/// the simulation was built, load_seconds for reading the scenario), vehicle counts, teleports and the trip
/// averages. `interrupted_by` names the signal that stopped the run early, if one did (nullptr: none).
void print_run_report(std::FILE* out, const Run& run, double wall_seconds, double load_seconds,
                      const char* interrupted_by = nullptr);
/// How a command ends a run it stepped to its end or until `signal` (0: none) stopped it: one line on stderr
/// for the signal, then the report on stdout.
void report_run_end(const Run& run, double wall_seconds, double load_seconds, int signal);

}  // namespace lpsim

#pragma once
// The jam report (`lpsim run --jam-report FILE`): one <jam> element per teleport and per episode of a vehicle
// standing longer than the report's stop time, with what bounded its speed and the chain of vehicles that
// blocked it. LPSim's own format (no SUMO counterpart); tools/jam_compare.py reads it beside SUMO's FCD.
#include <cstdint>
#include <string>
#include <vector>

#include "converters/output_file.hpp"
#include "demand/demand.hpp"
#include "engine/samples.hpp"
#include "net/network.hpp"

namespace lpsim {

/// One vehicle of a blocker chain, as it stood in the step the chain was taken from.
struct JamVehicleState {
  uint32_t vehicle = 0;
  uint32_t lane = 0;
  float pos = 0, speed = 0;
  uint8_t reason = 0;  // StopReason (kernels/step_view.hpp)

  /// Field by field for a checkpoint's state (app/state_file), without the padding.
  template <class A>
  void visit_state(A& a) {
    a(vehicle);
    a(lane);
    a(pos);
    a(speed);
    a(reason);
  }
};

/// How a standing episode ended.
enum class JamEnd : uint8_t { Moved, Teleported, LeftRoad, RunEnded };

/// One standing episode (or a teleport). `where` is the vehicle in the step it had stood the stop time (a
/// teleport: its last step on the road); `chain` the vehicles that blocked it then, each blocking the one
/// before (empty when its reason has no blocker);
/// `cycle_from` the index in `chain` where a deadlock cycle starts (the chain's last vehicle is blocked by
/// chain[cycle_from], or by the vehicle itself when cycle_from is kSelf), or -1 when the chain ends at a
/// vehicle that is not blocked by another.
struct JamRecord {
  static constexpr int32_t kSelf = -2;
  double begin = 0, end = 0;  // s: first step seen standing, and the step it moved, left or teleported
  JamEnd ended = JamEnd::Moved;
  TeleportCause teleport = TeleportCause::Jam;  // when ended == Teleported
  JamVehicleState where;
  std::vector<double> reason_seconds;  // seconds standing per StopReason, indexed by it
  std::vector<JamVehicleState> chain;
  int32_t cycle_from = -1;

  template <class A>
  void visit_state(A& a) {
    a(begin);
    a(end);
    a(ended);
    a(teleport);
    a(where);
    a(reason_seconds);
    a(chain);
    a(cycle_from);
  }
};

/// The name the report gives a StopReason ("leader", "wrong_lane", "signal", "halt_rule", "no_room",
/// "yield", "merge_gap", "swap", "scheduled_stop"; "free" for none).
const char* stop_reason_name(uint8_t reason);

class JamReportWriter {
 public:
  /// Opens `path` (".gz" gives gzip) and writes the root tag, or with `continue_at` >= 0 continues the
  /// report a saved run left there (OutputFile). net and demand must outlive the writer.
  JamReportWriter(const std::string& path, const Network& net, const Demand& demand, double stop_time,
                  int64_t continue_at = -1);
  ~JamReportWriter();
  JamReportWriter(const JamReportWriter&) = delete;
  JamReportWriter& operator=(const JamReportWriter&) = delete;

  void write(const JamRecord& r);
  void flush() { out_.flush(); }
  /// Everything written so far handed to the file: where a resumed run continues it (OutputFile).
  uint64_t continue_point() { return out_.continue_point(); }
  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  void vehicle_attrs(const JamVehicleState& s);

  const Network& net_;
  const Demand& demand_;
  OutputFile out_;
};

}  // namespace lpsim

#include "converters/jam_report_writer.hpp"

#include <stdexcept>
#include <string>

namespace lpsim {

namespace {

const char* end_name(JamEnd e) {
  switch (e) {
    case JamEnd::Moved:
      return "moved";
    case JamEnd::Teleported:
      return "teleported";
    case JamEnd::LeftRoad:
      return "left";
    case JamEnd::RunEnded:
      return "running";
  }
  return "moved";
}

// The words of the run's teleport warning, joined so that an attribute value is one token.
const char* teleport_name(TeleportCause c) {
  return c == TeleportCause::Yield ? "yield" : c == TeleportCause::WrongLane ? "wrong_lane" : "jam";
}

}  // namespace

const char* stop_reason_name(uint8_t reason) {
  // In the order of StopReason (kernels/step_view.hpp), which converters/ does not include.
  static constexpr const char* kNames[] = {"free",    "leader", "wrong_lane", "signal", "halt_rule",
                                           "no_room", "yield",  "merge_gap",  "swap",   "scheduled_stop"};
  return reason < sizeof(kNames) / sizeof(kNames[0]) ? kNames[reason] : "unknown";
}

JamReportWriter::JamReportWriter(const std::string& path, const Network& net, const Demand& demand,
                                 double stop_time, int64_t continue_at)
    : net_(net),
      demand_(demand),
      out_(continue_at < 0 ? OutputFile(path) : OutputFile(path, static_cast<uint64_t>(continue_at))) {
  if (continue_at >= 0) return;
  out_.text("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  out_.text(
      "<!-- LPSim jam report: every teleport and every vehicle standing (speed < 0.1 m/s) at least\n"
      "     stopTime s. lane, pos, reason (what bounded its speed) and blockers: as of the step it had "
      "stood\n"
      "     stopTime s (a teleport: its last step on the road); reasons: its standing seconds per reason;\n"
      "     blocker: the chain of vehicles ahead (on its lane, else the first on the next lane of its "
      "route)\n"
      "     while they crawl below 10 km/h; deadlock: a chain of standing vehicles that comes back. -->\n");
  out_.text("<jamReport");
  out_.attr_fixed("stopTime", stop_time);
  out_.text(">\n");
}

JamReportWriter::~JamReportWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void JamReportWriter::vehicle_attrs(const JamVehicleState& s) {
  out_.attr("id", demand_.vehicle_id[s.vehicle]);
  out_.attr("lane", net_.lane_id[s.lane]);
  out_.attr_fixed("pos", s.pos);
  out_.attr_fixed("speed", s.speed);
  out_.attr("reason", stop_reason_name(s.reason));
}

void JamReportWriter::write(const JamRecord& r) {
  out_.text("    <jam");
  vehicle_attrs(r.where);
  out_.attr_fixed("begin", r.begin);
  out_.attr_fixed("end", r.end);
  out_.attr_fixed("duration", r.end - r.begin);
  out_.attr("ended", end_name(r.ended));
  if (r.ended == JamEnd::Teleported) out_.attr("teleport", teleport_name(r.teleport));
  // Seconds standing per reason over the whole episode, in StopReason order, to one decimal.
  std::string reasons;
  for (size_t k = 0; k < r.reason_seconds.size(); ++k) {
    if (r.reason_seconds[k] <= 0) continue;
    if (!reasons.empty()) reasons += ' ';
    reasons += stop_reason_name(static_cast<uint8_t>(k));
    reasons += ':';
    const long long tenths = static_cast<long long>(r.reason_seconds[k] * 10 + 0.5);
    reasons += std::to_string(tenths / 10);
    if (tenths % 10 != 0) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
      reasons += '.';
      reasons += std::to_string(tenths % 10);
    }
  }
  out_.attr("reasons", reasons);
  if (r.chain.empty() && r.cycle_from == -1) {
    out_.text("/>\n");
    return;
  }
  out_.text(">\n");
  for (const JamVehicleState& b : r.chain) {
    out_.text("        <blocker");
    vehicle_attrs(b);
    out_.text("/>\n");
  }
  if (r.cycle_from != -1) {
    // The cycle's members, in the order each blocks the one before: from its start to the chain's end.
    std::string ids, lanes;
    auto add = [&](const JamVehicleState& s) {
      if (!ids.empty()) {
        ids += ' ';
        lanes += ' ';
      }
      ids += demand_.vehicle_id[s.vehicle];
      lanes += net_.lane_id[s.lane];
    };
    if (r.cycle_from == JamRecord::kSelf) add(r.where);
    for (size_t k = r.cycle_from == JamRecord::kSelf ? 0 : static_cast<size_t>(r.cycle_from);
         k < r.chain.size(); ++k)
      add(r.chain[k]);
    out_.text("        <deadlock");
    out_.attr("vehicles", ids);
    out_.attr("lanes", lanes);
    out_.text("/>\n");
  }
  out_.text("    </jam>\n");
}

void JamReportWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</jamReport>\n");
  out_.close();
}

}  // namespace lpsim

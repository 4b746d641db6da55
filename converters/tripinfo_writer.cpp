#include "converters/tripinfo_writer.hpp"

#include <stdexcept>

namespace lpsim {

TripinfoWriter::TripinfoWriter(const std::string& path, const Network& net, const Demand& demand,
                               std::vector<std::string> devices, int64_t continue_at)
    : net_(net),
      demand_(demand),
      devices_(std::move(devices)),
      out_(continue_at < 0 ? OutputFile(path) : OutputFile(path, static_cast<uint64_t>(continue_at))) {
  if (continue_at < 0) write_sumo_xml_header(out_, "tripinfos", "tripinfo_file.xsd");
}

TripinfoWriter::~TripinfoWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void TripinfoWriter::write(const TripRecord& trip) {
  const std::string& id = demand_.vehicle_id[trip.vehicle];
  // SUMO's write-unfinished/write-undeparted lines: what did not happen is -1 (depart as the integer "-1")
  // and an empty lane id; a running trip's duration runs to the end, an undeparted one's is 0.
  const bool departed = trip.unfinished != kTripUndeparted;
  const bool arrived = trip.unfinished == 0;
  out_.text("    <tripinfo");
  out_.attr("id", id);
  if (departed)
    out_.attr_fixed("depart", trip.depart);
  else
    out_.text(" depart=\"-1\"");
  out_.attr("departLane", departed ? std::string_view(net_.lane_id[trip.depart_lane]) : std::string_view());
  out_.attr_fixed("departPos", departed ? trip.depart_pos : -1.0);
  out_.attr_fixed("departSpeed", departed ? trip.depart_speed : -1.0);
  out_.attr_fixed("departDelay", trip.depart_delay);
  out_.attr_fixed("arrival", arrived ? trip.arrival : -1.0);
  out_.attr("arrivalLane", arrived ? std::string_view(net_.lane_id[trip.arrival_lane]) : std::string_view());
  out_.attr_fixed("arrivalPos", arrived ? trip.arrival_pos : -1.0);
  out_.attr_fixed("arrivalSpeed", arrived ? trip.arrival_speed : -1.0);
  out_.attr_fixed("duration", departed ? trip.arrival - trip.depart : 0.0);
  out_.attr_fixed("routeLength", trip.route_length);
  out_.attr_fixed("waitingTime", trip.waiting_time);
  out_.attr_int("waitingCount", trip.waiting_count);
  out_.attr_fixed("stopTime", trip.stop_time);
  out_.attr_fixed("timeLoss", trip.time_loss);
  out_.text(" rerouteNo=\"0\" devices=\"");
  for (size_t i = 0; i < devices_.size(); ++i) {
    if (i > 0) out_.put(' ');
    out_.escaped(devices_[i]);
    out_.put('_');
    out_.escaped(id);
  }
  out_.put('"');
  out_.attr("vType", demand_.types.id[demand_.vehicle_type[trip.vehicle]]);
  out_.attr_fixed("speedFactor", trip.speed_factor);
  out_.text(!arrived          ? " vaporized=\"end\"/>\n"
            : trip.removed    ? " vaporized=\"traci\"/>\n"
            : trip.teleported ? " vaporized=\"teleport\"/>\n"
                              : " vaporized=\"\"/>\n");
}

void TripinfoWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</tripinfos>\n");
  out_.close();
}

}  // namespace lpsim

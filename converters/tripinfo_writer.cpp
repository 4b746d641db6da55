#include "converters/tripinfo_writer.hpp"

#include <stdexcept>

namespace lpsim {

TripinfoWriter::TripinfoWriter(const std::string& path, const Network& net, const Demand& demand,
                               std::vector<std::string> devices)
    : net_(net), demand_(demand), devices_(std::move(devices)), out_(path) {
  write_sumo_xml_header(out_, "tripinfos", "tripinfo_file.xsd");
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
  out_.text("    <tripinfo");
  out_.attr("id", id);
  out_.attr_fixed("depart", trip.depart);
  out_.attr("departLane", net_.lane_id[trip.depart_lane]);
  out_.attr_fixed("departPos", trip.depart_pos);
  out_.attr_fixed("departSpeed", trip.depart_speed);
  out_.attr_fixed("departDelay", trip.depart_delay);
  out_.attr_fixed("arrival", trip.arrival);
  out_.attr("arrivalLane", net_.lane_id[trip.arrival_lane]);
  out_.attr_fixed("arrivalPos", trip.arrival_pos);
  out_.attr_fixed("arrivalSpeed", trip.arrival_speed);
  out_.attr_fixed("duration", trip.arrival - trip.depart);
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
  out_.text(trip.teleported ? " vaporized=\"teleport\"/>\n" : " vaporized=\"\"/>\n");
}

void TripinfoWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</tripinfos>\n");
  out_.close();
}

}  // namespace lpsim

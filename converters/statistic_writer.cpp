#include "converters/statistic_writer.hpp"

#include <stdexcept>

namespace lpsim {

StatisticWriter::StatisticWriter(const std::string& path) : out_(path) {
  write_sumo_xml_header(out_, "statistics", "statistic_file.xsd");
}

StatisticWriter::~StatisticWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void StatisticWriter::count(std::string_view name, uint64_t v) {
  out_.put(' ');
  out_.text(name);
  out_.text("=\"");
  out_.unsigned_integer(v);
  out_.put('"');
}

void StatisticWriter::write(const RunStatistics& s) {
  out_.text("    <vehicles");
  count("loaded", s.loaded);
  count("inserted", s.inserted);
  count("running", s.running);
  count("waiting", s.waiting);
  out_.text("/>\n    <teleports");
  count("total", s.teleports_jam + s.teleports_yield + s.teleports_wrong_lane);
  count("jam", s.teleports_jam);
  count("yield", s.teleports_yield);
  count("wrongLane", s.teleports_wrong_lane);
  out_.text(
      "/>\n"
      "    <safety collisions=\"0\" emergencyStops=\"0\"/>\n"
      "    <persons loaded=\"0\" running=\"0\" jammed=\"0\"/>\n"
      "    <vehicleTripStatistics");
  // SUMO divides by the trip count, or by 1 when no trip ended (all means 0 then).
  const double n = s.trips > 0 ? static_cast<double>(s.trips) : 1.0;
  count("count", s.trips);
  out_.attr_fixed("routeLength", s.route_length / n);
  out_.attr_fixed("speed", s.speed / n);
  out_.attr_fixed("duration", s.duration / n);
  out_.attr_fixed("waitingTime", s.waiting_time / n);
  out_.attr_fixed("timeLoss", s.time_loss / n);
  out_.attr_fixed("departDelay", s.depart_delay / n);
  out_.attr_fixed("departDelayWaiting", s.depart_delay_waiting);
  out_.attr_fixed("totalTravelTime", s.duration);
  out_.attr_fixed("totalDepartDelay", s.depart_delay);
  out_.text(
      "/>\n"
      "    <pedestrianStatistics number=\"0\" routeLength=\"0.00\" duration=\"0.00\" timeLoss=\"0.00\"/>\n"
      "    <rideStatistics number=\"0\"/>\n"
      "    <transportStatistics number=\"0\"/>\n");
}

void StatisticWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</statistics>\n");
  out_.close();
}

}  // namespace lpsim

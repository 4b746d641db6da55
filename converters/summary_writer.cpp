#include "converters/summary_writer.hpp"

#include <cmath>
#include <stdexcept>

namespace lpsim {

SummaryWriter::SummaryWriter(const std::string& path, int64_t continue_at)
    : out_(continue_at < 0 ? OutputFile(path) : OutputFile(path, static_cast<uint64_t>(continue_at))) {
  if (continue_at < 0) write_sumo_xml_header(out_, "summary", "summary_file.xsd");
}

SummaryWriter::~SummaryWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void SummaryWriter::write(const SummaryRow& row) {
  const auto count = [this](std::string_view name, uint64_t v) {
    out_.put(' ');
    out_.text(name);
    out_.text("=\"");
    out_.unsigned_integer(v);
    out_.put('"');
  };
  out_.text("    <step");
  out_.attr_fixed("time", row.time);
  count("loaded", row.loaded);
  count("inserted", row.inserted);
  count("running", row.running);
  count("waiting", row.waiting);
  count("ended", row.ended);
  count("arrived", row.arrived);
  count("collisions", row.collisions);
  count("teleports", row.teleports);
  count("halting", row.halting);
  count("stopped", row.stopped);
  out_.attr_fixed("meanWaitingTime", row.inserted > 0 ? row.mean_waiting_time : -1.0);
  out_.attr_fixed("meanTravelTime", row.ended > 0 ? row.mean_travel_time : -1.0);
  out_.attr_fixed("meanSpeed", row.running > 0 ? row.mean_speed : -1.0);
  out_.attr_fixed("meanSpeedRelative", row.running > 0 ? row.mean_speed_relative : -1.0);
  out_.attr_int("duration", std::llround(row.duration_ms));
  out_.text("/>\n");
}

void SummaryWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</summary>\n");
  out_.close();
}

}  // namespace lpsim

#include "converters/fcd_writer.hpp"

#include <stdexcept>

namespace lpsim {

FcdWriter::FcdWriter(const std::string& path, const Network& net, const Demand& demand, int64_t continue_at)
    : net_(net),
      demand_(demand),
      geometry_(net),
      out_(continue_at < 0 ? OutputFile(path) : OutputFile(path, static_cast<uint64_t>(continue_at))) {
  if (continue_at < 0) write_sumo_xml_header(out_, "fcd-export", "fcd_file.xsd");
}

FcdWriter::~FcdWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void FcdWriter::write(const FcdFrame& frame) {
  const size_t n = frame.vehicle.size();
  if (frame.lane.size() != n || frame.pos.size() != n || frame.speed.size() != n)
    throw std::logic_error("FcdFrame: vehicle, lane, pos and speed differ in size");
  out_.text("    <timestep");
  out_.attr_fixed("time", frame.time);
  if (n == 0) {
    out_.text("/>\n");
    return;
  }
  out_.text(">\n");
  for (size_t i = 0; i < n; ++i) {
    const uint32_t vehicle = frame.vehicle[i], lane = frame.lane[i];
    const uint32_t type = demand_.vehicle_type[vehicle];
    const LanePoint point = geometry_.at(lane, frame.pos[i]);
    const double angle = geometry_.vehicle_heading(lane, frame.pos[i], demand_.types.length[type]);
    out_.text("        <vehicle");
    out_.attr("id", demand_.vehicle_id[vehicle]);
    out_.attr_fixed("x", point.x);
    out_.attr_fixed("y", point.y);
    out_.attr_fixed("angle", angle);
    out_.attr("type", demand_.types.id[type]);
    out_.attr_fixed("speed", frame.speed[i]);
    out_.attr_fixed("pos", frame.pos[i]);
    out_.attr("lane", net_.lane_id[lane]);
    out_.text(" slope=\"0.00\"/>\n");
  }
  out_.text("    </timestep>\n");
}

void FcdWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</fcd-export>\n");
  out_.close();
}

}  // namespace lpsim

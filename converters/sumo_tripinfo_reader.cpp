#include "converters/sumo_tripinfo_reader.hpp"

#include <filesystem>

#include "converters/xml_stream.hpp"

namespace lpsim {

namespace {

void read_pieces(const std::string& path, std::vector<SumoTripPiece>& pieces) {
  XmlStream xml(path);
  for (XmlStream::Event e = xml.next(); e != XmlStream::Event::Eof; e = xml.next()) {
    if (e != XmlStream::Event::Start || xml.name() != "tripinfo") continue;
    SumoTripPiece p;
    p.id = xml.required("id");
    p.depart = xml.required_number("depart");
    p.depart_lane = xml.required("departLane");
    p.depart_pos = xml.required_number("departPos");
    p.depart_speed = xml.required_number("departSpeed");
    p.depart_delay = xml.required_number("departDelay");
    p.arrival = xml.required_number("arrival");
    p.arrival_lane = xml.required("arrivalLane");
    p.arrival_pos = xml.required_number("arrivalPos");
    p.arrival_speed = xml.required_number("arrivalSpeed");
    p.route_length = xml.required_number("routeLength");
    p.waiting_time = xml.required_number("waitingTime");
    p.waiting_count = xml.integer("waitingCount", 0);
    p.stop_time = xml.number("stopTime", 0);
    p.time_loss = xml.number("timeLoss", 0);
    p.vaporized = xml.get("vaporized", "");
    pieces.push_back(std::move(p));
  }
}

}  // namespace

std::vector<SumoTripPiece> read_sumo_tripinfo(const std::string& path, bool cut_off) {
  std::vector<SumoTripPiece> pieces;
  if (cut_off) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return pieces;
    try {
      read_pieces(path, pieces);
    } catch (const InputError&) {
      // The cut: what was read before it is whole (an element counts once its start tag is complete).
    }
    return pieces;
  }
  read_pieces(path, pieces);
  return pieces;
}

}  // namespace lpsim

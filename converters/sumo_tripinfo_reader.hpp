#pragma once
// SUMO's tripinfo output read back: what the co-simulation merges into one line per trip from the pieces of
// it that SUMO drove (each hand-over out of SUMO ends a piece that SUMO marks vaporized="traci").
#include <string>
#include <vector>

namespace lpsim {

/// One <tripinfo> element: the piece of a trip SUMO drove (times in s, lengths in m).
struct SumoTripPiece {
  std::string id;
  double depart = 0, depart_pos = 0, depart_speed = 0, depart_delay = 0;
  std::string depart_lane, arrival_lane;
  double arrival = 0, arrival_pos = 0, arrival_speed = 0;
  double route_length = 0, waiting_time = 0, stop_time = 0, time_loss = 0;
  long long waiting_count = 0;
  // Why SUMO ended it short of its arrival: "traci" (taken out by a client: a hand-over back), "teleport"
  // (teleported beyond its route's last edge), "end" (still running at the end); empty: it arrived.
  std::string vaporized;
};

/// The tripinfo elements of a SUMO tripinfo output, in file order; InputError with file:line when the file
/// is missing, malformed or an element lacks an attribute SUMO always writes.
/// `cut_off`: the file may end anywhere (SUMO died while writing it): the complete elements before the cut
/// are returned, and a missing file is none. Otherwise every problem is an InputError.
std::vector<SumoTripPiece> read_sumo_tripinfo(const std::string& path, bool cut_off = false);

}  // namespace lpsim

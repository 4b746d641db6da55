#pragma once
// statistic output (SUMO's --statistic-output, statistic_file.xsd): the run's totals at its end, as SUMO 1.15
// writes them. LPSim has no collisions, emergency stops, persons, rides or transports: those are written as
// 0, as SUMO writes them for a run without any. departDelayWaiting is -1, as SUMO writes it unless it was
// asked to write unfinished trips, which LPSim cannot. vehicleTripStatistics is always written (SUMO writes
// it only when its tripinfo device is on; LPSim always keeps the totals, and prints them in its report).
#include <cstdint>
#include <string>

#include "converters/output_file.hpp"

namespace lpsim {

/// What the statistic output reports: vehicle counts at the end, teleports by cause, and sums over the
/// trips that ended (s, m).
struct RunStatistics {
  uint64_t loaded = 0, inserted = 0, running = 0, waiting = 0;
  uint64_t teleports_jam = 0, teleports_yield = 0, teleports_wrong_lane = 0;
  uint64_t trips = 0;
  double route_length = 0, duration = 0, waiting_time = 0, time_loss = 0, depart_delay = 0;
  double speed = 0;  // sum over the trips of route length / duration (SUMO averages the trips' speeds)
  // Mean depart delay of the vehicles still waiting to depart at the end, as tripinfo's write-undeparted
  // reports them; -1 when none was reported.
  double depart_delay_waiting = -1;
};

class StatisticWriter {
 public:
  /// Opens `path` (".gz" gives gzip) and writes the root tag, so that a bad path fails before the run.
  explicit StatisticWriter(const std::string& path);
  ~StatisticWriter();
  StatisticWriter(const StatisticWriter&) = delete;
  StatisticWriter& operator=(const StatisticWriter&) = delete;

  /// Writes the statistics, once, at the end of the run.
  void write(const RunStatistics& stats);
  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  void count(std::string_view name, uint64_t v);
  OutputFile out_;
};

}  // namespace lpsim

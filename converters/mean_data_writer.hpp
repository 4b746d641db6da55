#pragma once
// edgeData / laneData output (SUMO's meandata_file.xsd): per interval, traffic measures of every edge (or
// of every lane, nested in its edge) computed from the engine's integer LaneCounters; or, for type
// "emissions", the emissions of converters/emission_mean_data.hpp. The rest of this comment is about the
// traffic measures.
//
// Definitions, for one edge (lanes summed; L = edge length = length of its first car lane, n = its car
// lane count, v_max = edge speed) or one lane (L = lane length, n = 1, v_max = lane speed), over an
// interval of T = end - begin seconds with step length dt:
//   sampledSeconds    S  = sampled_steps * dt                          vehicle-seconds on it
//   travelled         D  = travelled_mm / 1000                         metres driven on it
//   speed                = D / S                                       m/s, space-mean speed
//   traveltime           = min(L * S / D, 100000)                      s, = L / speed; omitted when D <= 1 mm
//   overlapTraveltime    = min((L + l) * S / D, 100000), l = O / S     s, time to clear it completely;
//                          100000 when D = 0. SUMO uses the mean full vehicle length for l; LaneCounters
//                          only has the occupied length O (see occupancy), so l is the mean length on it.
//   density              = min(S / T * 1000 / L, 1000 * n / l_min)     veh/km over all its lanes; l_min =
//                          shortest vehicle type length (SUMO caps with the shortest vehicle seen)
//   laneDensity          = density / n                                 veh/km/lane
//   occupancy            = O / T / L / n * 100, O = occupied_mm_steps / 1000 * dt (m*s)   % of length*time
//   waitingTime          = waiting_steps * dt                          vehicle-seconds below 0.1 m/s
//   timeLoss             = time_loss_ms / 1000                         s lost against the desired speed
//   speedRelative        = speed / v_max                               (0 when v_max = 0)
//   departed, arrived, entered, left: counts as given. laneChangedFrom/To are written as 0: LaneCounters
//   does not count lane changes yet.
// With S = 0 only sampledSeconds and the counts are written (as SUMO). An edge or lane is "empty" when
// S = 0 and all counts are 0; exclude_empty skips empty ones (laneData: an edge is kept if any of its
// lanes is not empty, and only its non-empty lanes are written). Internal edges are written only with
// with_internal. Edges without car lanes appear in edgeData (all zero) but not in laneData, which has no
// lane to write for them.
#include <cstdint>
#include <string>

#include "converters/emission_mean_data.hpp"
#include "converters/output_file.hpp"
#include "core/additional_spec.hpp"
#include "demand/demand.hpp"
#include "engine/samples.hpp"
#include "net/network.hpp"

namespace lpsim {

/// Counters of one edge or lane over one interval, in SI units.
struct MeanDataTotals {
  double sampled_seconds = 0, travelled_m = 0, waiting_seconds = 0, time_loss_seconds = 0;
  double occupied_m_seconds = 0;
  int64_t departed = 0, arrived = 0, entered = 0, left = 0;

  bool empty() const;
};

/// Sums lanes [first_lane, first_lane + lanes) of `counters`; dt is the step length in seconds.
MeanDataTotals sum_lane_counters(const LaneCounters& counters, uint32_t first_lane, uint32_t lanes,
                                 double dt);

/// Derived measures (see the header comment); meaningful only when totals.sampled_seconds > 0.
struct MeanDataMeasures {
  bool has_traveltime = false;
  double traveltime = 0, overlap_traveltime = 0, density = 0, lane_density = 0, occupancy = 0;
  double speed = 0, speed_relative = 0;
};

MeanDataMeasures derive_mean_data(const MeanDataTotals& totals, double length, uint32_t lanes,
                                  double speed_limit, double interval_seconds, double min_vehicle_length);

class MeanDataWriter {
 public:
  /// Opens spec.file (".gz" gives gzip) and writes the root tag. net and demand must outlive the writer.
  /// volumetric_fuel: the run sums fuel by volume (the defaults of excludeEmpty="defaults" follow it).
  /// `continue_at` >= 0: the file a saved run left, continued from that byte (OutputFile), without a header.
  MeanDataWriter(const MeanDataSpec& spec, const Network& net, const Demand& demand,
                 bool volumetric_fuel = false, int64_t continue_at = -1);
  ~MeanDataWriter();
  MeanDataWriter(const MeanDataWriter&) = delete;
  MeanDataWriter& operator=(const MeanDataWriter&) = delete;

  /// Writes one <interval>. interval.counters must have one entry per network lane.
  void write(const MeanDataInterval& interval);
  /// Hands what was written so far to the file (OutputFile::flush). Called between records, so that a file
  /// cut short by a later kill holds them all and lacks only its closing tag.
  void flush() { out_.flush(); }
  /// Everything written so far handed to the file: where a resumed run continues it (OutputFile).
  uint64_t continue_point() { return out_.continue_point(); }

  /// Writes the closing tag and closes the file (InputError on failure); later calls do nothing.
  void close();

 private:
  void write_values(const MeanDataTotals& totals, double length, uint32_t lanes, double speed_limit,
                    double interval_seconds);
  /// Whether lanes [first, first + lanes) counted nothing in the interval (what excludeEmpty leaves out).
  bool empty(const MeanDataInterval& interval, uint32_t first, uint32_t lanes) const;
  /// The attributes after the id of an edge (lanes: its lanes) or a lane (lanes: 1) and the element's end.
  void write_entry(const MeanDataInterval& interval, uint32_t first, uint32_t lanes, double length,
                   double speed_limit, double interval_seconds);
  void write_edge(const MeanDataInterval& interval, uint32_t edge, double interval_seconds);
  void write_lanes(const MeanDataInterval& interval, uint32_t edge, double interval_seconds);

  MeanDataSpec spec_;
  const Network& net_;
  double min_vehicle_length_ = 0;
  DefaultEmissionVehicle default_vehicle_;  // for an emissions output's excludeEmpty="defaults"
  OutputFile out_;
};

}  // namespace lpsim

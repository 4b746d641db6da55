#include "converters/mean_data_writer.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lpsim {

namespace {

constexpr double kMaxTravelTime = 100000;  // SUMO's default maxTraveltime cap, s
constexpr double kNumericalEps = 0.001;    // SUMO's NUMERICAL_EPS: below this a distance counts as none

}  // namespace

bool MeanDataTotals::empty() const {
  return sampled_seconds == 0 && departed == 0 && arrived == 0 && entered == 0 && left == 0;
}

MeanDataTotals sum_lane_counters(const LaneCounters& c, uint32_t first_lane, uint32_t lanes, double dt) {
  // Integer sums first: exact and independent of the order lanes are visited.
  int64_t sampled = 0, travelled_mm = 0, waiting = 0, loss_ms = 0, occupied = 0;
  MeanDataTotals t;
  for (uint32_t l = first_lane; l < first_lane + lanes; ++l) {
    sampled += c.sampled_steps[l];
    travelled_mm += c.travelled_mm[l];
    waiting += c.waiting_steps[l];
    loss_ms += c.time_loss_ms[l];
    occupied += c.occupied_mm_steps[l];
    t.departed += c.departed[l];
    t.arrived += c.arrived[l];
    t.entered += c.entered[l];
    t.left += c.left[l];
  }
  t.sampled_seconds = double(sampled) * dt;
  t.travelled_m = double(travelled_mm) / 1000.0;
  t.waiting_seconds = double(waiting) * dt;
  t.time_loss_seconds = double(loss_ms) / 1000.0;
  t.occupied_m_seconds = double(occupied) / 1000.0 * dt;
  return t;
}

MeanDataMeasures derive_mean_data(const MeanDataTotals& t, double length, uint32_t lanes, double speed_limit,
                                  double interval_seconds, double min_vehicle_length) {
  MeanDataMeasures m;
  if (t.sampled_seconds <= 0) return m;
  const double S = t.sampled_seconds, D = t.travelled_m;
  const double n = std::max<uint32_t>(lanes, 1);
  if (D > kNumericalEps) {
    m.has_traveltime = true;
    m.traveltime = std::min(kMaxTravelTime, length * S / D);
  }
  m.overlap_traveltime = kMaxTravelTime;
  if (D > 0) {
    const double mean_length_on_lane = t.occupied_m_seconds / S;
    m.overlap_traveltime = std::min(kMaxTravelTime, (length + mean_length_on_lane) * S / D);
  }
  const double density_cap = 1000.0 * n / std::max(min_vehicle_length, kNumericalEps);
  m.density = length > 0 ? std::min(S / interval_seconds * 1000.0 / length, density_cap) : density_cap;
  m.lane_density = m.density / n;
  m.occupancy = length > 0 ? t.occupied_m_seconds / interval_seconds / length / n * 100.0 : 0.0;
  m.speed = D / S;
  m.speed_relative = speed_limit > 0 ? m.speed / speed_limit : 0.0;
  return m;
}

MeanDataWriter::MeanDataWriter(const MeanDataSpec& spec, const Network& net, const Demand& demand,
                               bool volumetric_fuel, int64_t continue_at)
    : spec_(spec),
      net_(net),
      default_vehicle_(default_emission_vehicle(demand, volumetric_fuel)),
      out_(continue_at < 0 ? OutputFile(spec.file)
                           : OutputFile(spec.file, static_cast<uint64_t>(continue_at))) {
  min_vehicle_length_ = std::numeric_limits<double>::max();
  for (float length : demand.types.length)
    if (length > 0) min_vehicle_length_ = std::min<double>(min_vehicle_length_, length);
  if (min_vehicle_length_ == std::numeric_limits<double>::max()) min_vehicle_length_ = 0;
  if (continue_at < 0) write_sumo_xml_header(out_, "meandata", "meandata_file.xsd");
}

MeanDataWriter::~MeanDataWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors must not throw; call close() to see write errors.
  }
}

void MeanDataWriter::write(const MeanDataInterval& interval) {
  if (interval.counters == nullptr || interval.counters->sampled_steps.size() != net_.num_lanes() ||
      (spec_.type == MeanDataType::Emissions && interval.counters->emission[0].size() != net_.num_lanes()))
    throw std::logic_error("MeanDataInterval: counters missing or not sized to the network's lanes");
  const double seconds = interval.end - interval.begin;
  if (!(seconds > 0)) throw std::logic_error("MeanDataInterval: end must be after begin");

  out_.text("    <interval");
  out_.attr_fixed("begin", interval.begin);
  out_.attr_fixed("end", interval.end);
  out_.attr("id", spec_.id);
  out_.text(">\n");
  for (uint32_t edge = 0; edge < net_.num_edges(); ++edge) {
    if (net_.edge_is_internal[edge] && !spec_.with_internal) continue;
    if (spec_.lane_level)
      write_lanes(interval, edge, seconds);
    else
      write_edge(interval, edge, seconds);
  }
  out_.text("    </interval>\n");
}

bool MeanDataWriter::empty(const MeanDataInterval& interval, uint32_t first, uint32_t lanes) const {
  if (spec_.type == MeanDataType::Emissions)
    return sum_emission_sums(*interval.counters, first, lanes).sampled_seconds == 0;
  return sum_lane_counters(*interval.counters, first, lanes, interval.step_length).empty();
}

void MeanDataWriter::write_entry(const MeanDataInterval& interval, uint32_t first, uint32_t lanes,
                                 double length, double speed_limit, double seconds) {
  if (spec_.type == MeanDataType::Emissions)
    return write_emission_values(out_, sum_emission_sums(*interval.counters, first, lanes), length,
                                 speed_limit, seconds, spec_.empty_defaults ? &default_vehicle_ : nullptr);
  write_values(sum_lane_counters(*interval.counters, first, lanes, interval.step_length), length, lanes,
               speed_limit, seconds);
}

void MeanDataWriter::write_edge(const MeanDataInterval& interval, uint32_t edge, double seconds) {
  const uint32_t first = net_.edge_first_lane[edge], lanes = net_.edge_num_lanes[edge];
  if (spec_.exclude_empty && empty(interval, first, lanes)) return;
  out_.text("        <edge");
  out_.attr("id", net_.edge_id[edge]);
  // SUMO's edge speed limit is its first lane's (what an emissions output's defaults read).
  const double speed_limit =
      spec_.type == MeanDataType::Emissions && lanes > 0 ? net_.lane_speed[first] : net_.edge_speed[edge];
  write_entry(interval, first, lanes, net_.edge_length[edge], speed_limit, seconds);
}

void MeanDataWriter::write_lanes(const MeanDataInterval& interval, uint32_t edge, double seconds) {
  const uint32_t first = net_.edge_first_lane[edge], lanes = net_.edge_num_lanes[edge];
  if (lanes == 0) return;
  bool any = !spec_.exclude_empty;
  for (uint32_t l = first; l < first + lanes && !any; ++l) any = !empty(interval, l, 1);
  if (!any) return;

  out_.text("        <edge");
  out_.attr("id", net_.edge_id[edge]);
  out_.text(">\n");
  for (uint32_t l = first; l < first + lanes; ++l) {
    if (spec_.exclude_empty && empty(interval, l, 1)) continue;
    out_.text("            <lane");
    out_.attr("id", net_.lane_id[l]);
    write_entry(interval, l, 1, net_.lane_length[l], net_.lane_speed[l], seconds);
  }
  out_.text("        </edge>\n");
}

void MeanDataWriter::write_values(const MeanDataTotals& t, double length, uint32_t lanes, double speed_limit,
                                  double seconds) {
  out_.attr_fixed("sampledSeconds", t.sampled_seconds);
  if (t.sampled_seconds > 0) {
    const MeanDataMeasures m = derive_mean_data(t, length, lanes, speed_limit, seconds, min_vehicle_length_);
    if (m.has_traveltime) out_.attr_fixed("traveltime", m.traveltime);
    out_.attr_fixed("overlapTraveltime", m.overlap_traveltime);
    out_.attr_fixed("density", m.density);
    out_.attr_fixed("laneDensity", m.lane_density);
    out_.attr_fixed("occupancy", m.occupancy);
    out_.attr_fixed("waitingTime", t.waiting_seconds);
    out_.attr_fixed("timeLoss", t.time_loss_seconds);
    out_.attr_fixed("speed", m.speed);
    out_.attr_fixed("speedRelative", m.speed_relative);
  }
  out_.attr_int("departed", t.departed);
  out_.attr_int("arrived", t.arrived);
  out_.attr_int("entered", t.entered);
  out_.attr_int("left", t.left);
  // LaneCounters has no lane-change counts yet.
  out_.text(" laneChangedFrom=\"0\" laneChangedTo=\"0\"/>\n");
}

void MeanDataWriter::close() {
  if (!out_.is_open()) return;
  out_.text("</meandata>\n");
  out_.close();
}

}  // namespace lpsim

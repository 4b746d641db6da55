#include "app/snapshot.hpp"

#include <zlib.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <type_traits>

namespace lpsim {

namespace {

constexpr char kMagic[8] = {'L', 'P', 'S', 'I', 'M', 'S', 'N', 'P'};

struct Writer {
  std::string buf;
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    buf.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void field(std::string& s) {
    pod<uint64_t>(s.size());
    buf.append(s);
  }
  template <class T>
  void field(T& v) requires std::is_arithmetic_v<T> || std::is_enum_v<T> {
    pod(v);
  }
  void field(Point& p) { pod(p); }
  void field(SourceLoc& l) {
    field(l.file);
    pod(l.line);
  }
  template <class T>
  void field(std::vector<T>& v) {
    pod<uint64_t>(v.size());
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      buf.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    } else {
      for (auto& x : v) field(x);
    }
  }
  template <class K, class V>
  void field(std::map<K, V>& m) {
    pod<uint64_t>(m.size());
    for (auto& [k, v] : m) {
      K key = k;
      field(key);
      field(v);
    }
  }
};

struct Reader {
  const char* p;
  const char* end;
  std::string path;

  void need(uint64_t n) {
    if (static_cast<uint64_t>(end - p) < n) throw InputError(SourceLoc{path, 0}, "snapshot is truncated");
  }
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, p, sizeof(T));
    p += sizeof(T);
    return v;
  }
  void field(std::string& s) {
    auto n = pod<uint64_t>();
    need(n);
    s.assign(p, n);
    p += n;
  }
  template <class T>
  void field(T& v) requires std::is_arithmetic_v<T> || std::is_enum_v<T> {
    v = pod<T>();
  }
  void field(Point& pt) { pt = pod<Point>(); }
  void field(SourceLoc& l) {
    field(l.file);
    l.line = pod<int>();
  }
  template <class T>
  void field(std::vector<T>& v) {
    auto n = pod<uint64_t>();
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      need(n * sizeof(T));
      v.resize(n);
      if (n > 0) std::memcpy(v.data(), p, n * sizeof(T));  // an empty vector's data() may be null
      p += n * sizeof(T);
    } else {
      if (n > static_cast<uint64_t>(end - p)) throw InputError(SourceLoc{path, 0}, "snapshot is truncated");
      v.resize(n);
      for (auto& x : v) field(x);
    }
  }
  template <class K, class V>
  void field(std::map<K, V>& m) {
    auto n = pod<uint64_t>();
    for (uint64_t i = 0; i < n; ++i) {
      K k;
      V v;
      field(k);
      field(v);
      m.emplace(std::move(k), std::move(v));
    }
  }
};

// Every persisted field is listed once here; writing and reading walk the same list.
template <class IO>
void visit(IO& io, Network& n) {
  io.field(n.edge_id), io.field(n.edge_first_lane), io.field(n.edge_num_lanes);
  io.field(n.edge_from_junction), io.field(n.edge_to_junction), io.field(n.edge_is_internal);
  io.field(n.edge_length), io.field(n.edge_speed), io.field(n.edge_priority);
  io.field(n.lane_id), io.field(n.lane_edge), io.field(n.lane_index), io.field(n.lane_length);
  io.field(n.lane_speed), io.field(n.lane_cell_begin), io.field(n.lane_conn_begin);
  io.field(n.lane_shape_begin), io.field(n.shape_x), io.field(n.shape_y);
  io.field(n.conn_from_lane), io.field(n.conn_to_lane), io.field(n.conn_via_lane), io.field(n.conn_to_edge);
  io.field(n.conn_signal), io.field(n.conn_link_index), io.field(n.conn_state), io.field(n.conn_dir);
  io.field(n.conn_junction), io.field(n.conn_foe_begin), io.field(n.conn_foe);
  io.field(n.conn_keep_clear);
  io.field(n.junction_id), io.field(n.junction_type), io.field(n.junction_x), io.field(n.junction_y);
  io.field(n.signal_id), io.field(n.signal_program), io.field(n.signal_actuated), io.field(n.signal_offset);
  io.field(n.signal_phase_begin), io.field(n.phase_duration), io.field(n.phase_min_dur);
  io.field(n.phase_max_dur), io.field(n.phase_state_begin), io.field(n.phase_state);
  io.field(n.signal_max_gap), io.field(n.signal_detector_gap), io.field(n.signal_passing_time);
  io.field(n.signal_det_begin), io.field(n.det_lane), io.field(n.det_pos), io.field(n.phase_det_begin);
  io.field(n.phase_det);
  io.field(n.roundabout_edges), io.field(n.edge_other_lanes), io.field(n.edge_other_lane_speeds);
  io.field(n.skipped_non_car_lanes), io.field(n.skipped_connections), io.field(n.net_offset);
  io.field(n.edge_succ_begin), io.field(n.edge_succ), io.field(n.edge_succ_permissions);
  io.field(n.lane_permissions), io.field(n.edge_permissions);
  io.field(n.lane_restriction_begin), io.field(n.restriction_vclass), io.field(n.restriction_speed);
}

template <class IO>
void visit(IO& io, VehicleTypes& t) {
  io.field(t.id), io.field(t.length), io.field(t.min_gap), io.field(t.accel), io.field(t.decel);
  io.field(t.emergency_decel), io.field(t.max_speed), io.field(t.desired_max_speed), io.field(t.speed_factor);
  io.field(t.speed_dev);
  io.field(t.tau), io.field(t.sigma), io.field(t.delta), io.field(t.vclass), io.field(t.car_follow_model);
  io.field(t.model);
  io.field(t.vclass_mask);
  io.field(t.emission_class), io.field(t.emission_model), io.field(t.emission_coeff), io.field(t.coast_incl);
  io.field(t.coast_mass_term), io.field(t.fuel_density), io.field(t.shut_off_stop), io.field(t.loc);
}

template <class IO>
void visit(IO& io, Demand::Skipped& s) {
  io.field(s.id), io.field(s.reason), io.field(s.loc);
}

template <class IO>
void visit(IO& io, Demand& d) {
  visit(io, d.types);
  io.field(d.vehicle_id), io.field(d.vehicle_type), io.field(d.depart), io.field(d.route_begin);
  io.field(d.route_length), io.field(d.speed_factor), io.field(d.source), io.field(d.depart_lane_kind);
  io.field(d.depart_lane), io.field(d.depart_pos_kind), io.field(d.depart_pos), io.field(d.depart_speed_kind);
  io.field(d.depart_speed), io.field(d.arrival_pos_kind), io.field(d.arrival_pos), io.field(d.route_edges);
  io.field(d.stops.vehicle_begin), io.field(d.stops.route_pos), io.field(d.stops.lane);
  io.field(d.stops.start_pos), io.field(d.stops.end_pos), io.field(d.stops.duration), io.field(d.stops.until);
  io.field(d.rerouting), io.field(d.via_begin), io.field(d.via_edges);
  uint64_t n = d.unroutable.size();
  io.field(n);
  d.unroutable.resize(n);
  for (auto& s : d.unroutable) visit(io, s);
  io.field(d.unsupported);
  io.field(d.routing.vehicles), io.field(d.routing.requests);  // not the time: snapshots are deterministic
}

template <class IO>
void visit(IO& io, MeanDataSpec& m) {
  io.field(m.id), io.field(m.file), io.field(m.lane_level), io.field(m.period), io.field(m.begin);
  io.field(m.end), io.field(m.exclude_empty), io.field(m.with_internal), io.field(m.loc), io.field(m.type);
  io.field(m.empty_defaults);
}

template <class IO>
void visit(IO& io, Scenario& s) {
  visit(io, s.network);
  visit(io, s.demand);
  uint64_t n = s.mean_data.size();
  io.field(n);
  s.mean_data.resize(n);
  for (auto& m : s.mean_data) visit(io, m);
}

template <class Map>
void index_names(const std::vector<std::string>& names, Map& map) {
  map.clear();
  map.reserve(names.size());
  for (uint32_t i = 0; i < names.size(); ++i) map.emplace(names[i], i);
}

}  // namespace

void write_snapshot(const Scenario& scenario, const std::string& path) {
  Writer w;
  visit(w, const_cast<Scenario&>(scenario));  // the writer only reads
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(SourceLoc{path, 0}, "cannot write snapshot");
  uint32_t version = kSnapshotVersion;
  uint64_t size = w.buf.size();
  uint32_t crc =
      static_cast<uint32_t>(crc32_z(0, reinterpret_cast<const Bytef*>(w.buf.data()), w.buf.size()));
  out.write(kMagic, sizeof kMagic);
  out.write(reinterpret_cast<const char*>(&version), sizeof version);
  out.write(reinterpret_cast<const char*>(&size), sizeof size);
  out.write(reinterpret_cast<const char*>(&crc), sizeof crc);
  out.write(w.buf.data(), static_cast<std::streamsize>(w.buf.size()));
  if (!out.flush()) throw InputError(SourceLoc{path, 0}, "writing snapshot failed (disk full?)");
}

bool is_snapshot(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof kMagic] = {};
  return in.read(magic, sizeof magic) && std::memcmp(magic, kMagic, sizeof kMagic) == 0;
}

Scenario read_snapshot(const std::string& path) {
  auto t0 = std::chrono::steady_clock::now();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(SourceLoc{path, 0}, "cannot open snapshot (missing?)");
  const auto file_size = static_cast<uint64_t>(in.tellg());
  in.seekg(0);
  constexpr uint64_t header = sizeof kMagic + sizeof(uint32_t) + sizeof(uint64_t) + sizeof(uint32_t);
  if (file_size < header) throw InputError(SourceLoc{path, 0}, "not an LPSim snapshot (too short)");
  char magic[sizeof kMagic];
  uint32_t version = 0, crc = 0;
  uint64_t size = 0;
  in.read(magic, sizeof magic);
  in.read(reinterpret_cast<char*>(&version), sizeof version);
  in.read(reinterpret_cast<char*>(&size), sizeof size);
  in.read(reinterpret_cast<char*>(&crc), sizeof crc);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(SourceLoc{path, 0}, "not an LPSim snapshot");
  if (version != kSnapshotVersion)
    throw InputError(SourceLoc{path, 0}, "snapshot format version " + std::to_string(version) +
                                             ", this lpsim reads " + std::to_string(kSnapshotVersion) +
                                             ": convert again");
  if (size != file_size - header)
    throw InputError(SourceLoc{path, 0}, "snapshot is truncated or has trailing bytes (payload " +
                                             std::to_string(file_size - header) + " of " +
                                             std::to_string(size) + ")");
  std::string buf(size, '\0');
  in.read(buf.data(), static_cast<std::streamsize>(size));
  if (static_cast<uint32_t>(crc32_z(0, reinterpret_cast<const Bytef*>(buf.data()), buf.size())) != crc)
    throw InputError(SourceLoc{path, 0}, "snapshot checksum mismatch (corrupted file)");

  Scenario sc;
  Reader r{buf.data(), buf.data() + buf.size(), path};
  visit(r, sc);
  if (r.p != r.end) throw InputError(SourceLoc{path, 0}, "snapshot has unread bytes (inconsistent format)");
  Network& n = sc.network;
  index_names(n.edge_id, n.edge_index);
  index_names(n.lane_id, n.lane_index_by_id);
  index_names(n.junction_id, n.junction_index);
  index_names(n.signal_id, n.signal_index);
  index_names(sc.demand.types.id, sc.demand.types.index);
  sc.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sc;
}

}  // namespace lpsim

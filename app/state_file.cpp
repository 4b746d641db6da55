#include "app/state_file.hpp"

#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "core/fnv_hash.hpp"
#include "engine/part_link.hpp"

namespace lpsim {

namespace {

constexpr char kMagic[8] = {'L', 'P', 'S', 'I', 'M', 'S', 'T', '\0'};
constexpr uint32_t kFormatVersion = 6;  // 6: a link saves the current map's foreign footprints only

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t layout;  // the sizes of the plain values the payload holds, hashed
  uint64_t digest;
  uint64_t payload_bytes;  // as the run reads it
  uint64_t stored_bytes;   // as the file holds it (deflated)
  uint32_t crc;            // of the payload as the run reads it
  uint32_t reserved;
};

// Deflate's fastest level: on the regional snapshot's state (4.1 MB) its file is 7 % larger than the default
// level's and takes a third of its time (52 against 145 ms), as saving a large run must stay cheap.
constexpr int kDeflateLevel = Z_BEST_SPEED;

uint32_t layout() {
  Fnv f;
  for (const size_t s : {sizeof(VehicleView), sizeof(TripRecord), sizeof(TripCounters), sizeof(RunCounts),
                         sizeof(TeleportEvent), sizeof(LaneApproach), sizeof(SlotInit), sizeof(StepParams),
                         sizeof(PartStats), sizeof(FootprintWrite)})
    f.value(uint64_t{s});
  return static_cast<uint32_t>(f.get() ^ (f.get() >> 32));
}

uint32_t crc_of(const std::vector<uint8_t>& payload) {
  return static_cast<uint32_t>(crc32_z(0, reinterpret_cast<const Bytef*>(payload.data()), payload.size()));
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw InputError(SourceLoc{path, 0}, "not a state of this run: " + why);
}

}  // namespace

uint64_t scenario_digest(const Scenario& sc, const SimulationOptions& o) {
  Fnv f;
  const Network& n = sc.network;
  f.value(n.num_lanes());
  f.value(n.num_edges());
  f.value(n.num_cells());
  f.array(n.lane_length);
  f.array(n.lane_speed);
  f.array(n.conn_to_lane);
  for (const std::string& id : n.edge_id) f.text(id);
  const Demand& d = sc.demand;
  f.value(d.size());
  f.array(d.depart);
  f.array(d.vehicle_type);
  f.array(d.route_begin);
  f.array(d.route_edges);
  f.array(d.types.max_speed);
  for (const std::string& id : d.vehicle_id) f.text(id);
  f.value(o.begin);
  f.value(o.step_ms);
  f.value(o.seed);
  f.value(o.time_to_teleport);
  f.value(o.time_to_teleport_highways);
  f.value(o.highway_min_speed);
  f.value(o.time_to_impatience);
  f.value(o.max_depart_delay);
  f.value(o.ignore_junction_blocker);
  f.value(o.lane_counters);
  f.value(o.emission_sums);
  f.value(o.volumetric_fuel);
  f.value(o.rerouting.adaptation_interval_ms);
  f.value(o.rerouting.adaptation_steps);
  f.value(o.rerouting.period_ms);
  f.value(o.rerouting.pre_period_ms);
  return f.get();
}

void write_state_file(const std::string& path, uint64_t digest, const std::vector<uint8_t>& payload) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kFormatVersion;
  h.layout = layout();
  h.digest = digest;
  h.payload_bytes = payload.size();
  h.crc = crc_of(payload);
  std::vector<uint8_t> stored(compressBound(payload.size()));
  uLongf stored_bytes = stored.size();
  if (compress2(stored.data(), &stored_bytes, payload.data(), payload.size(), kDeflateLevel) != Z_OK)
    throw InputError(SourceLoc{path, 0}, "cannot compress the state (out of memory)");
  h.stored_bytes = stored_bytes;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(reinterpret_cast<const char*>(stored.data()), static_cast<std::streamsize>(stored_bytes));
    out.close();
    if (!out) throw InputError(SourceLoc{path, 0}, "cannot write the state file");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw InputError(SourceLoc{path, 0}, "cannot write the state file (renaming " + tmp + ")");
}

std::vector<uint8_t> read_state_file(const std::string& path, uint64_t digest) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLoc{path, 0}, "cannot read the state file");
  Header h{};
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  if (in.gcount() != static_cast<std::streamsize>(sizeof h) ||
      std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    refuse(path, "not an LPSim state file");
  if (h.version != kFormatVersion)
    refuse(path, "format version " + std::to_string(h.version) + ", this lpsim reads version " +
                     std::to_string(kFormatVersion));
  if (h.layout != layout())
    refuse(path, "written by an lpsim of another build (its values are laid out otherwise)");
  if (h.digest != digest)
    refuse(path,
           "saved from another scenario or with other options (network, demand, step length, seed, "
           "begin, teleport or rerouting options or edgeData outputs differ)");
  in.seekg(0, std::ios::end);
  const auto file_bytes = static_cast<uint64_t>(in.tellg());
  if (file_bytes < sizeof h + h.stored_bytes) refuse(path, "the file is truncated");
  if (file_bytes > sizeof h + h.stored_bytes) refuse(path, "bytes after the state's end");
  // A deflated stream expands at most about 1000-fold: a larger claim is a corrupted header.
  if (h.payload_bytes / 1032 > h.stored_bytes + 1)
    refuse(path, "the file is corrupted (its lengths do not match)");
  std::vector<uint8_t> stored(h.stored_bytes);
  in.seekg(sizeof h);
  in.read(reinterpret_cast<char*>(stored.data()), static_cast<std::streamsize>(stored.size()));
  if (static_cast<uint64_t>(in.gcount()) != h.stored_bytes) refuse(path, "the file is truncated");
  std::vector<uint8_t> payload(h.payload_bytes);
  uLongf payload_bytes = payload.size();
  if (uncompress(payload.data(), &payload_bytes, stored.data(), stored.size()) != Z_OK ||
      payload_bytes != h.payload_bytes || crc_of(payload) != h.crc)
    refuse(path, "the file is corrupted (it does not inflate to its checksum)");
  return payload;
}

}  // namespace lpsim

#pragma once
// The one list of a backend's run state (Stepper::save_state, load_state): the tables a step reads that an
// earlier step wrote, in the order a state holds them after the index of the lane map they are in, and then
// the vehicle columns of the slots in use. Both backends visit their own storage with it (host vectors,
// device arrays), and BackendState holds a saved one on the host, so that a state can be taken apart and put
// together again without a backend (a partitioned run's state re-cut for other parts).
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "backends/host_columns.hpp"
#include "backends/state_bytes.hpp"

namespace lpsim {

/// How a table is kept in a state: whole, as mostly zeros, as mostly all ones (a lane's "none",
/// kNoJunctionStand), or the active list, whose length is the number of active slots.
enum class Kept : uint8_t { kWhole, kSparse, kSparseNone, kActive };

/// A backend's table as a pointer and a length (host or device memory).
template <class T>
struct TableSpan {
  T* data = nullptr;
  uint64_t size = 0;
};

template <class T>
using HostTable = std::vector<T>;

/// The tables of a backend's run state, each an S<element>: TableSpan in a backend, HostTable on the host.
template <template <class> class S>
struct BackendTables {
  S<uint8_t> map;  // the lane map the last step wrote, with its padding
  S<char> link_state;
  S<int64_t> signal_next_switch_ms;
  S<int32_t> actuated_phase;
  S<int64_t> actuated_start_ms;
  S<int64_t> det_last_ms;
  S<int64_t> lane_records;     // kNumTrafficCounters per lane; empty without lane counters
  S<int64_t> emission_sums;    // kNumEmissionSums per lane; empty without emission sums
  S<uint32_t> junction_stand;  // per lane, of the lane map the last step wrote; empty unless tracked
  S<uint32_t> active;          // the slots the passes visit, ascending
};

/// table(t.<name>, kept) for each table, in the order a state holds them. Everything else a step writes
/// before it reads it: the other lane map and junction stands are cleared of what they held (the footprints
/// and stands of one step before) before the step writes them; the claims and merge requests, and the
/// approaches, count only in the step that wrote them (the step in their key).
template <class Tables, class Table>
void visit_backend_tables(Tables& t, Table&& table) {
  table(t.map, Kept::kSparse);
  table(t.link_state, Kept::kWhole);
  table(t.signal_next_switch_ms, Kept::kWhole);
  table(t.actuated_phase, Kept::kWhole);
  table(t.actuated_start_ms, Kept::kWhole);
  table(t.det_last_ms, Kept::kWhole);
  table(t.lane_records, Kept::kSparse);
  table(t.emission_sums, Kept::kSparse);
  table(t.junction_stand, Kept::kSparseNone);
  table(t.active, Kept::kActive);
}

/// Appends n elements at `data`, kept as `kept` says.
template <class T>
void put_table(StateBytesOut& out, const T* data, uint64_t n, Kept kept) {
  if (kept == Kept::kSparse)
    out.sparse(data, n);
  else if (kept == Kept::kSparseNone)
    out.sparse(data, n, static_cast<T>(~T{}));
  else
    out.array(data, n);
}

/// Reads exactly n elements into `data` (a table whose length the backend's setup fixes).
template <class T>
void get_table(StateBytesIn& in, T* data, uint64_t n, Kept kept) {
  if (kept == Kept::kSparse)
    in.sparse(data, n);
  else if (kept == Kept::kSparseNone)
    in.sparse(data, n, static_cast<T>(~T{}));
  else
    in.array(data, n);
}

/// Reads a table of the saved length into `v`.
template <class T>
void get_table(StateBytesIn& in, std::vector<T>& v, Kept kept) {
  v.resize(in.next_length());
  get_table(in, v.data(), v.size(), kept);
}

/// A backend's saved run state on the host.
struct BackendState {
  int32_t map_index = 0;  // the lane map the state is in
  BackendTables<HostTable> tables;
  uint32_t num_slots = 0;  // slots whose columns the state holds
  HostVehicleColumns vehicles;
};

/// `state` (Stepper::save_state's bytes of a run with `num_slots` slots in use) into `out`.
inline void decode_backend_state(const std::vector<uint8_t>& state, uint32_t num_slots, BackendState& out) {
  StateBytesIn in(state);
  in.value(out.map_index);
  visit_backend_tables(out.tables, [&](auto& v, Kept kept) { get_table(in, v, kept); });
  out.num_slots = num_slots;
  out.vehicles.reserve(num_slots, false);
  visit_vehicle_columns([&](uint32_t per, auto*& c) { in.array(c, uint64_t{num_slots} * per); },
                        out.vehicles.view());
  if (!in.done()) throw std::runtime_error("backend state: bytes left after its last array");
}

/// The bytes Stepper::load_state reads.
inline std::vector<uint8_t> encode_backend_state(BackendState& s) {
  StateBytesOut out;
  out.value(s.map_index);
  visit_backend_tables(s.tables, [&](auto& v, Kept kept) { put_table(out, v.data(), v.size(), kept); });
  visit_vehicle_columns([&](uint32_t per, auto*& c) { out.array(c, uint64_t{s.num_slots} * per); },
                        s.vehicles.view());
  return std::move(out.bytes());
}

}  // namespace lpsim

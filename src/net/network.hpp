#pragma once
// The network as the engine sees it: dense tables in structure-of-arrays form, built once from a NetSpec
// by network_builder. Every lane some vehicle may use is present (sidewalks, crossings and walking areas are
// not); each carries the vClasses allowed on it (core/vclass.hpp). Every lane (normal and internal
// junction lanes) owns a contiguous run of 1-metre cells in one lane map; no padding between lanes.
//
// Index conventions: edges, lanes, connections, junctions and signals are numbered densely from 0 in the
// order of the source file. -1 (kNone) marks "none" in int32 fields.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/net_spec.hpp"

namespace lpsim {

inline constexpr int32_t kNone = -1;

enum class JunctionType : uint8_t {
  Priority,
  TrafficLight,
  RightBeforeLeft,
  AllwayStop,
  PriorityStop,
  Zipper,
  DeadEnd,
  Internal,
  Unregulated,
  Other
};

struct Network {
  // --- edges (normal and internal) ---
  std::vector<std::string> edge_id;
  std::vector<uint32_t> edge_first_lane;  // lanes of an edge are contiguous, ordered by SUMO index
  std::vector<uint8_t> edge_num_lanes;    // vehicle lanes only; 0 if the edge has none
  std::vector<int32_t> edge_from_junction, edge_to_junction;  // kNone for internal edges
  std::vector<uint8_t> edge_is_internal;
  std::vector<float> edge_length;          // m (length of its first lane)
  std::vector<float> edge_speed;           // m/s, max over its lanes (as SUMO's edge speed)
  std::vector<uint32_t> edge_permissions;  // vClasses some lane of the edge allows (union of its lanes')
  std::vector<int32_t> edge_priority;
  // The lanes of an edge left out of the lane tables (sidewalks, rail): how many, and their speed limits'
  // sum (m/s). SUMO's mean speed of an edge, which its rerouting device averages, counts them as empty lanes.
  std::vector<uint8_t> edge_other_lanes;
  std::vector<float> edge_other_lane_speeds;

  // --- lanes (vehicle lanes only) ---
  std::vector<std::string> lane_id;
  std::vector<uint32_t> lane_edge;
  std::vector<uint8_t> lane_index;         // SUMO lane index within its edge
  std::vector<float> lane_length;          // m
  std::vector<float> lane_speed;           // m/s
  std::vector<uint32_t> lane_permissions;  // vClass mask of the lane (core/vclass.hpp)
  // Speed limits by vehicle class from the edge's type (<restriction>): CSR [begin[l], begin[l+1]) in
  // restriction_vclass (a vehicle's vClass mask, matched exactly) and restriction_speed (m/s); size lanes+1.
  std::vector<uint32_t> lane_restriction_begin;
  std::vector<uint32_t> restriction_vclass;
  std::vector<float> restriction_speed;
  std::vector<uint64_t> lane_cell_begin;   // first cell in the lane map; size lanes+1 (last = total cells)
  std::vector<uint32_t> lane_conn_begin;   // outgoing connections [begin[l], begin[l+1]); size lanes+1
  std::vector<uint32_t> lane_shape_begin;  // points [begin[l], begin[l+1]) in shape_x/shape_y; size lanes+1
  std::vector<float> shape_x, shape_y;     // lane shapes, net coordinates

  // --- connections: lane-to-lane links, grouped by from_lane (CSR via lane_conn_begin) ---
  std::vector<uint32_t> conn_from_lane, conn_to_lane;
  std::vector<int32_t> conn_via_lane;  // internal lane the vehicle crosses, kNone if direct
  std::vector<uint32_t> conn_to_edge;
  std::vector<int32_t> conn_signal;      // index into signals, kNone if not signal controlled
  std::vector<int16_t> conn_link_index;  // link index within the signal program, -1 if none
  std::vector<char> conn_state;          // SUMO connection state: M m = s w o O Z ...
  std::vector<char> conn_dir;            // s l r t L R
  std::vector<int32_t> conn_junction;    // junction crossed, kNone if unknown
  // Right of way: the connections each connection must yield to (from the junction's <request> rows),
  // CSR [conn_foe_begin[c], conn_foe_begin[c+1]) in conn_foe. Filled by build_junction_foes.
  std::vector<uint32_t> conn_foe_begin, conn_foe;
  // 1: a vehicle enters the link only when it could leave the junction (SUMO's MSVehicle::keepClear: the
  // connection's keepClear, a link with foes in its junction's <request> row, not from a roundabout edge).
  // Junctions without request rows (nets from CSV) keep every link's keepClear.
  std::vector<uint8_t> conn_keep_clear;

  // --- junctions ---
  std::vector<std::string> junction_id;
  std::vector<JunctionType> junction_type;
  std::vector<float> junction_x, junction_y;

  // --- signals: one program per traffic light (the one in force: add-files replace the net's) ---
  std::vector<std::string> signal_id, signal_program;
  std::vector<uint8_t> signal_actuated;  // type actuated: gap control (other types run static)
  std::vector<float> signal_max_gap, signal_detector_gap, signal_passing_time;  // s, actuated params
  std::vector<float> signal_offset;                                             // s
  std::vector<uint32_t> signal_phase_begin;         // phases [begin[s], begin[s+1]); size signals+1
  std::vector<float> phase_duration;                // s
  std::vector<float> phase_min_dur, phase_max_dur;  // -1 when not given
  std::vector<uint32_t> phase_state_begin;          // chars [begin[p], begin[p]+signal_links) in phase_state
  std::vector<char> phase_state;                    // r y g G s u o O per link index

  // --- actuated signals' induction loops, placed as SUMO places them (actuated_detectors.cpp) ---
  std::vector<uint32_t> signal_det_begin;            // loops [begin[s], begin[s+1]); size signals+1
  std::vector<uint32_t> det_lane;                    // lane the loop lies on (upstream of short approaches)
  std::vector<float> det_pos;                        // m from that lane's start
  std::vector<uint32_t> phase_det_begin, phase_det;  // loops that may extend each phase; size phases+1

  // --- roundabouts (kept for priority rules) ---
  std::vector<std::vector<uint32_t>> roundabout_edges;

  // --- provenance ---
  int64_t skipped_non_car_lanes = 0;
  int64_t skipped_connections = 0;  // connections touching a non-car lane
  Point net_offset;

  // --- lookups (built by the builder) ---
  std::unordered_map<std::string, uint32_t> edge_index, lane_index_by_id, junction_index, signal_index;
  // Lanes of normal edges that no road vehicle may use (sidewalks, rail, tram tracks), left out of the lane
  // tables: each id with its edge, so that a stopping place or stop on one is told from an unknown lane.
  // Not kept in snapshots (only the demand builder reads it).
  std::unordered_map<std::string, uint32_t> left_out_lane_edge;

  uint32_t num_edges() const { return static_cast<uint32_t>(edge_id.size()); }
  uint32_t num_lanes() const { return static_cast<uint32_t>(lane_id.size()); }
  uint32_t num_connections() const { return static_cast<uint32_t>(conn_from_lane.size()); }
  uint32_t num_junctions() const { return static_cast<uint32_t>(junction_id.size()); }
  uint32_t num_signals() const { return static_cast<uint32_t>(signal_id.size()); }
  uint64_t num_cells() const { return lane_cell_begin.empty() ? 0 : lane_cell_begin.back(); }

  /// Edges a vehicle may drive next from `edge` (some lane of `edge` connects to some lane of it).
  /// CSR built by the builder: successors [edge_succ_begin[e], edge_succ_begin[e+1]) in edge_succ.
  /// edge_succ_permissions: per entry, the vClasses that can make that move (allowed on a from-lane, on
  /// every internal lane crossed and on the to-lane).
  std::vector<uint32_t> edge_succ_begin, edge_succ, edge_succ_permissions;
  /// Whether a vehicle of class mask `vclass` can drive from `from_edge` onto `to_edge` (any class: default).
  bool connected(uint32_t from_edge, uint32_t to_edge, uint32_t vclass = kAllVClasses) const;

  /// Lane-km of normal (non-internal) vehicle lanes.
  double lane_km() const;
  /// Length of the shape segment from point i-1 to point i of shape_x/shape_y [m], in double precision.
  double shape_segment_length(uint32_t i) const;
};

/// Frees the name lookups (edge_index ... signal_index): a process that resolves no more names after loading
/// (an MPI rank other than 0, which writes no outputs) need not keep them.
void release_name_indexes(Network& net);

}  // namespace lpsim

#pragma once
// Plain description of a road network as read from a file (SUMO .net.xml or the original LPSim CSV).
// Readers in converters/ fill it; src/net/network_builder turns it into the lane-map layout. Ids stay strings
// here; the builder maps them to dense indices.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/vclass.hpp"

namespace lpsim {

struct Point {
  double x = 0, y = 0;
};

struct LaneSpec {
  std::string id;
  int index = 0;
  double speed = 13.89;                 // m/s
  double length = 0;                    // m
  std::string allow, disallow;          // SUMO vClass lists, as written
  uint32_t permissions = kAllVClasses;  // vClass mask resolved by the reader from allow/disallow
  std::vector<Point> shape;
  SourceLoc loc;
};

enum class EdgeFunction : uint8_t { Normal, Internal, Connector, Crossing, WalkingArea };

struct EdgeSpec {
  std::string id, from, to;  // from/to junction ids (empty for internal edges)
  EdgeFunction function = EdgeFunction::Normal;
  int priority = -1;
  std::string type;
  std::string bidi;             // the edge driven the other way on the same road (SUMO's bidi), or empty
  std::vector<LaneSpec> lanes;  // ordered by index
  SourceLoc loc;
};

struct JunctionSpec {
  std::string id, type;  // type as in SUMO: traffic_light, priority, right_before_left, allway_stop, ...
  double x = 0, y = 0;
  std::vector<std::string> inc_lanes, int_lanes;
  // <request> rows by junction link index: bit strings as SUMO writes them (link j at char n-1-j).
  std::vector<std::string> response, foes;
  SourceLoc loc;
};

struct ConnectionSpec {
  std::string from, to;  // edge ids
  int from_lane = 0, to_lane = 0;
  std::string via;  // internal lane id, empty if none
  std::string tl;   // traffic light id, empty if none
  int link_index = -1;
  char dir = 's';          // s,t,l,r,L,R; 'T' also stands for SUMO's "invalid"
  char state = 'M';        // M,m,=,o,O,s,w,Z,...
  bool keep_clear = true;  // keepClear: vehicles do not enter the junction while they could not leave it
  SourceLoc loc;
};

struct PhaseSpec {
  double duration = 0;
  std::string state;
  double min_dur = -1, max_dur = -1;  // -1: not given
  std::string name;
  SourceLoc loc;  // its own line: a phase whose state is too short is blamed there
};

struct TlLogicSpec {
  std::string id, program_id, type = "static";  // static, actuated, delay_based, ...
  double offset = 0;
  std::vector<PhaseSpec> phases;
  std::vector<std::pair<std::string, std::string>> params;  // <param key value>, in file order
  SourceLoc loc;
};

/// A speed limit one vehicle class keeps on the lanes of an edge type (<type><restriction vClass speed/>).
struct SpeedRestrictionSpec {
  uint32_t vclass = 0;  // the class's bit (core/vclass.hpp)
  double speed = 0;     // m/s
};

/// An edge type of the net (<type id>): what LPSim reads of it are its speed restrictions by vClass.
struct EdgeTypeSpec {
  std::string id;
  std::vector<SpeedRestrictionSpec> restrictions;
  SourceLoc loc;
};

struct RoundaboutSpec {
  std::vector<std::string> nodes, edges;
};

struct NetSpec {
  std::string source;  // file it came from
  std::vector<EdgeSpec> edges;
  std::vector<JunctionSpec> junctions;
  std::vector<ConnectionSpec> connections;
  std::vector<TlLogicSpec> tl_logics;
  std::vector<RoundaboutSpec> roundabouts;
  std::vector<EdgeTypeSpec> edge_types;  // <type> elements (the edges name theirs in EdgeSpec::type)
  Point net_offset;                      // <location netOffset>
  int64_t skipped_non_car_lanes = 0;     // lanes no vehicle may use (sidewalks, crossings, walking areas)
};

}  // namespace lpsim

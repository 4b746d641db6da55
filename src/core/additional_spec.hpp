#pragma once
// What add-files contribute besides demand: signal programs that replace the net's, and definitions of
// edgeData/laneData outputs kept for the output writers.
#include <cstdint>
#include <string>
#include <vector>

#include "core/net_spec.hpp"

namespace lpsim {

/// What an edgeData/laneData measures: traffic (type "", "traffic" or "performance") or exhaust emissions
/// (type "emissions", or "hbefa", SUMO's deprecated name for it).
enum class MeanDataType : uint8_t { Traffic, Emissions };

struct MeanDataSpec {
  std::string id, file;
  bool lane_level = false;  // laneData instead of edgeData
  double period = -1;       // 'period' or 'freq'; -1: one interval for the whole run
  double begin = -1, end = -1;
  bool exclude_empty = false;
  bool with_internal = false;
  SourceLoc loc;
  MeanDataType type = MeanDataType::Traffic;
  // excludeEmpty="defaults" on an emissions output: empty edges are written with the values of a default
  // vehicle driving through at the speed limit (a traffic output writes them as with "false").
  bool empty_defaults = false;
  bool hbefa_name = false;  // type="hbefa": SUMO warns that the name is deprecated (not kept in snapshots)
};

struct AdditionalSpec {
  std::vector<TlLogicSpec> tl_logics;  // replace the net's program with the same id
  std::vector<MeanDataSpec> mean_data;
};

}  // namespace lpsim

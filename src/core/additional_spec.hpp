#pragma once
// What add-files contribute besides demand: signal programs that replace the net's, and definitions of
// edgeData/laneData outputs kept for the output writers.
#include <string>
#include <vector>

#include "core/net_spec.hpp"

namespace lpsim {

struct MeanDataSpec {
  std::string id, file;
  bool lane_level = false;  // laneData instead of edgeData
  double period = -1;       // 'period' or 'freq'; -1: one interval for the whole run
  double begin = -1, end = -1;
  bool exclude_empty = false;
  bool with_internal = false;
  SourceLoc loc;
};

struct AdditionalSpec {
  std::vector<TlLogicSpec> tl_logics;  // replace the net's program with the same id
  std::vector<MeanDataSpec> mean_data;
};

}  // namespace lpsim

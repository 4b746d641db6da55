#pragma once
// A co-simulation corridor as read from its file: the edges SUMO simulates (converters/corridor_file.hpp
// says the format).
#include <string>
#include <vector>

#include "core/error.hpp"

namespace lpsim {

struct CorridorSpec {
  std::string file;
  struct Item {
    std::string id;     // an edge id, or a lane id (of the edge meant)
    bool lane = false;  // named as `lane:ID`
    int line = 0;
  };
  std::vector<Item> items;
  // Objects of other kinds in a sumo-gui selection (junction:, vehicle:, ...): kind -> how many.
  std::vector<std::pair<std::string, int>> other_kinds;
};

}  // namespace lpsim

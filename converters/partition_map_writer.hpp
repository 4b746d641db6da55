#pragma once
// A PNG map of a partitioned network (cairo): every lane drawn along its shape in its part's colour.
#include <stdint.h>

#include <string>
#include <vector>

#include "net/network.hpp"

namespace lpsim {

/// Writes the map of `net` with each lane in the colour of lane_part[lane] (kNone: grey), `width` pixels wide
/// (the height follows the network's aspect). A file that cannot be written is an InputError naming it.
void write_partition_map(const std::string& path, const Network& net, const std::vector<int32_t>& lane_part,
                         int32_t parts, int width = 2000);

}  // namespace lpsim

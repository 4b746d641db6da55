#pragma once
// The text `lpsim partition` prints: a table per part and the totals.
#include <string>

#include "partition/partition_summary.hpp"

namespace lpsim {

/// `title` first (method, seed, time), then one markdown row per part and a line of totals.
std::string describe_partition(const PartitionSummary& s, const std::string& title);

}  // namespace lpsim

#pragma once
// A partition file checked against the network it is used with.
#include <stdint.h>

#include <vector>

#include "core/partition_spec.hpp"
#include "net/network.hpp"
#include "partition/junction_graph.hpp"

namespace lpsim {

/// The part of each junction that `spec` gives: a junction takes the part of the roads that lead to it (they
/// must agree: a junction's approaches share one part), a junction no road leads to the part of its first
/// road out. InputError (file:line) for an edge the network lacks or that is internal, an edge listed twice,
/// a part outside 0..parts-1, a normal edge not listed, approaches of one junction in two parts, or (with
/// expected_parts > 0) a part count other than expected_parts.
std::vector<int32_t> resolve_partition(const PartitionSpec& spec, const Network& net, int32_t expected_parts);

/// The load an edgeData output at `path` measured on each edge of `net` (edges it lacks: none), and in
/// `*seconds` the time its intervals cover. InputError naming the file for an edge the network lacks (an
/// output of another scenario).
MeasuredLoad read_measured_load(const std::string& path, const Network& net, double* seconds);

}  // namespace lpsim

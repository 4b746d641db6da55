#include "app/partition_report.hpp"

#include <cstdio>

namespace lpsim {

std::string describe_partition(const PartitionSummary& s, const std::string& title) {
  std::string out = title + "\n\n";
  out +=
      "| part | junctions | lanes | lane-km | vehicle-steps | share | cut lanes in | cut lanes out | "
      "vehicles in | "
      "ghost lanes | cells (own + ghost) | neighbours |\n";
  out += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  int64_t total = 0;
  for (const auto& p : s.parts) total += p.vehicle_steps;
  char buf[320];
  for (size_t i = 0; i < s.parts.size(); ++i) {
    const PartSummary& p = s.parts[i];
    std::string nb;
    for (int32_t n : p.neighbours) {
      if (!nb.empty()) nb += ' ';
      nb += std::to_string(n);
    }
    std::snprintf(buf, sizeof buf,
                  "| %zu | %u | %u | %.1f | %lld | %.3f | %u | %u | %lld | %u | %llu + %llu | %s |\n", i,
                  p.junctions, p.lanes, p.lane_km, static_cast<long long>(p.vehicle_steps),
                  total > 0 ? static_cast<double>(p.vehicle_steps) / static_cast<double>(total) : 0.0,
                  p.cut_lanes_in, p.cut_lanes_out, static_cast<long long>(p.vehicles_in), p.ghost_lanes,
                  static_cast<unsigned long long>(p.cells), static_cast<unsigned long long>(p.ghost_cells),
                  nb.empty() ? "-" : nb.c_str());
    out += buf;
  }
  uint64_t ghost_cells = 0;
  for (const auto& p : s.parts) ghost_cells += p.ghost_cells;
  std::snprintf(
      buf, sizeof buf,
      "\nparts %zu, cut roads %lld, cut lanes %lld, ghost cells %llu, largest part %.3f of the network's "
      "cells, expected migrations %lld, imbalance %.3f (largest part's vehicle-steps over the mean)\n",
      s.parts.size(), static_cast<long long>(s.cut_roads), static_cast<long long>(s.cut_lanes),
      static_cast<unsigned long long>(ghost_cells), s.largest_share, static_cast<long long>(s.migrations),
      s.imbalance);
  out += buf;
  if (s.measured_migrations >= 0) {
    std::snprintf(buf, sizeof buf, "measured migrations %lld (vehicles of the run that entered a cut road)\n",
                  static_cast<long long>(s.measured_migrations));
    out += buf;
  }
  return out;
}

}  // namespace lpsim

// `lpsim partition`: splits a scenario's network into K parts (or summarizes a given partition file),
// writes the partition file, prints the table of parts and draws the map.
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/commands.hpp"
#include "app/output_paths.hpp"
#include "app/partition_report.hpp"
#include "app/partition_resolution.hpp"
#include "app/partitioned_parts.hpp"
#include "app/scenario_args.hpp"
#include "converters/partition_file.hpp"
#include "converters/partition_map_writer.hpp"
#include "core/error.hpp"
#include "partition/partition_method.hpp"
#include "partition/partition_summary.hpp"

namespace lpsim {

namespace {

// The map writer draws PNG only: another name would get PNG bytes under a misleading extension.
void refuse_non_png_map(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png")
    throw InputError("--map draws a PNG image: give a file name ending in .png, not '" + path + "'");
}

}  // namespace

int command_partition(const std::vector<std::string>& args) {
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config, CliCommand::Partition);
  refuse_overwrites(sc, CliCommand::Partition);
  const Network& net = sc.network;
  std::vector<int32_t> junction_part;
  int32_t k = config.parts;
  std::string title;
  refuse_split_options_without_parts(config);
  if (!config.partition_map.empty()) refuse_non_png_map(config.partition_map);
  auto write_map = [&](const std::vector<int32_t>& junction_part, int32_t parts) {
    if (!config.partition_map.empty())
      write_partition_map(config.partition_map, net,
                          lane_parts(net, edge_parts_from_junctions(net, junction_part)), parts);
  };
  if (!config.partition_file.empty()) {
    if (!config.output_file.empty())
      throw InputError("--partition-file summarizes a partition, -o writes a new one: give one of them");
    const PartitionSpec spec = read_partition_file(config.partition_file);
    junction_part = resolve_partition(spec, net, k);
    k = spec.parts;
    title = "partition " + config.partition_file + ": " + std::to_string(k) + " parts";
    write_map(junction_part, k);
  } else {
    if (k < 1) throw InputError("partition needs --parts K (the number of parts)");
    if (config.output_file.empty()) throw InputError("partition needs -o <partition file>");
    const PartitionMethod method = *partition_method_from_name(config.partition_method);
    const auto t0 = std::chrono::steady_clock::now();
    double measured_seconds = 0;
    const JunctionGraph g =
        config.partition_load_from.empty()
            ? build_junction_graph(net, sc.demand, config.step_length)
            : build_junction_graph(net,
                                   read_measured_load(config.partition_load_from, net, &measured_seconds),
                                   config.step_length);
    junction_part = partition_junctions(g, k, method, static_cast<uint64_t>(config.seed));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Before the partition file: a map that cannot be written leaves no half-done result behind.
    write_map(junction_part, k);
    const std::vector<int32_t> edge_part = edge_parts_from_junctions(net, junction_part);
    std::vector<std::string> ids;
    std::vector<int32_t> parts;
    for (uint32_t e = 0; e < net.num_edges(); ++e) {
      if (net.edge_is_internal[e]) continue;
      ids.push_back(net.edge_id[e]);
      parts.push_back(edge_part[e] >= 0 ? edge_part[e] : 0);
    }
    const std::string source = config.config_file.empty() ? config.net_file : config.config_file;
    write_partition_file(
        config.output_file,
        {"LPSim partition: each normal edge and its part (a road is in the part of the junction it "
         "leads to)",
         std::string("method ") + partition_method_name(method) + ", seed " + std::to_string(config.seed) +
             ", " + std::to_string(k) + " parts, scenario " + source},
        k, ids, parts);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f", seconds);
    title = std::string("partition ") + config.output_file + ": " + partition_method_name(method) + ", " +
            std::to_string(k) + " parts, seed " + std::to_string(config.seed) + ", " + buf +
            " s (graph and partitioner)";
  }
  PartitionSummary summary = summarize_partition(net, sc.demand, junction_part, k, config.step_length);
  if (!config.migrations_from.empty()) {
    double seconds = 0;
    add_measured_migrations(summary, net, junction_part,
                            read_measured_load(config.migrations_from, net, &seconds).entered);
  }
  std::fputs(describe_partition(summary, title).c_str(), stdout);
  return 0;
}

}  // namespace lpsim

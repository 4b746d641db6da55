#include "app/output_paths.hpp"

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace lpsim {

namespace {

namespace fs = std::filesystem;

struct NamedPath {
  std::string what;  // the option or element that names the file
  std::string path;
  SourceLoc loc;  // where it was named, when that is a file (edgeData/laneData in an add-file)
};

std::vector<NamedPath> inputs_of(const ConfigSpec& c) {
  std::vector<NamedPath> in;
  auto add = [&](const char* what, const std::string& path) {
    if (!path.empty()) in.push_back({what, path, {}});
  };
  add("-c (configuration-file)", c.config_file);
  add("the snapshot", c.snapshot_file);
  add("--net-file", c.net_file);
  for (const auto& f : c.route_files) add("--route-files", f);
  for (const auto& f : c.additional_files) add("--additional-files", f);
  add("--lpsim-nodes", c.lpsim_nodes_csv);
  add("--lpsim-edges", c.lpsim_edges_csv);
  add("--lpsim-od", c.lpsim_od_csv);
  add("--partition-file", c.partition_file);
  add("--migrations-from", c.migrations_from);
  add("--partition.load-from", c.partition_load_from);
  add("--corridor", c.corridor_file);
  return in;
}

std::vector<NamedPath> outputs_of(const Scenario& sc, CliCommand command) {
  std::vector<NamedPath> out;
  auto add = [&](const char* what, const std::string& path) {
    if (!path.empty()) out.push_back({what, path, {}});
  };
  const ConfigSpec& c = sc.config;
  if (command == CliCommand::Convert || command == CliCommand::Partition) add("-o (output)", c.output_file);
  if (command == CliCommand::Partition) add("--map", c.partition_map);
  if (command != CliCommand::Run && command != CliCommand::Cosim) return out;
  add("--fcd-output", c.outputs.fcd);
  add("--tripinfo-output", c.outputs.tripinfo);
  add("--summary-output", c.outputs.summary);
  add("--statistic-output", c.outputs.statistic);
  add("--edgedata-output", c.outputs.edgedata);
  add("--lanedata-output", c.outputs.lanedata);
  add("--jam-report", c.jam_report);
  for (const auto& m : sc.mean_data)
    if (!m.file.empty())
      out.push_back({std::string(m.lane_level ? "<laneData" : "<edgeData") + " id=\"" + m.id + "\"> file",
                     m.file, m.loc});
  // SUMO's side of each (the statistics and the jam report are LPSim's alone).
  if (command == CliCommand::Cosim) {
    const size_t lpsim_outputs = out.size();
    for (size_t i = 0; i < lpsim_outputs; ++i)
      if (out[i].what != "--statistic-output" && out[i].what != "--jam-report")
        out.push_back({"SUMO's side of " + out[i].what, sumo_side_path(out[i].path), out[i].loc});
  }
  return out;
}

// Whether two paths name one file. Existing files: same device and inode (hard links, symlinks, any
// spelling). Otherwise the absolute paths with symlinks of the existing part resolved and . and .. removed.
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ea, eb;
  if (fs::exists(a, ea) && fs::exists(b, eb)) {
    std::error_code e;
    const bool same = fs::equivalent(a, b, e);
    if (!e) return same;
  }
  std::error_code e1, e2;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, e1), e1);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, e2), e2);
  if (e1 || e2) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return ca == cb;
}

[[noreturn]] void refuse(const NamedPath& output, const NamedPath& other, const char* role) {
  const std::string what =
      "output " + output.what + " '" + output.path + "' is the same file as " + role + " " + other.what +
      " '" + other.path + "'; refusing to " +
      (std::string(role) == "input" ? "overwrite an input" : "write two outputs to one file");
  if (!output.loc.file.empty()) throw InputError(output.loc, what);
  throw InputError(what);
}

}  // namespace

std::string sumo_side_path(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / (std::string(kSumoSidePrefix) + p.filename().string())).string();
}

void refuse_overwrites(const Scenario& scenario, CliCommand command, const std::vector<ExtraOutput>& extra) {
  const std::vector<NamedPath> inputs = inputs_of(scenario.config);
  std::vector<NamedPath> outputs = outputs_of(scenario, command);
  for (const ExtraOutput& e : extra) outputs.push_back({e.what, e.path, {}});
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (const auto& in : inputs)
      if (same_file(outputs[i].path, in.path)) refuse(outputs[i], in, "input");
    for (size_t j = 0; j < i; ++j)
      if (same_file(outputs[i].path, outputs[j].path)) refuse(outputs[i], outputs[j], "output");
  }
}

}  // namespace lpsim

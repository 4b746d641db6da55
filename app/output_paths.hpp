#pragma once
// No output may overwrite an input or another output: checked once the scenario is loaded (the add-files'
// edgeData/laneData files are known only then) and before anything is written.
#include "app/scenario.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

/// In a co-simulation SUMO writes its side of each output beside LPSim's under this prefix of the file name
/// (SUMO's --output-prefix, which also covers the outputs its additional files and --sumo-args name).
inline constexpr const char* kSumoSidePrefix = "sumo.";

/// Where SUMO writes its side of an output of the co-simulation: "out/fcd.xml" -> "out/sumo.fcd.xml".
std::string sumo_side_path(const std::string& path);

/// An output named outside the scenario's options (a co-simulation's --sumo-args): what names it, its path.
struct ExtraOutput {
  std::string what, path;
};

/// Refuses with an InputError naming both options and paths an output of `command` (run: the SUMO outputs
/// and the add-files' edgeData/laneData files; cosim: those and SUMO's side of each, as sumo_side_path();
/// convert: -o), or one of `extra`, that is the same file as an input (the .sumocfg, net, route and
/// add-files, LPSim CSV files, the snapshot read) or as another output. "The same" survives spellings: ./x,
/// a/../x, symlinks, and for existing files hard links (same device and inode).
void refuse_overwrites(const Scenario& scenario, CliCommand command,
                       const std::vector<ExtraOutput>& extra = {});

}  // namespace lpsim

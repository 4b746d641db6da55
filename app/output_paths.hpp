#pragma once
// No output may overwrite an input or another output: checked once the scenario is loaded (the add-files'
// edgeData/laneData files are known only then) and before anything is written.
#include "app/scenario.hpp"
#include "converters/cli_options.hpp"

namespace lpsim {

/// Refuses with an InputError naming both options and paths an output of `command` (run: the SUMO outputs
/// and the add-files' edgeData/laneData files; convert: -o) that is the same file as an input (the .sumocfg,
/// net, route and add-files, LPSim CSV files, the snapshot read) or as another output. "The same" survives
/// spellings: ./x, a/../x, symlinks, and for existing files hard links (same device and inode).
void refuse_overwrites(const Scenario& scenario, CliCommand command);

}  // namespace lpsim

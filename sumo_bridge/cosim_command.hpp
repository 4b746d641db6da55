#pragma once
// `lpsim cosim`: a run of the scenario in which SUMO simulates the corridor's edges
// (sumo_bridge/cosimulation).
#include <string>
#include <vector>

namespace lpsim {

/// Runs the co-simulation the arguments describe; the exit status (128 + the signal when one stopped it).
int command_cosim(const std::vector<std::string>& args);

/// --sumo-args split as a shell would split it without expansions: on blanks, '...' and "..." grouping.
/// InputError on an unclosed quote.
std::vector<std::string> split_sumo_args(const std::string& text);

}  // namespace lpsim

#pragma once
#include <string>

#include "core/config_spec.hpp"

namespace lpsim {

/// Reads a .sumocfg: input files (paths made relative to the cfg's folder), time, processing and output
/// options. Unknown options are ignored, as SUMO's own unknown-but-valid ones would be irrelevant here.
ConfigSpec read_sumocfg(const std::string& path);

}  // namespace lpsim

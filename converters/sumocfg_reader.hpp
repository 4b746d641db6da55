#pragma once
#include <string>

#include "core/config_spec.hpp"
#include "core/error.hpp"

namespace lpsim {

/// Reads a .sumocfg: input files (paths made relative to the cfg's folder), time, processing and output
/// options. SUMO options LPSim does not implement are refused or noted as apply_option says; a name SUMO
/// does not know either is an InputError naming file:line, as in SUMO. The begin/end window is checked by
/// the caller once the command line has had its say (SUMO's order); `time_window_at`, when given, receives
/// where the later of <begin> and <end> stands (untouched when neither does).
ConfigSpec read_sumocfg(const std::string& path, SourceLoc* time_window_at = nullptr);

}  // namespace lpsim

#pragma once
// SUMO-style options, from a .sumocfg or from the command line, mapped onto ConfigSpec. One table of
// option names serves both, so `<end value="3600"/>` and `--end 3600` mean the same thing.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/config_spec.hpp"
#include "core/error.hpp"

namespace lpsim {

/// Where an option's value came from: names it in errors and anchors relative paths.
struct OptionSource {
  SourceLoc loc;              // cfg file:line, or {"command line", 0}
  std::string base_dir;       // relative paths are resolved against it; empty: kept as given
  bool command_line = false;  // errors then say "--name" rather than "<name>"
};

/// Applies option `name` (long name without dashes; SUMO's synonyms net, routes, additional accepted) with
/// its text value to `config`. Returns false when LPSim does not know the name. Options that make sense
/// only on the command line (configuration-file, output) are unknown when `where.command_line` is false.
/// A bad value raises InputError naming where, the option and the value.
bool apply_option(ConfigSpec& config, std::string_view name, const std::string& value,
                  const OptionSource& where);

/// SUMO time value: seconds ("3600", "0.5", "-1") or "h:m:s" / "d:h:m:s" (parts non-negative, the last
/// may have a fraction; a leading '-' negates the whole). nullopt when it is none of these.
std::optional<double> parse_sumo_time(std::string_view text);

/// SUMO boolean, case-insensitive: true/yes/on/1/x or false/no/off/0/-. nullopt otherwise.
std::optional<bool> parse_sumo_bool(std::string_view text);

/// Parses command-line options (program name and sub-command already removed), SUMO style:
/// `--name value`, `--name=value`, short forms -c -n -r -a -b -e -o, `--ignore-route-errors` alone or with
/// true/false. A configuration file (-c) is read first; every other option overrides it wherever it appears.
/// Arguments not starting with '-' (and all after "--") are positional: they go to `positional`, or raise
/// InputError when `positional` is null. Unknown options and missing values raise InputError naming them.
ConfigSpec parse_cli_options(const std::vector<std::string>& args,
                             std::vector<std::string>* positional = nullptr);

}  // namespace lpsim

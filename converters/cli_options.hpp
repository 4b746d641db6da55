#pragma once
// SUMO-style options, from a .sumocfg or from the command line, mapped onto ConfigSpec. One table of
// option names serves both, so `<end value="3600"/>` and `--end 3600` mean the same thing.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/config_spec.hpp"
#include "core/error.hpp"
#include "core/time_range.hpp"

namespace lpsim {

/// The commands of `lpsim` that take options; each option says which of them use it.
enum class CliCommand { Info, Convert, Run, Partition, Cosim, Assign };

/// Where an option's value came from: names it in errors and anchors relative paths.
struct OptionSource {
  SourceLoc loc;              // cfg file:line, or {"command line", 0}
  std::string base_dir;       // relative paths are resolved against it; empty: kept as given
  bool command_line = false;  // errors then say "--name" rather than "<name>"
};

/// Applies option `name` (long name without dashes; SUMO's synonyms net, routes, additional accepted) with
/// its text value to `config`. A SUMO option LPSim does not implement is refused with an InputError ("not
/// supported by LPSim") when it could change the results, or noted in `config.inert_options` when it cannot;
/// set to SUMO's default value it asks for nothing and is accepted as if absent. Returns false when neither
/// LPSim nor SUMO knows the name. LPSim's own options (configuration-file, output, device,
/// max-lane-map-gb) are unknown when `where.command_line` is false, so a .sumocfg stays valid for SUMO.
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
/// InputError when `positional` is null. Unknown options and missing values raise InputError naming them;
/// with a `command`, so does an option that command does not use. SUMO's short and long names of the
/// options LPSim does not implement are treated as apply_option says. Times beyond kMaxTimeSeconds and a
/// begin after the end (when the end is >= 0) are refused, whether they come from the .sumocfg or not.
ConfigSpec parse_cli_options(const std::vector<std::string>& args,
                             std::vector<std::string>* positional = nullptr,
                             std::optional<CliCommand> command = std::nullopt);

/// Refuses a begin after the end (an end >= 0), as SUMO does; `where` is where the later of them was set.
void check_time_window(const ConfigSpec& config, const SourceLoc& where);

/// One line per option `command` takes ("  -e, --end TIME   description"), from the option table itself.
std::string describe_options(CliCommand command);

/// Whether `args` (a command's, after its name) ask for help: -h, --help or -? where an option may stand,
/// not as the value of one (--sumo-args --help passes --help on to SUMO), and not after "--".
bool help_requested(const std::vector<std::string>& args);

}  // namespace lpsim

#pragma once
// SUMO's options that LPSim does not implement, so that none is silently ignored: each is either inert (it
// cannot change what LPSim computes or writes: logging, validation, the GUI) or unsupported (it would change
// the results: demand scaling, mesoscopic mode, rerouting, other outputs...). The options LPSim implements
// are in cli_options.cpp's table, not here.
#include <string_view>

#include "core/config_spec.hpp"

namespace lpsim {

enum class ForeignOptionClass {
  Inert,        // cannot change LPSim's results: accepted with one warning naming it
  Unsupported,  // would change results: refused, unless given its SUMO default value
  Scoped,       // acts only where a scenario has what `scope` names: decided once it is loaded
};

struct ForeignOption {
  std::string_view name;
  std::string_view sumo_default;  // SUMO 1.15's default, as `sumo --save-template` writes it
  char short_name;                // 0 if none
  ForeignOptionClass kind;
  OptionScope scope = OptionScope::BidiEdges;  // what a Scoped option acts on
};

/// The SUMO option called `name` (a current name, or one of the few synonyms listed), or nullptr.
const ForeignOption* find_foreign_option(std::string_view name);
const ForeignOption* find_foreign_short(char short_name);

/// True when `value` asks for what SUMO does without the option, compared as numbers, booleans or text, so
/// "1.0" equals "1" and "False" equals "false".
bool is_sumo_default(const ForeignOption& option, std::string_view value);

/// True when the option is a switch (its default is true or false): on the command line it may stand alone.
bool is_foreign_switch(const ForeignOption& option);

}  // namespace lpsim

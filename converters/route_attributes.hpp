#pragma once
// Parsing of the attribute values SUMO route files use: times, depart/arrival keywords, id lists,
// booleans and distribution specifiers. Pure functions; callers turn a failure into an InputError that
// names the file, the element and the value.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "converters/cli_options.hpp"  // parse_sumo_time, parse_sumo_bool
#include "core/demand_spec.hpp"

namespace lpsim {

/// Fill one field of DepartSpec from its SUMO attribute value; false for an unknown keyword or a bad number.
bool parse_depart_lane(std::string_view text, DepartSpec& out);
bool parse_depart_pos(std::string_view text, DepartSpec& out);
bool parse_depart_speed(std::string_view text, DepartSpec& out);
bool parse_arrival_pos(std::string_view text, DepartSpec& out);

/// Mean and deviation of a speedFactor: a plain number (deviation absent), "norm(mean,dev)" or
/// "normc(mean,dev,min,max)".
struct MeanDev {
  double mean = 1.0;
  std::optional<double> dev;
};
std::optional<MeanDev> parse_speed_factor(std::string_view text);

/// Splits on spaces, tabs and newlines, dropping empty pieces (files often carry stray spaces).
std::vector<std::string> split_ids(std::string_view text);

/// The text without leading and trailing whitespace.
std::string_view trim(std::string_view text);

}  // namespace lpsim

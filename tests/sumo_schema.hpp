// SUMO's XML schemas for the output tests, which validate what LPSim writes with xmllint against them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "temp_dir.hpp"

namespace lpsim::test {

inline const char* const kSumoXsdDir = "/usr/share/sumo/data/xsd";

/// The path of a schema xmllint can compile: `schema` itself, or a patched copy written into `dir`. SUMO
/// 1.15's summary_file.xsd types 'time' as "nonNegativeFloat", which baseTypes.xsd does not define, so the
/// copy names the defined "nonNegativeFloatType" (and includes baseTypes.xsd by its absolute path).
inline std::string usable_sumo_schema(const std::string& schema, const TempDir& dir) {
  std::ifstream in(schema, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string broken = "type=\"nonNegativeFloat\"";
  if (text.find(broken) == std::string::npos) return schema;
  for (size_t at; (at = text.find(broken)) != std::string::npos;)
    text.replace(at, broken.size(), "type=\"nonNegativeFloatType\"");
  const std::string include = "schemaLocation=\"baseTypes.xsd\"";
  const size_t at = text.find(include);
  if (at != std::string::npos)
    text.replace(at, include.size(), "schemaLocation=\"" + std::string(kSumoXsdDir) + "/baseTypes.xsd\"");
  const size_t slash = schema.find_last_of('/');
  return dir.write("patched_" + (slash == std::string::npos ? schema : schema.substr(slash + 1)), text);
}

}  // namespace lpsim::test

// An edgeData/laneData output read back as numbers (each interval's edge or lane entries and their
// attributes), and a bundled scenario copied to a test's folder: what the tests that compare emission
// outputs (LPSim against SUMO, one run of LPSim against another) share.
#pragma once

#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <tuple>

#include "lpsim_cli.hpp"

namespace lpsim::test {

/// (interval begin, interval end, edge or lane id) -> attribute -> value, for every entry with a
/// sampledSeconds attribute (the lanes of a laneData output, the edges of an edgeData output).
using MeanDataEntries = std::map<std::tuple<double, double, std::string>, std::map<std::string, double>>;

inline MeanDataEntries meandata_entries(const std::string& text) {
  MeanDataEntries out;
  // An interval's start (groups 1, 2) or an edge or lane element (groups 3, 4).
  static const std::regex tag(
      R"re(<interval begin="([^"]*)" end="([^"]*)"|<(?:edge|lane) id="([^"]*)"([^>]*)>)re");
  static const std::regex attribute(R"re(([A-Za-z_0-9]+)="([^"]*)")re");
  double begin = 0, end = 0;
  for (auto t = std::sregex_iterator(text.begin(), text.end(), tag); t != std::sregex_iterator(); ++t) {
    const std::smatch& m = *t;
    if (m[1].matched) {
      begin = std::stod(m[1]);
      end = std::stod(m[2]);
      continue;
    }
    const std::string attrs = m[4];
    std::map<std::string, double> values;
    for (auto a = std::sregex_iterator(attrs.begin(), attrs.end(), attribute); a != std::sregex_iterator();
         ++a)
      values[(*a)[1]] = std::stod((*a)[2]);
    if (values.count("sampledSeconds")) out[{begin, end, m[3]}] = values;
  }
  return out;
}

/// The files of bundled scenario `name` (scenarios/<name>/*) copied into `dir`, so that the outputs its
/// add-file names land there.
inline void copy_scenario(const std::string& name, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (const auto& f : std::filesystem::directory_iterator(std::string(LPSIM_SCENARIOS_DIR) + "/" + name))
    std::filesystem::copy_file(f.path(), dir / f.path().filename(),
                               std::filesystem::copy_options::overwrite_existing);
}

}  // namespace lpsim::test

#include "converters/corridor_file.hpp"

#include <fstream>

namespace lpsim {

namespace {

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") + 1 - b);
}

// The kinds sumo-gui and netedit write are SUMO's element names: a lower-case letter, then letters and
// digits (junction, poi, busStop, e1Detector). Anything else (Edge, a stray byte) is not a selection line.
bool selection_kind(const std::string& kind) {
  if (kind.empty() || kind[0] < 'a' || kind[0] > 'z') return false;
  for (const char c : kind)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) return false;
  return true;
}

}  // namespace

CorridorSpec read_corridor_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(SourceLoc{path, 0}, "cannot open corridor file (missing?)");
  CorridorSpec spec;
  spec.file = path;
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    // Editors on Windows start a UTF-8 file with a byte-order mark.
    if (line == 1 && raw.compare(0, 3, "\xEF\xBB\xBF") == 0) raw.erase(0, 3);
    const std::string s = trimmed(raw);
    if (s.empty() || s[0] == '#') continue;
    if (s.find_first_of(" \t") != std::string::npos)
      throw InputError(SourceLoc{path, line},
                       "one object per line expected (edge:ID or an edge id), got '" + s + "'");
    // SUMO's internal edge and lane ids start with ':', kinds never do.
    const size_t colon = s.find(':');
    if (colon == std::string::npos || colon == 0) {
      spec.items.push_back({s, false, line});
      continue;
    }
    const std::string kind = s.substr(0, colon), id = s.substr(colon + 1);
    if (id.empty()) throw InputError(SourceLoc{path, line}, "no id after '" + kind + ":'");
    if (kind == "edge" || kind == "lane") {
      spec.items.push_back({id, kind == "lane", line});
      continue;
    }
    if (!selection_kind(kind))
      throw InputError(SourceLoc{path, line}, "'" + kind +
                                                  ":' is not a kind of object sumo-gui selects (a corridor "
                                                  "line is edge:ID, lane:ID or an edge id), got '" +
                                                  s + "'");
    auto it = spec.other_kinds.begin();
    while (it != spec.other_kinds.end() && it->first != kind) ++it;
    if (it == spec.other_kinds.end())
      spec.other_kinds.push_back({kind, 1});
    else
      ++it->second;
  }
  if (spec.items.empty()) throw InputError(SourceLoc{path, 0}, "the corridor file names no edge");
  return spec;
}

}  // namespace lpsim

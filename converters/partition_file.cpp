#include "converters/partition_file.hpp"

#include <charconv>
#include <fstream>
#include <string_view>

#include "converters/output_file.hpp"
#include "converters/route_attributes.hpp"

namespace lpsim {

namespace {

bool parse_int(std::string_view s, int32_t& out) {
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

}  // namespace

void write_partition_file(const std::string& path, const std::vector<std::string>& comment, int32_t parts,
                          const std::vector<std::string>& edge_id, const std::vector<int32_t>& part) {
  OutputFile out(path);
  for (const auto& c : comment) {
    out.text("# ");
    out.text(c);
    out.put('\n');
  }
  out.text("parts ");
  out.integer(parts);
  out.put('\n');
  for (size_t i = 0; i < edge_id.size(); ++i) {
    out.text(edge_id[i]);
    out.put(' ');
    out.integer(part[i]);
    out.put('\n');
  }
  out.close();
}

PartitionSpec read_partition_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(SourceLoc{path, 0}, "cannot read the partition file");
  PartitionSpec spec;
  spec.loc = SourceLoc{path, 0};
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string_view s = trim(raw);
    if (s.empty() || s.front() == '#') continue;
    const size_t space = s.find_first_of(" \t");
    const SourceLoc where{path, line};
    if (space == std::string_view::npos)
      throw InputError(where, "expected '<edge id> <part>' or 'parts K', got '" + std::string(s) + "'");
    const std::string_view key = s.substr(0, space), value = trim(s.substr(space));
    int32_t number = 0;
    if (!parse_int(value, number))
      throw InputError(where,
                       "'" + std::string(value) + "' is not a whole number (line '" + std::string(s) + "')");
    if (spec.parts == 0) {
      if (key != "parts") throw InputError(where, "the file must declare 'parts K' before its first edge");
      if (number < 1 || number > kMaxParts)
        throw InputError(
            where, "parts must lie in 1.." + std::to_string(kMaxParts) + ", not " + std::to_string(number));
      spec.parts = number;
      spec.loc = where;
      continue;
    }
    if (key == "parts") throw InputError(where, "'parts' declared twice");
    spec.edge_id.emplace_back(key);
    spec.part.push_back(number);
    spec.line.push_back(line);
  }
  if (spec.parts == 0) throw InputError(SourceLoc{path, 0}, "no 'parts K' line: not a partition file");
  return spec;
}

}  // namespace lpsim

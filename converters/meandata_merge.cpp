#include "converters/meandata_merge.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string_view>
#include <vector>

#include "converters/input_file.hpp"
#include "converters/output_file.hpp"
#include "converters/xml_stream.hpp"
#include "core/error.hpp"

namespace lpsim {

namespace {

std::string escaped(std::string_view s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The element's attributes as written: name="value" ... (values escaped again).
std::string attributes(const XmlStream& xml) {
  std::string out;
  xml.for_each_attr([&](std::string_view name, std::string_view value) {
    out += ' ';
    out += name;
    out += "=\"";
    out += escaped(value);
    out += '"';
  });
  return out;
}

// SUMO's entries of the corridor's edges per interval: interval begin -> its end and (escaped edge id -> the
// entry's lines).
struct SumoInterval {
  double end = 0;
  std::map<std::string, std::string> entries;
};
using Entries = std::map<double, SumoInterval>;

Entries read_sumo_entries(const std::string& path, const std::unordered_set<std::string>& corridor) {
  XmlStream xml(path);
  Entries out;
  std::map<std::string, std::string>* interval = nullptr;
  std::string* entry = nullptr;  // the corridor edge being read
  bool edge_open = false;        // its element has children (laneData)
  for (XmlStream::Event e = xml.next(); e != XmlStream::Event::Eof; e = xml.next()) {
    if (e == XmlStream::Event::Start) {
      if (xml.name() == "interval") {
        SumoInterval& i = out[xml.required_number("begin")];
        i.end = xml.required_number("end");
        interval = &i.entries;
      } else if (xml.name() == "edge" && interval != nullptr) {
        const std::string id = xml.required("id");
        entry = corridor.count(id) ? &(*interval)[escaped(id)] : nullptr;
        if (entry != nullptr) {
          // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
          *entry = "        <edge";
          *entry += attributes(xml);
        }
        edge_open = false;
      } else if (xml.name() == "lane" && entry != nullptr) {
        if (!edge_open) *entry += ">\n";
        edge_open = true;
        *entry += "            <lane";
        *entry += attributes(xml);
        *entry += "/>\n";
      }
    } else if (xml.name() == "edge" && entry != nullptr) {
      *entry += edge_open ? "        </edge>\n" : "/>\n";
      entry = nullptr;
    }
  }
  return out;
}

// The value of attribute `name` in one line of LPSim's output ("" when it has none).
std::string_view attribute_in(std::string_view line, std::string_view name) {
  std::string key = " ";
  key += name;
  key += "=\"";
  const size_t at = line.find(key);
  if (at == std::string_view::npos) return {};
  const size_t begin = at + key.size();
  const size_t end = line.find('"', begin);
  return end == std::string_view::npos ? std::string_view{} : line.substr(begin, end - begin);
}

std::string read_whole(const std::string& path) {
  InputFile in(path);
  std::string text;
  char buf[1 << 16];
  for (size_t n; (n = in.read(buf, sizeof buf)) > 0;) text.append(buf, n);
  return text;
}

std::vector<MeanDataSpanDiff> write_merged(const std::string& text, const std::string& lpsim_file,
                                           const std::string& sumo_file, const Entries& sumo,
                                           const std::unordered_set<std::string>& corridor,
                                           const std::string& merging) {
  std::vector<MeanDataSpanDiff> diffs;
  {
    OutputFile out(merging);
    const std::map<std::string, std::string>* interval = nullptr;
    std::unordered_set<std::string> written;
    bool skipping = false;  // inside a corridor edge's laneData entry of LPSim's
    int line_no = 0;
    for (size_t start = 0; start < text.size();) {
      size_t nl = text.find('\n', start);
      if (nl == std::string::npos) nl = text.size();
      const std::string_view line(text.data() + start, nl - start);
      start = nl + 1;
      ++line_no;
      const size_t first = line.find_first_not_of(' ');
      const std::string_view tag = first == std::string_view::npos ? std::string_view{} : line.substr(first);
      if (skipping) {
        if (tag.rfind("</edge>", 0) == 0) skipping = false;
        continue;
      }
      if (tag.rfind("<interval ", 0) == 0) {
        const std::optional<double> begin = parse_double(attribute_in(line, "begin"));
        const auto it = begin ? sumo.lower_bound(*begin - 1e-6) : sumo.end();
        if (it == sumo.end() || std::fabs(it->first - *begin) > 1e-6)
          throw InputError(lpsim_file + ":" + std::to_string(line_no) + ": interval begin=\"" +
                           std::string(attribute_in(line, "begin")) + "\" has no interval in SUMO's " +
                           sumo_file);
        interval = &it->second.entries;
        written.clear();
        const std::optional<double> end = parse_double(attribute_in(line, "end"));
        if (end && std::fabs(*end - it->second.end) > 1e-6)
          diffs.push_back(MeanDataSpanDiff{*begin, *end, it->second.end});
      } else if (tag.rfind("</interval>", 0) == 0 && interval != nullptr) {
        for (const auto& [id, entry] : *interval)
          if (!written.count(id)) out.text(entry);
        interval = nullptr;
      } else if (tag.rfind("<edge ", 0) == 0 && interval != nullptr) {
        const std::string id(attribute_in(line, "id"));
        if (corridor.count(id)) {
          skipping = tag.find("/>") == std::string_view::npos;
          const auto entry = interval->find(id);
          if (entry != interval->end()) {
            out.text(entry->second);
            written.insert(id);
          }
          continue;
        }
      }
      out.text(line);
      if (nl < text.size()) out.put('\n');
    }
    out.close();
  }
  return diffs;
}

}  // namespace

std::vector<MeanDataSpanDiff> merge_meandata(const std::string& lpsim_file, const std::string& sumo_file,
                                             const std::unordered_set<std::string>& corridor_edges) {
  const Entries sumo = read_sumo_entries(sumo_file, corridor_edges);
  const std::string text = read_whole(lpsim_file);
  std::unordered_set<std::string> corridor;  // as the ids appear in the file
  for (const std::string& id : corridor_edges) corridor.insert(escaped(id));

  const std::filesystem::path p(lpsim_file);
  const std::string merging = (p.parent_path() / ("merging." + p.filename().string())).string();
  std::vector<MeanDataSpanDiff> diffs;
  try {
    diffs = write_merged(text, lpsim_file, sumo_file, sumo, corridor, merging);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(merging, ignored);
    throw;
  }
  std::filesystem::rename(merging, lpsim_file);
  return diffs;
}

}  // namespace lpsim

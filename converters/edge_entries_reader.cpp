#include "converters/edge_entries_reader.hpp"

#include "converters/xml_stream.hpp"

namespace lpsim {

std::unordered_map<std::string, int64_t> read_edge_entries(const std::string& path) {
  std::unordered_map<std::string, int64_t> entered;
  XmlStream xml(path);
  bool interval = false;
  for (XmlStream::Event e; (e = xml.next()) != XmlStream::Event::Eof;) {
    if (e == XmlStream::Event::End) {
      if (xml.name() == "interval") interval = false;
      continue;
    }
    if (xml.name() == "interval") interval = true;
    if (interval && xml.name() == "edge") entered[xml.required("id")] += xml.integer("entered", 0);
  }
  return entered;
}

}  // namespace lpsim

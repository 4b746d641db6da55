#include "converters/edge_entries_reader.hpp"

#include "converters/xml_stream.hpp"

namespace lpsim {

EdgeDataTotals read_edge_totals(const std::string& path) {
  EdgeDataTotals totals;
  XmlStream xml(path);
  bool interval = false;
  for (XmlStream::Event e; (e = xml.next()) != XmlStream::Event::Eof;) {
    if (e == XmlStream::Event::End) {
      if (xml.name() == "interval") interval = false;
      continue;
    }
    if (xml.name() == "interval") {
      interval = true;
      totals.seconds += xml.number("end", 0) - xml.number("begin", 0);
    }
    if (interval && xml.name() == "edge") {
      EdgeTotals& t = totals.edges[xml.required("id")];
      t.entered += xml.integer("entered", 0);
      t.sampled_seconds += xml.number("sampledSeconds", 0);
    }
  }
  return totals;
}

}  // namespace lpsim

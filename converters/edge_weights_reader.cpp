#include "converters/edge_weights_reader.hpp"

#include <cmath>

#include "converters/xml_stream.hpp"
#include "core/error.hpp"

namespace lpsim {

IntervalTravelTimes read_edge_weights(const std::string& path,
                                      const std::unordered_map<std::string, uint32_t>& edge_index,
                                      uint32_t num_edges) {
  IntervalTravelTimes times;
  times.num_edges = num_edges;
  XmlStream xml(path);
  int64_t interval = -1;
  bool short_interval = false;  // the run's end may cut the last one short
  for (XmlStream::Event e; (e = xml.next()) != XmlStream::Event::Eof;) {
    if (e == XmlStream::Event::End) continue;
    if (xml.name() == "interval") {
      const double begin = xml.required_number("begin"), end = xml.required_number("end");
      if (interval < 0) {
        times.begin = begin;
        times.period = end - begin;
        if (!(times.period > 0)) throw InputError(xml.loc(), "interval: end must be after begin");
      } else if (short_interval ||
                 std::abs(begin - (times.begin + double(interval + 1) * times.period)) > 1e-6 ||
                 end - begin > times.period + 1e-6) {
        throw InputError(xml.loc(), "interval [" + std::to_string(begin) + ", " + std::to_string(end) +
                                        "): weight intervals must be consecutive and equally long (the last "
                                        "may be shorter)");
      }
      short_interval = interval >= 0 && end - begin < times.period - 1e-6;
      ++interval;
      times.time.resize(times.time.size() + num_edges, std::nanf(""));
      continue;
    }
    if (xml.name() != "edge" || interval < 0) continue;
    const auto it = edge_index.find(xml.required("id"));
    if (it == edge_index.end()) continue;
    const double t = xml.number("traveltime", NAN);
    if (!std::isnan(t)) times.time[size_t(interval) * num_edges + it->second] = static_cast<float>(t);
  }
  if (interval < 0) throw InputError(path + ": no <interval> of edge weights");
  return times;
}

}  // namespace lpsim

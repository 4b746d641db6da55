#include "converters/route_alternatives_reader.hpp"

#include "converters/xml_stream.hpp"
#include "core/error.hpp"

namespace lpsim {

std::unordered_map<std::string, RouteAlternatives> read_route_alternatives(
    const std::string& path, const std::unordered_map<std::string, uint32_t>& edge_index) {
  std::unordered_map<std::string, RouteAlternatives> all;
  XmlStream xml(path);
  std::string vehicle;  // inside a <vehicle>: its id
  RouteAlternatives alts;
  bool in_distribution = false;
  SourceLoc distribution_loc;
  for (XmlStream::Event e; (e = xml.next()) != XmlStream::Event::Eof;) {
    const std::string& name = xml.name();
    if (e == XmlStream::Event::End) {
      if (name == "routeDistribution" && in_distribution) {
        in_distribution = false;
        if (alts.last >= alts.routes.size())
          throw InputError(distribution_loc, "routeDistribution of vehicle '" + vehicle + "': last=\"" +
                                                 std::to_string(alts.last) + "\" but " +
                                                 std::to_string(alts.routes.size()) + " routes");
        all[vehicle] = std::move(alts);
      } else if (name == "vehicle") {
        vehicle.clear();
      }
      continue;
    }
    if (name == "vehicle") {
      vehicle = xml.required("id");
    } else if (name == "routeDistribution" && !vehicle.empty()) {
      in_distribution = true;
      distribution_loc = xml.loc();
      alts = RouteAlternatives{};
      alts.last = static_cast<uint32_t>(xml.integer("last", 0));
    } else if (name == "route" && in_distribution) {
      RouteAlternative r;
      r.cost = xml.required_number("cost");
      r.probability = xml.required_number("probability");
      const std::string edges = xml.required("edges");
      for (size_t at = 0; at < edges.size();) {
        const size_t start = edges.find_first_not_of(' ', at);
        if (start == std::string::npos) break;
        const size_t end = std::min(edges.find(' ', start), edges.size());
        const std::string id = edges.substr(start, end - start);
        const auto it = edge_index.find(id);
        if (it == edge_index.end())
          throw InputError(xml.loc(), "route of vehicle '" + vehicle + "': unknown edge '" + id + "'");
        r.edges.push_back(it->second);
        at = end;
      }
      alts.routes.push_back(std::move(r));
    }
  }
  return all;
}

}  // namespace lpsim

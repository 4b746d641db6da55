#include "converters/vclass.hpp"

namespace lpsim {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool blank(std::string_view s) {
  for (char c : s)
    if (!is_space(c)) return false;
  return true;
}

}  // namespace

bool vclass_list_names_passenger(std::string_view list) {
  size_t i = 0;
  while (i < list.size()) {
    while (i < list.size() && is_space(list[i])) ++i;
    size_t start = i;
    while (i < list.size() && !is_space(list[i])) ++i;
    std::string_view name = list.substr(start, i - start);
    if (name == "passenger" || name == "all") return true;
  }
  return false;
}

bool passenger_allowed(std::string_view allow, std::string_view disallow) {
  if (!blank(allow)) return vclass_list_names_passenger(allow);
  if (!blank(disallow)) return !vclass_list_names_passenger(disallow);
  return true;
}

}  // namespace lpsim

#include "converters/route_attributes.hpp"

#include <array>
#include <cctype>

#include "converters/xml_stream.hpp"

namespace lpsim {

std::string_view trim(std::string_view text) {
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!text.empty() && space(text.front())) text.remove_prefix(1);
  while (!text.empty() && space(text.back())) text.remove_suffix(1);
  return text;
}

bool parse_depart_lane(std::string_view text, DepartSpec& out) {
  text = trim(text);
  static constexpr std::pair<std::string_view, DepartLane> kKeywords[] = {{"first", DepartLane::First},
                                                                          {"random", DepartLane::Random},
                                                                          {"free", DepartLane::Free},
                                                                          {"allowed", DepartLane::Allowed},
                                                                          {"best", DepartLane::Best}};
  for (const auto& [word, value] : kKeywords)
    if (text == word) {
      out.lane = value;
      return true;
    }
  auto index = parse_integer(text);
  if (!index || *index < 0 || *index > 1000000) return false;
  out.lane = DepartLane::Given;
  out.lane_index = static_cast<int>(*index);
  return true;
}

bool parse_depart_pos(std::string_view text, DepartSpec& out) {
  text = trim(text);
  static constexpr std::pair<std::string_view, DepartPos> kKeywords[] = {
      {"base", DepartPos::Base}, {"random", DepartPos::Random},
      {"free", DepartPos::Free}, {"random_free", DepartPos::RandomFree},
      {"last", DepartPos::Last}, {"stop", DepartPos::Stop}};
  for (const auto& [word, value] : kKeywords)
    if (text == word) {
      out.pos = value;
      return true;
    }
  // Negative positions count from the lane's end, as in SUMO.
  auto pos = parse_double(text);
  if (!pos) return false;
  out.pos = DepartPos::Given;
  out.pos_value = *pos;
  return true;
}

bool parse_depart_speed(std::string_view text, DepartSpec& out) {
  text = trim(text);
  static constexpr std::pair<std::string_view, DepartSpeed> kKeywords[] = {
      {"random", DepartSpeed::Random},         {"max", DepartSpeed::Max},   {"desired", DepartSpeed::Desired},
      {"speedLimit", DepartSpeed::SpeedLimit}, {"last", DepartSpeed::Last}, {"avg", DepartSpeed::Avg}};
  for (const auto& [word, value] : kKeywords)
    if (text == word) {
      out.speed = value;
      return true;
    }
  auto speed = parse_double(text);
  if (!speed || *speed < 0) return false;
  out.speed = DepartSpeed::Given;
  out.speed_value = *speed;
  return true;
}

bool parse_arrival_pos(std::string_view text, DepartSpec& out) {
  text = trim(text);
  if (text == "max") {
    out.arrival = ArrivalPos::Max;
    return true;
  }
  if (text == "random") {
    out.arrival = ArrivalPos::Random;
    return true;
  }
  auto pos = parse_double(text);
  if (!pos) return false;
  out.arrival = ArrivalPos::Given;
  out.arrival_value = *pos;
  return true;
}

std::optional<MeanDev> parse_speed_factor(std::string_view text) {
  text = trim(text);
  if (auto plain = parse_double(text)) return MeanDev{*plain, std::nullopt};
  size_t open = text.find('(');
  if (open == std::string_view::npos || text.back() != ')') return std::nullopt;
  std::string_view name = trim(text.substr(0, open));
  std::string_view args = text.substr(open + 1, text.size() - open - 2);
  std::vector<double> values;
  while (true) {
    size_t comma = args.find(',');
    auto v = parse_double(trim(args.substr(0, comma)));
    if (!v) return std::nullopt;
    values.push_back(*v);
    if (comma == std::string_view::npos) break;
    args.remove_prefix(comma + 1);
  }
  bool shape_ok = (name == "norm" && values.size() == 2) || (name == "normc" && values.size() == 4);
  if (!shape_ok || values[1] < 0) return std::nullopt;
  return MeanDev{values[0], values[1]};
}

std::vector<std::string> split_ids(std::string_view text) {
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  size_t pieces = 0;
  for (size_t i = 0; i < text.size(); ++i)
    if (!space(text[i]) && (i == 0 || space(text[i - 1]))) ++pieces;
  std::vector<std::string> out;
  out.reserve(pieces);
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && space(text[i])) ++i;
    size_t start = i;
    while (i < text.size() && !space(text[i])) ++i;
    if (i > start) out.emplace_back(text.substr(start, i - start));
  }
  return out;
}

}  // namespace lpsim

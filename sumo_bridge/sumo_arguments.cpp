#include "sumo_bridge/sumo_arguments.hpp"

#include <cstdio>
#include <filesystem>
#include <unordered_set>
#include <utility>

#include "core/error.hpp"

namespace lpsim {

namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ",") + s;
  return out;
}

const char* depart_lane_value(DepartLane k) {
  switch (k) {
    case DepartLane::Random:
      return "random";
    case DepartLane::Free:
      return "free";
    case DepartLane::Allowed:
      return "allowed";
    case DepartLane::Best:
      return "best";
    default:
      return "first";
  }
}

const char* depart_pos_value(DepartPos k) {
  switch (k) {
    case DepartPos::Random:
      return "random";
    case DepartPos::Free:
      return "free";
    case DepartPos::RandomFree:
      return "random_free";
    case DepartPos::Last:
      return "last";
    default:
      return "base";
  }
}

const char* depart_speed_value(DepartSpeed k) {
  switch (k) {
    case DepartSpeed::Random:
      return "random";
    case DepartSpeed::Max:
      return "max";
    case DepartSpeed::Desired:
      return "desired";
    case DepartSpeed::SpeedLimit:
      return "speedLimit";
    case DepartSpeed::Last:
      return "last";
    case DepartSpeed::Avg:
      return "avg";
    default:
      return "0";
  }
}

}  // namespace

std::string sumo_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

namespace {

// An option of `args` at i and its value: "--name=value", or "--name" and the word after it.
struct OptionAt {
  std::string name, value;
  size_t words = 1;  // how many words it takes
};
OptionAt option_at(const std::vector<std::string>& args, size_t i) {
  const std::string& a = args[i];
  const size_t eq = a.find('=');
  if (eq != std::string::npos) return {a.substr(0, eq), a.substr(eq + 1), 1};
  if (i + 1 < args.size()) return {a, args[i + 1], 2};
  return {a, "", 1};
}

bool output_option(const std::string& name) {
  const std::string suffix = "-output";
  return (name.size() > suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) ||
         name == "--log" || name == "-l" || name == "--message-log" || name == "--error-log";
}

}  // namespace

std::vector<ExtraOutput> sumo_args_outputs(const std::vector<std::string>& user_args) {
  std::vector<ExtraOutput> out;
  for (size_t i = 0; i < user_args.size(); ++i) {
    if (user_args[i].rfind("-", 0) != 0) continue;
    const OptionAt o = option_at(user_args, i);
    if (!output_option(o.name) || o.value.empty()) continue;
    out.push_back({"SUMO's " + o.name + " in --sumo-args (written as " + sumo_side_path(o.value) + ")",
                   sumo_side_path(o.value)});
    i += o.words - 1;
  }
  return out;
}

void refuse_unsupported_sumo_args(const std::vector<std::string>& user_args) {
  for (const std::string& a : user_args) {
    const std::string name = a.substr(0, a.find('='));
    if (name == "--remote-port" || name == "--num-clients")
      throw InputError("--sumo-args: " + name +
                       " makes SUMO wait for TraCI clients, and the co-simulation is its only one: the run "
                       "would hang (--sumo-binary runs a SUMO of its own over TraCI)");
    if (name == "--tripinfo-output.write-unfinished" || name == "--tripinfo-output.write-undeparted")
      throw InputError(
          "--sumo-args: " + name +
          ": a co-simulation's tripinfo holds the trips that ended (unfinished ones are not merged "
          "from both sides yet)");
  }
}

std::vector<std::string> cosim_sumo_arguments(const ConfigSpec& c, const std::string& tripinfo,
                                              const std::string& extra_additional,
                                              const std::vector<std::string>& user_args) {
  refuse_unsupported_sumo_args(user_args);
  // The co-simulation's options, as (name, value) pairs.
  std::vector<std::pair<std::string, std::string>> ours{{"--net-file", c.net_file}};
  // The route files for their vTypes (and distributions) only: SUMO drops every vehicle and flow at scale 0.
  if (!c.route_files.empty()) {
    ours.emplace_back("--route-files", joined(c.route_files));
    ours.emplace_back("--scale", "0");
  }
  std::vector<std::string> additional = c.additional_files;
  if (!extra_additional.empty()) additional.push_back(extra_additional);
  // Additional files the user gives SUMO join the co-simulation's (which carry the signal programs and the
  // edgeData the merge reads) instead of replacing them.
  std::vector<std::string> rest;
  for (size_t i = 0; i < user_args.size(); ++i) {
    const OptionAt o = option_at(user_args, i);
    if (o.name == "-a" || o.name == "--additional-files" || o.name == "--additional") {
      for (size_t from = 0, comma; from <= o.value.size(); from = comma + 1) {
        comma = o.value.find(',', from);
        if (comma == std::string::npos) comma = o.value.size();
        if (comma > from) additional.push_back(o.value.substr(from, comma - from));
      }
      i += o.words - 1;
    } else {
      rest.push_back(user_args[i]);
    }
  }
  if (!additional.empty()) ours.emplace_back("--additional-files", joined(additional));
  ours.insert(ours.end(),
              {{"--begin", sumo_number(c.begin)},
               {"--step-length", sumo_number(c.step_length)},
               {"--seed", std::to_string(c.seed)},
               {"--time-to-teleport", sumo_number(c.time_to_teleport)},
               {"--time-to-teleport.highways", sumo_number(c.time_to_teleport_highways)},
               {"--time-to-teleport.highways.min-speed", sumo_number(c.time_to_teleport_highways_min_speed)},
               {"--time-to-impatience", sumo_number(c.time_to_impatience)},
               {"--default.carfollowmodel", c.default_car_follow_model},
               {"--no-step-log", "true"},
               {"--output-prefix", kSumoSidePrefix},
               {"--tripinfo-output", tripinfo}});
  const OutputSpec& o = c.outputs;
  if (!o.fcd.empty()) ours.emplace_back("--fcd-output", o.fcd);
  if (o.fcd_period > 0) ours.emplace_back("--device.fcd.period", sumo_number(o.fcd_period));
  if (!o.summary.empty()) ours.emplace_back("--summary-output", o.summary);
  // SUMO refuses an option given twice: one the user passes replaces ours (its short forms too).
  std::unordered_set<std::string> given;
  for (const std::string& a : rest) {
    const std::string name = a.substr(0, a.find('='));
    given.insert(name == "-n"   ? "--net-file"
                 : name == "-r" ? "--route-files"
                 : name == "-a" ? "--additional-files"
                 : name == "-b" ? "--begin"
                                : name);
  }
  for (const char* kept : {"--output-prefix", "--tripinfo-output", "--scale"})
    if (given.count(kept))
      throw InputError(std::string("--sumo-args: the co-simulation sets SUMO's ") + kept +
                       " itself (SUMO's outputs are written beside LPSim's, as sumo.<name>)");
  std::vector<std::string> a;
  for (const auto& [name, value] : ours)
    if (!given.count(name)) a.insert(a.end(), {name, value});
  a.insert(a.end(), rest.begin(), rest.end());
  return a;
}

SumoDepart sumo_depart(const Demand& d, uint32_t v) {
  SumoDepart out;
  const auto lane_kind = static_cast<DepartLane>(d.depart_lane_kind[v]);
  out.lane = lane_kind == DepartLane::Given ? std::to_string(d.depart_lane[v]) : depart_lane_value(lane_kind);
  const auto pos_kind = static_cast<DepartPos>(d.depart_pos_kind[v]);
  out.pos = pos_kind == DepartPos::Given ? sumo_number(d.depart_pos[v]) : depart_pos_value(pos_kind);
  const auto speed_kind = static_cast<DepartSpeed>(d.depart_speed_kind[v]);
  out.speed =
      speed_kind == DepartSpeed::Given ? sumo_number(d.depart_speed[v]) : depart_speed_value(speed_kind);
  return out;
}

}  // namespace lpsim

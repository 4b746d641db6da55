#include "app/load_warnings.hpp"

#include <map>
#include <string_view>

namespace lpsim {

namespace {

// The models the step implements (docs/MODELS.md): IDM and Krauss car following (any other model runs the
// IDM), and a lane changer that stands in for SUMO's default LC2013 (mandatory changes towards the best
// lanes, MOBIL for speed).
bool car_follow_implemented(const std::string& model) { return model == "IDM" || model == "Krauss"; }
constexpr std::string_view kLaneChangeModel = "LC2013";
// A warning names this many ids and then how many more there are.
constexpr size_t kIdsNamed = 5;

std::string id_list(const std::vector<std::string>& ids) {
  std::string out;
  for (size_t i = 0; i < ids.size() && i < kIdsNamed; ++i) out += (i ? ", '" : "'") + ids[i] + "'";
  if (ids.size() > kIdsNamed) out += " and " + std::to_string(ids.size() - kIdsNamed) + " more";
  return out;
}

std::string plural(size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

}  // namespace

std::vector<std::string> unimplemented_settings(const DemandSpec& demand, const NetSpec& net,
                                                const AdditionalSpec& additional,
                                                const std::string& default_car_follow_model) {
  // model -> the vTypes asking for it, in file order (a vType naming no model asks for the default).
  std::map<std::string, std::vector<std::string>> car_follow, lane_change;
  for (const VTypeSpec& t : demand.vtypes) {
    const std::string& model = t.car_follow_model_given ? t.car_follow_model : default_car_follow_model;
    if (!car_follow_implemented(model)) car_follow[model].push_back(t.id);
    if (!t.lane_change_model.empty() && t.lane_change_model != kLaneChangeModel)
      lane_change[t.lane_change_model].push_back(t.id);
  }
  std::vector<std::string> lines;
  for (const auto& [model, ids] : car_follow)
    lines.push_back("carFollowModel '" + model + "' is not implemented, IDM is used instead for " +
                    plural(ids.size(), "vType") + ": " + id_list(ids));
  // Vehicles without a vType run SUMO's DEFAULT_VEHTYPE, which takes the default model too.
  if (!car_follow_implemented(default_car_follow_model) && car_follow.count(default_car_follow_model) == 0)
    lines.push_back("carFollowModel '" + default_car_follow_model +
                    "' (--default.carfollowmodel) is not implemented, IDM is used instead for vTypes that "
                    "name no model");
  for (const auto& [model, ids] : lane_change)
    lines.push_back("laneChangeModel '" + model +
                    "' is not implemented, LPSim's lane changing (in place of " +
                    std::string(kLaneChangeModel) + ") is used instead for " + plural(ids.size(), "vType") +
                    ": " + id_list(ids));

  // SUMO 1.15 warns of its old name for emissions meandata, and takes it.
  for (const MeanDataSpec& m : additional.mean_data)
    if (m.hbefa_name)
      lines.push_back(std::string(m.lane_level ? "laneData" : "edgeData") + " '" + m.id + "' (" +
                      m.loc.str() + "): the type 'hbefa' is deprecated, 'emissions' is its name now");

  // The program each signal runs: the net's, replaced by an add-file's of the same id (network_builder).
  std::map<std::string, const TlLogicSpec*> program_of;
  for (const TlLogicSpec& tl : net.tl_logics) program_of[tl.id] = &tl;
  for (const TlLogicSpec& tl : additional.tl_logics) program_of[tl.id] = &tl;
  std::map<std::string, size_t> count_by_type;
  std::vector<std::string> not_static;
  std::vector<std::string> ignored_params;  // 'key' of 'id'
  for (const auto& [id, tl] : program_of) {
    if (tl->type == "actuated") {
      for (const auto& [key, value] : tl->params)
        if (key != "max-gap" && key != "detector-gap" && key != "passing-time")
          ignored_params.push_back(key + "' of '" + id);
    } else if (tl->type != "static") {
      ++count_by_type[tl->type];
      not_static.push_back(id);
    }
  }
  if (!ignored_params.empty())
    lines.push_back(
        "actuated signal parameters other than max-gap, detector-gap and passing-time are not "
        "implemented, SUMO's defaults are used instead of " +
        id_list(ignored_params));
  if (!not_static.empty()) {
    std::string types;
    for (const auto& [type, n] : count_by_type)
      types += (types.empty() ? "" : ", ") + type + " (" + std::to_string(n) + ")";
    lines.push_back("signal programs of type " + types +
                    " are not implemented, these traffic lights run their phases as static programs: " +
                    id_list(not_static));
  }
  return lines;
}

}  // namespace lpsim

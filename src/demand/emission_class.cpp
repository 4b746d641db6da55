#include "demand/emission_class.hpp"

#include <array>
#include <span>

#include "demand/hbefa_tables.hpp"

namespace lpsim {

namespace {

constexpr std::string_view kHbefa3Default = "PC_G_EU4";
constexpr std::string_view kHbefa2Default = "P_7_7";
// Models SUMO 1.15 has that LPSim does not implement: their classes load, an emissions output refuses them.
constexpr std::array<std::string_view, 5> kOtherModels{"HBEFA4", "PHEMlight", "PHEMlight5", "Energy",
                                                       "MMPEVEM"};

bool same_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

bool is_other_model(std::string_view model) {
  for (std::string_view m : kOtherModels)
    if (m == model) return true;
  return false;
}

EmissionClass zero_class() { return EmissionClass{}; }

EmissionClass hbefa_class(std::string_view model, const HbefaClass& c) {
  EmissionClass out;
  const std::string_view name = c.name;
  const bool hbefa3 = model == "HBEFA3";
  out.model = hbefa3                                        ? kEmissionHbefa3
              : name.find("_A0_") != std::string_view::npos ? kEmissionHbefa2NoAccel
                                                            : kEmissionHbefa2;
  out.name = std::string(model) + "/" + c.name;
  out.coeff = &c.coeff[0][0];
  out.fuel_density = !hbefa3 ? 790 : name.find("_D_") != std::string_view::npos ? 836 : 742;
  return out;
}

// Class `name` of model HBEFA3, HBEFA2 or Zero.
std::optional<EmissionClass> model_class(std::string_view model, std::string_view name) {
  if (name == "zero") return zero_class();
  const bool fallback = same_ignoring_case(name, "unknown") || same_ignoring_case(name, "default");
  if (model == "Zero") return fallback ? std::optional(zero_class()) : std::nullopt;
  const std::span<const HbefaClass> table = model == "HBEFA3" ? hbefa3_classes() : hbefa2_classes();
  if (fallback) name = model == "HBEFA3" ? kHbefa3Default : kHbefa2Default;
  for (const HbefaClass& c : table)
    if (same_ignoring_case(c.name, name)) return hbefa_class(model, c);
  return std::nullopt;
}

EmissionClass other_class(std::string_view text) {
  EmissionClass out;
  out.model = kEmissionOther;
  out.name = std::string(text);
  return out;
}

}  // namespace

std::optional<EmissionClass> find_emission_class(std::string_view text) {
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    if (text == "zero" || text == "Zero") return zero_class();
    if (text == "HBEFA3" || text == "HBEFA2") return model_class(text, "default");
    if (is_other_model(text)) return other_class(text);
    return model_class("HBEFA2", text);
  }
  const std::string_view model = text.substr(0, slash), name = text.substr(slash + 1);
  if (model == "HBEFA3" || model == "HBEFA2" || model == "Zero") return model_class(model, name);
  if (is_other_model(model)) return other_class(text);
  return std::nullopt;
}

EmissionClass default_emission_class(std::string_view vclass) {
  std::string_view name = "PC_G_EU4";
  if (vclass == "delivery" || vclass == "emergency")
    name = "LDV";
  else if (vclass == "truck" || vclass == "trailer")
    name = "HDV";
  else if (vclass == "bus")
    name = "Bus";
  else if (vclass == "coach")
    name = "Coach";
  else if (vclass == "motorcycle" || vclass == "moped")
    name = "LDV_G_EU6";
  else if (vclass == "rail" || vclass == "ship")
    name = "HDV_D_EU0";
  else if (vclass == "bicycle" || vclass == "pedestrian" || vclass == "evehicle" || vclass == "tram" ||
           vclass == "rail_urban" || vclass == "rail_electric" || vclass == "rail_fast")
    return zero_class();
  return *model_class("HBEFA3", name);
}

VehicleBody vclass_body(std::string_view vclass) {
  struct Entry {
    std::string_view vclass;
    VehicleBody body;
  };
  // SUMO 1.15's vClass defaults (SUMOVTypeParameter::VClassDefaultValues); every other class: a car's.
  static constexpr Entry kBodies[] = {
      {"delivery", {5000, 2.16, 2.86}}, {"emergency", {5000, 2.16, 2.86}}, {"truck", {12000, 2.4, 2.4}},
      {"trailer", {15000, 2.55, 4.0}},  {"bus", {7500, 2.5, 3.4}},         {"coach", {12000, 2.6, 4.0}},
      {"motorcycle", {200, 0.9, 1.5}},  {"moped", {80, 0.78, 1.7}},        {"rail", {79500, 2.84, 3.75}},
      {"ship", {100000, 4, 4}},
  };
  for (const Entry& e : kBodies)
    if (e.vclass == vclass) return e.body;
  return VehicleBody{1500, 1.8, 1.5};
}

CoastingParams coasting_params(double mass, double width, double height) {
  const double area = kEmissionPi / 4 * width * height;
  return CoastingParams{area / mass * -9.05337017 - 0.00017774, 0.00001066 * mass};
}

}  // namespace lpsim

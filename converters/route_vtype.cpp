#include "converters/route_vtype.hpp"

#include <limits>
#include <utility>
#include <vector>

#include "converters/route_attributes.hpp"

namespace lpsim {

namespace {

struct VClassDefaults {
  std::string_view vclass;
  double length, min_gap, accel, decel, emergency_decel, max_speed_kmh, speed_dev, sigma;
  double desired_max_speed_kmh = std::numeric_limits<double>::infinity();
};

// Measured from SUMO 1.15 (traci.vehicletype getters on a <vType vClass="..."/> with no other attributes).
constexpr VClassDefaults kVClassDefaults[] = {
    // A bicycle rides at 20 km/h at most (desiredMaxSpeed) although its maxSpeed is 50 km/h: measured with
    // traci.vehicle.getAllowedSpeed on a 100 km/h lane (20 km/h times the speed factor).
    {"bicycle", 1.6, 0.5, 1.2, 3.0, 7.0, 50, 0.1, 0.5, 20},
    {"bus", 12, 2.5, 1.2, 4.0, 7.0, 100, 0.0, 0.5},
    {"coach", 14, 2.5, 2.0, 4.0, 7.0, 100, 0.05, 0.5},
    {"delivery", 6.5, 2.5, 2.6, 4.5, 9.0, 200, 0.05, 0.5},
    {"emergency", 6.5, 2.5, 2.6, 4.5, 9.0, 200, 0.0, 0.5},
    {"army", 5, 2.5, 2.6, 4.5, 9.0, 200, 0.0, 0.5},
    {"authority", 5, 2.5, 2.6, 4.5, 9.0, 200, 0.0, 0.5},
    {"ignoring", 5, 2.5, 2.6, 4.5, 9.0, 200, 0.0, 0.5},
    {"taxi", 5, 2.5, 2.6, 4.5, 9.0, 200, 0.05, 0.5},
    {"moped", 2.1, 2.5, 1.1, 7.0, 10.0, 60, 0.1, 0.5},
    {"motorcycle", 2.2, 2.5, 6.0, 10.0, 10.0, 200, 0.1, 0.5},
    {"pedestrian", 0.215, 0.25, 1.5, 2.0, 5.0, 37.58, 0.1, 0.5},
    {"rail", 135, 5, 0.25, 1.3, 5.0, 160, 0.0, 0.0},
    {"rail_electric", 200, 5, 0.5, 1.3, 5.0, 220, 0.0, 0.0},
    {"rail_fast", 200, 5, 0.5, 1.3, 5.0, 330, 0.0, 0.0},
    {"rail_urban", 109.5, 5, 1.0, 3.0, 7.0, 100, 0.0, 0.0},
    {"ship", 17, 2.5, 0.1, 0.15, 1.0, 8 / 1.94 * 3.6, 0.1, 0.0},
    {"trailer", 16.5, 2.5, 1.1, 4.0, 7.0, 130, 0.05, 0.5},
    {"tram", 22, 2.5, 1.0, 3.0, 7.0, 80, 0.0, 0.0},
    {"truck", 7.1, 2.5, 1.3, 4.0, 7.0, 130, 0.05, 0.5},
};

[[noreturn]] void fail_at(const SourceLoc& loc, std::string_view element, const std::string& id,
                          const std::string& message) {
  throw InputError(loc, "<" + std::string(element) + " id=\"" + id + "\">: " + message);
}

enum class Sign { Positive, NonNegative };

// Upper bounds far beyond any vehicle, so that the step's float arithmetic (speeds squared, stopping
// distances, IDM powers) stays finite; SUMO has none, and a real scenario never comes near them.
constexpr double kMaxAcceleration = 1000;  // m/s^2: accel, decel, emergencyDecel
constexpr double kMaxTau = 3600;           // s
constexpr double kMaxLength = 10000;       // m: length, minGap
constexpr double kMaxSpeed = 1000;         // m/s: maxSpeed
constexpr double kMaxSpeedFactor = 100;
constexpr double kNoMax = std::numeric_limits<float>::max();  // the float range only (probability, speedDev)

double number_value(const SourceLoc& loc, std::string_view element, const std::string& id,
                    std::string_view key, std::string_view text, Sign sign, double max) {
  auto v = parse_double(text);
  bool ok = v && (sign == Sign::Positive ? *v > 0 : *v >= 0) && *v <= max;
  if (!ok) {
    std::string range = sign == Sign::Positive ? "a positive number" : "a non-negative number";
    range += max < kNoMax ? " up to " + std::to_string(static_cast<long long>(max))
                          : " within a 32-bit float's range";
    fail_at(loc, element, id,
            "attribute '" + std::string(key) + "' must be " + range + ": '" + std::string(text) + "'");
  }
  return *v;
}

// Sets a car-following field shared by vType attributes and carFollowing-X attributes; false if `key`
// is not one of them.
bool set_cf_field(const SourceLoc& loc, std::string_view element, VTypeSpec& t, std::string_view key,
                  std::string_view value) {
  auto num = [&](Sign sign, double max) { return number_value(loc, element, t.id, key, value, sign, max); };
  if (key == "accel")
    t.accel = num(Sign::Positive, kMaxAcceleration);
  else if (key == "decel")
    t.decel = num(Sign::Positive, kMaxAcceleration);
  else if (key == "emergencyDecel")
    t.emergency_decel = num(Sign::Positive, kMaxAcceleration);
  else if (key == "tau")
    t.tau = num(Sign::Positive, kMaxTau);  // SUMO refuses 0 too: the time gap divides
  else if (key == "sigma") {
    t.sigma = num(Sign::NonNegative, kNoMax);
    if (t.sigma > 1)
      fail_at(loc, element, t.id, "attribute 'sigma' must lie in [0, 1]: '" + std::string(value) + "'");
  } else {
    return false;
  }
  return true;
}

std::vector<std::pair<std::string, std::string>> collect_attrs(const XmlStream& xs) {
  std::vector<std::pair<std::string, std::string>> attrs;
  xs.for_each_attr([&](std::string_view k, std::string_view v) { attrs.emplace_back(k, v); });
  return attrs;
}

void read_cf_element(XmlStream& xs, VTypeSpec& t) {
  const SourceLoc loc = xs.loc();
  const std::string element = xs.name();
  t.car_follow_model = element.substr(std::string_view("carFollowing-").size());
  t.car_follow_model_given = true;
  for (const auto& [k, v] : collect_attrs(xs))
    if (!set_cf_field(loc, element, t, k, v)) t.params[k] = v;
}

}  // namespace

void apply_vclass_defaults(std::string_view vclass, VTypeSpec& t) {
  for (const auto& d : kVClassDefaults) {
    if (d.vclass != vclass) continue;
    t.length = d.length;
    t.min_gap = d.min_gap;
    t.accel = d.accel;
    t.decel = d.decel;
    t.emergency_decel = d.emergency_decel;
    t.max_speed = d.max_speed_kmh / 3.6;
    t.desired_max_speed = d.desired_max_speed_kmh / 3.6;
    t.speed_dev = d.speed_dev;
    t.sigma = d.sigma;
    return;
  }
}

VTypeSpec read_vtype(XmlStream& xs, std::map<std::string, int64_t>& skipped, double& probability) {
  VTypeSpec t;
  t.loc = xs.loc();
  const auto attrs = collect_attrs(xs);
  for (const auto& [k, v] : attrs)
    if (k == "id") t.id = v;
  if (t.id.empty()) xs.fail("missing attribute 'id'");
  for (const auto& [k, v] : attrs)
    if (k == "vClass") {
      t.vclass = std::string(trim(v));
      apply_vclass_defaults(t.vclass, t);
    }

  probability = 1.0;
  std::optional<double> speed_dev, factor_dev;
  bool max_speed_given = false, desired_max_given = false;
  auto num = [&](const std::string& key, const std::string& value, Sign sign, double max) {
    return number_value(t.loc, "vType", t.id, key, value, sign, max);
  };
  for (const auto& [k, v] : attrs) {
    if (k == "id" || k == "vClass") continue;
    if (set_cf_field(t.loc, "vType", t, k, v)) continue;
    if (k == "length")
      t.length = num(k, v, Sign::Positive, kMaxLength);
    else if (k == "minGap")
      t.min_gap = num(k, v, Sign::NonNegative, kMaxLength);
    else if (k == "maxSpeed") {
      t.max_speed = num(k, v, Sign::Positive, kMaxSpeed);
      max_speed_given = true;
    } else if (k == "desiredMaxSpeed") {
      t.desired_max_speed = num(k, v, Sign::Positive, kMaxSpeed);
      desired_max_given = true;
    } else if (k == "width")
      t.width = num(k, v, Sign::Positive, kMaxLength);
    else if (k == "height")
      t.height = num(k, v, Sign::Positive, kMaxLength);
    else if (k == "emissionClass")
      t.emission_class = v;  // resolved with the vClass (demand/emission_class): SUMO takes it verbatim
    else if (k == "speedDev")
      speed_dev = num(k, v, Sign::NonNegative, kNoMax);
    else if (k == "probability")
      probability = num(k, v, Sign::NonNegative, kNoMax);
    else if (k == "carFollowModel") {
      t.car_follow_model = std::string(trim(v));
      t.car_follow_model_given = true;
    } else if (k == "laneChangeModel") {
      t.lane_change_model = std::string(trim(v));
    } else if (k == "speedFactor") {
      auto sf = parse_speed_factor(v);
      if (!sf || sf->mean <= 0 || sf->mean > kMaxSpeedFactor)
        xs.fail("attribute 'speedFactor' must be a positive number up to " +
                std::to_string(static_cast<long long>(kMaxSpeedFactor)) +
                ", norm(mean,dev) or normc(mean,dev,min,max): '" + v + "'");
      t.speed_factor = sf->mean;
      factor_dev = sf->dev;
    } else {
      t.params[k] = v;
    }
  }
  // As SUMO 1.15 measured: a maxSpeed given without a desiredMaxSpeed lifts the vClass's desired limit (a
  // bicycle with maxSpeed 10 m/s rides at 10 m/s).
  if (max_speed_given && !desired_max_given) t.desired_max_speed = std::numeric_limits<double>::infinity();
  // As SUMO: speedDev wins over the deviation inside speedFactor, whatever the attribute order.
  if (speed_dev || factor_dev) {
    t.speed_dev = speed_dev ? *speed_dev : *factor_dev;
    t.speed_dev_given = true;
  }

  const int depth = xs.depth();
  for (;;) {
    auto ev = xs.next();
    if (ev == XmlStream::Event::Eof)
      throw InputError(t.loc, "<vType id=\"" + t.id + "\">: unexpected end of file");
    if (ev == XmlStream::Event::End && xs.depth() == depth) break;
    if (ev != XmlStream::Event::Start || xs.depth() != depth + 1) continue;
    if (xs.name() == "param") {
      t.params[xs.required("key")] = xs.required("value");
    } else if (xs.name().starts_with("carFollowing-")) {
      read_cf_element(xs, t);
    } else {
      // Its own children (if any) are passed over by the depth test above.
      ++skipped[xs.name()];
    }
  }
  return t;
}

}  // namespace lpsim

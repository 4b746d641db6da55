#pragma once
#include <cstdint>
#include <map>
#include <string>

#include "converters/xml_stream.hpp"
#include "core/demand_spec.hpp"

namespace lpsim {

/// Overwrites the fields SUMO 1.15 sets per vehicle class (length, minGap, accel, decel, emergencyDecel,
/// maxSpeed, speedDev, sigma) with that class's defaults; passenger-like classes keep the struct's.
void apply_vclass_defaults(std::string_view vclass, VTypeSpec& type);

/// Reads a <vType> at its Start event and leaves `xs` at its End event. vClass defaults apply first, then
/// the attributes; unknown attributes, nested <param> and nested <carFollowing-X> parameters go to params
/// (a carFollowing-X element also sets the model to X and its accel/decel/emergencyDecel/sigma/tau set the
/// fields, as in SUMO). Other children are counted in `skipped`. `probability` receives the attribute of
/// that name (1 when absent), used by vTypeDistribution members.
VTypeSpec read_vtype(XmlStream& xs, std::map<std::string, int64_t>& skipped, double& probability);

}  // namespace lpsim

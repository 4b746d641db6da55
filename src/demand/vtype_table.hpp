#pragma once
// Vehicle types and vType distributions of a DemandSpec, resolved per vehicle.
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/demand_spec.hpp"
#include "demand/demand.hpp"

namespace lpsim {

inline constexpr const char* kDefaultVTypeId = "DEFAULT_VEHTYPE";

/// The CarFollowModel (kernels/idm.hpp) a vType whose carFollowModel is `name` runs: Krauss for "Krauss",
/// the IDM for "IDM" and, as a stand-in (app/load_warnings warns), for every model LPSim does not implement.
uint8_t simulated_car_follow_model(std::string_view name);

class VTypeTable {
 public:
  /// Registers every vType (in spec order) and checks every distribution; InputError for duplicate ids,
  /// unknown members, bad weights, a non-numeric IDM "delta" or shutOffStopDuration, or an emissionClass
  /// SUMO does not know. A vType that names no car-following model
  /// gets `default_model` (SUMO's --default.carfollowmodel).
  VTypeTable(const DemandSpec& spec, std::string default_model);

  /// Type index for a vehicle whose type attribute is `type_ref` (empty: DEFAULT_VEHTYPE, added on first
  /// use unless the spec defines it). A distribution id yields a member drawn for the vehicle's `stream`.
  /// InputError at `loc` naming the type and `vehicle_id` when the id is unknown.
  uint32_t resolve(const std::string& type_ref, std::string_view vehicle_id, uint64_t seed, uint64_t stream,
                   const SourceLoc& loc);

  /// Per-vehicle speed factor of type `type` (normc around the type's factor, see demand_draws.hpp).
  float speed_factor(uint32_t type, uint64_t seed, uint64_t stream) const;

  VehicleTypes take() { return std::move(types_); }
  const VehicleTypes& types() const { return types_; }

 private:
  struct Distribution {
    std::vector<uint32_t> members;  // type indices
    std::vector<double> cumulative;
  };
  uint32_t add_type(const VTypeSpec& spec);
  void add_emission_columns(const VTypeSpec& spec);
  uint32_t default_type();

  std::string default_model_;
  VehicleTypes types_;
  std::unordered_map<std::string, uint32_t> dist_index_;
  std::vector<Distribution> dists_;
};

}  // namespace lpsim

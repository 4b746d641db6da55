#pragma once
// Reads of the vehicles' state between steps, for drivers and tests (the jam report, checks): one fetch of
// the parts of the state a caller needs from the backend (a device backend copies them at most once per
// change of its state), then lookups by vehicle that copy nothing. A vehicle off the road reports its
// ledger status, lane -1, position and speed 0.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "backends/stepper.hpp"
#include "engine/engine_net.hpp"
#include "engine/trip_ledger.hpp"
#include "net/network.hpp"

namespace lpsim {

class VehicleQuery {
 public:
  /// `state`: every slot column (StateParts::Columns), or everything (Full: the signals too). `by_vehicle`:
  /// the active list as vehicle << 32 | slot, ascending.
  VehicleQuery(const HostState& state, StateParts parts, const std::vector<uint64_t>& by_vehicle,
               const TripLedger& ledger, const Network& net, const EngineNet& engine_net)
      : s_(state), parts_(parts), keys_(by_vehicle), ledger_(ledger), net_(net), engine_net_(engine_net) {
    if (parts == StateParts::Sample) throw std::logic_error("a vehicle query needs every slot column");
  }

  /// The slot vehicle v holds, else -1. A vehicle that re-entered the road right after a teleport holds its
  /// old slot for one more step (to clear its footprint) besides the new one; the new one is further along
  /// the route.
  int32_t slot(uint32_t v) const;

  uint8_t status(uint32_t v) const { return on_road(&VehicleView::status, v, ledger_.status(v)); }
  int32_t lane(uint32_t v) const { return on_road(&VehicleView::lane, v, int32_t{-1}); }
  float pos(uint32_t v) const { return on_road(&VehicleView::pos, v, 0.0f); }
  float speed(uint32_t v) const { return on_road(&VehicleView::speed, v, 0.0f); }
  uint32_t route_pos(uint32_t v) const { return on_road(&VehicleView::route_pos, v, 0u); }
  /// What bounded the vehicle's speed in its last plan (StopReason in kernels/step_view.hpp).
  uint8_t limit_reason(uint32_t v) const { return on_road(&VehicleView::limit_reason, v, uint8_t{0}); }
  /// The current character of a connection's signal link (or its state when unsignalised). StateParts::Full.
  char link_state(uint32_t conn) const;
  /// The columns by slot, for a pass over every vehicle on the road (HostState::active).
  const HostState& state() const { return s_; }

 private:
  template <class T>
  T on_road(T* VehicleView::*column, uint32_t v, T off_road) const {
    const int32_t k = slot(v);
    return k >= 0 ? (s_.veh.*column)[k] : off_road;
  }

  const HostState& s_;
  StateParts parts_;
  const std::vector<uint64_t>& keys_;
  const TripLedger& ledger_;
  const Network& net_;
  const EngineNet& engine_net_;
};

}  // namespace lpsim

#pragma once
// A vehicle's slot columns as bytes, and back: what travels with a vehicle that crosses into another part of
// a partitioned run (its `exchange()`), in the one column list (visit_vehicle_columns), so a column added to
// the list travels without more code. The bytes are the host's representation; both ends run the same build.
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "kernels/step_view.hpp"

namespace lpsim {

/// Bytes of one packed vehicle.
inline size_t packed_vehicle_bytes() {
  VehicleView none{};
  size_t bytes = 0;
  visit_vehicle_columns(
      [&](uint32_t per, auto*& column) { bytes += per * sizeof(std::remove_reference_t<decltype(*column)>); },
      none);
  return bytes;
}

/// Appends the columns of slot `slot` of `v` to `out`.
inline void pack_vehicle(const VehicleView& v, uint32_t slot, std::vector<uint8_t>& out) {
  VehicleView view = v;
  visit_vehicle_columns(
      [&](uint32_t per, auto*& column) {
        using T = std::remove_reference_t<decltype(*column)>;
        const auto* bytes = reinterpret_cast<const uint8_t*>(column + static_cast<size_t>(slot) * per);
        out.insert(out.end(), bytes, bytes + per * sizeof(T));
      },
      view);
}

/// Writes the columns of slot `slot` of `v` from `in` (as pack_vehicle wrote them); returns the bytes read.
inline size_t unpack_vehicle(const uint8_t* in, VehicleView& v, uint32_t slot) {
  size_t at = 0;
  visit_vehicle_columns(
      [&](uint32_t per, auto*& column) {
        using T = std::remove_reference_t<decltype(*column)>;
        std::memcpy(column + static_cast<size_t>(slot) * per, in + at, per * sizeof(T));
        at += per * sizeof(T);
      },
      v);
  return at;
}

}  // namespace lpsim

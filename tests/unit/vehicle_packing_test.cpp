// A vehicle's slot columns travel as bytes (pack_vehicle / unpack_vehicle): unpacked into another slot of
// another view, every column entry of the slot equals the original, and its neighbours are untouched.
#include "backends/vehicle_packing.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <type_traits>
#include <vector>

#include "backends/host_columns.hpp"
#include "kernels/rng.hpp"

namespace lpsim {
namespace {

using Columns = HostColumns<VehicleView, VisitVehicleColumns>;

// Every byte of every column of `c`'s first `slots` slots drawn from the RNG (stream `stream`).
void fill(Columns& c, size_t slots, uint64_t stream) {
  c.reserve(slots, false);
  uint64_t n = 0;
  visit_vehicle_columns(
      [&](uint32_t per, auto*& column) {
        using T = std::remove_reference_t<decltype(*column)>;
        auto* bytes = reinterpret_cast<uint8_t*>(column);
        for (size_t i = 0; i < slots * per * sizeof(T); ++i)
          bytes[i] = static_cast<uint8_t>(256 * rng_uniform(3, stream, n++));
      },
      c.view());
}

// The bytes of slot `slot` of every column, concatenated.
std::vector<uint8_t> slot_bytes(Columns& c, uint32_t slot) {
  std::vector<uint8_t> out;
  out.reserve(256);  // a slot's bytes; without it GCC 12 warns falsely (-Wstringop-overflow) on the inserts
  visit_vehicle_columns(
      [&](uint32_t per, auto*& column) {
        using T = std::remove_reference_t<decltype(*column)>;
        const auto* b = reinterpret_cast<const uint8_t*>(column + static_cast<size_t>(slot) * per);
        out.insert(out.end(), b, b + per * sizeof(T));
      },
      c.view());
  return out;
}

TEST(VehiclePackingTest, AVehicleArrivesInAnotherSlotWithEveryColumn) {
  Columns from, to;
  fill(from, 4, 1);
  fill(to, 6, 2);
  const std::vector<uint8_t> before_left = slot_bytes(to, 4), before_right = slot_bytes(to, 2);
  std::vector<uint8_t> bytes;
  pack_vehicle(from.view(), 2, bytes);
  pack_vehicle(from.view(), 0, bytes);
  EXPECT_EQ(bytes.size() % 2, 0u);
  const size_t one = unpack_vehicle(bytes.data(), to.view(), 3);
  EXPECT_EQ(one, bytes.size() / 2);
  EXPECT_EQ(unpack_vehicle(bytes.data() + one, to.view(), 5), one);
  EXPECT_EQ(slot_bytes(to, 3), slot_bytes(from, 2));
  EXPECT_EQ(slot_bytes(to, 5), slot_bytes(from, 0));
  EXPECT_EQ(slot_bytes(to, 4), before_left);
  EXPECT_EQ(slot_bytes(to, 2), before_right);
  EXPECT_NE(slot_bytes(to, 3), slot_bytes(to, 2));
}

}  // namespace
}  // namespace lpsim

// The encodings of a saved state's arrays: mostly zeros as their nonzero stretches, mostly one value as where
// they differ from it. Each must read back exactly what was written, wherever the stretches lie.
#include "backends/state_bytes.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "engine/state_archive.hpp"

namespace lpsim {
namespace {

// Bytes that are zero but for `stretches` runs of random bytes at random places, of random lengths.
std::vector<uint8_t> mostly_zeros(size_t size, int stretches, std::mt19937& rng) {
  std::vector<uint8_t> b(size, 0);
  for (int s = 0; s < stretches && size > 0; ++s) {
    const size_t at = rng() % size, length = 1 + rng() % 40;
    for (size_t i = at; i < at + length && i < size; ++i) b[i] = static_cast<uint8_t>(rng());
  }
  return b;
}

TEST(StateBytesTest, MostlyZerosReadBackExactlyAtAnyOffsetAndLength) {
  std::mt19937 rng(7);
  for (const size_t size :
       {size_t{0}, size_t{1}, size_t{7}, size_t{8}, size_t{9}, size_t{63}, size_t{4097}}) {
    for (int round = 0; round < 20; ++round) {
      std::vector<uint8_t> in = mostly_zeros(size, round % 6, rng);
      if (size > 0 && round % 5 == 0) in.back() = 1;  // a stretch that ends with the array
      // An unaligned start too: the encoder skips zeros a word at a time.
      for (const size_t skew : {size_t{0}, size_t{3}}) {
        std::vector<uint8_t> shifted(skew, 0xAB);
        shifted.insert(shifted.end(), in.begin(), in.end());
        std::vector<uint8_t> out;
        put_zero_runs(out, shifted.data() + skew, in.size());
        std::vector<uint8_t> back(in.size(), 0xCD);
        EXPECT_EQ(get_zero_runs(out.data(), out.size(), back.data(), back.size()), out.size());
        EXPECT_EQ(back, in) << "size " << size << ", round " << round << ", skew " << skew;
      }
    }
  }
}

TEST(StateBytesTest, ALongRunOfZerosCostsNoBytesButItsHeader) {
  std::vector<uint8_t> map(1 << 20, 0);
  map[12345] = 9;
  std::vector<uint8_t> out;
  put_zero_runs(out, map.data(), map.size());
  EXPECT_EQ(out.size(), 8u + 16u + 1u);  // the count, one stretch's offset and length, its byte
}

TEST(StateBytesTest, AnArrayMostlyOneValueIsSavedAsWhereItDiffers) {
  std::vector<int32_t> lanes(10000, -1);
  lanes[17] = 4;
  lanes[9000] = 0;
  StateOut out;
  out.sparse(lanes, int32_t{-1});
  EXPECT_LT(out.bytes().size(), 100u);
  std::vector<int32_t> back;
  StateIn in(out.bytes().data(), out.bytes().size(), "test state");
  in.sparse(back, int32_t{-1});
  EXPECT_TRUE(in.done());
  EXPECT_EQ(back, lanes);

  std::vector<uint32_t> stands(5000, 0xFFFFFFFFu);
  stands[3] = 12;
  StateBytesOut bytes;
  bytes.sparse(stands.data(), stands.size(), 0xFFFFFFFFu);
  EXPECT_LT(bytes.bytes().size(), 100u);
  std::vector<uint32_t> read(stands.size(), 0);
  StateBytesIn bin(bytes.bytes());
  bin.sparse(read.data(), read.size(), 0xFFFFFFFFu);
  EXPECT_TRUE(bin.done());
  EXPECT_EQ(read, stands);
}

}  // namespace
}  // namespace lpsim

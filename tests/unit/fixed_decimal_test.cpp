// The fast fixed-point formatter writes what std::to_chars writes (which rounds the exact binary value half
// to even, as printf and SUMO's iostreams do), and declines what it does not cover.
#include "converters/fixed_decimal.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

namespace lpsim {
namespace {

std::string fast(double v, int decimals) {
  char buf[64];
  char* end = write_fixed_decimal(buf, v, decimals);
  return end == nullptr ? std::string("(declined)") : std::string(buf, end);
}

std::string reference(double v, int decimals) {
  char buf[400];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  return std::string(buf, r.ptr);
}

TEST(FixedDecimal, ExactTiesRoundHalfToEven) {
  EXPECT_EQ(fast(0.125, 2), "0.12");  // 0.125 is exact in binary: a true tie
  EXPECT_EQ(fast(0.375, 2), "0.38");
  EXPECT_EQ(fast(2.5, 0), "2");
  EXPECT_EQ(fast(3.5, 0), "4");
  EXPECT_EQ(fast(0.0625, 3), "0.062");
  // 0.005 is slightly above 5/1000 in binary, 0.015 slightly below 15/1000: not ties.
  EXPECT_EQ(fast(0.005, 2), reference(0.005, 2));
  EXPECT_EQ(fast(0.015, 2), reference(0.015, 2));
}

TEST(FixedDecimal, SignsZerosAndPadding) {
  EXPECT_EQ(fast(0.0, 2), "0.00");
  EXPECT_EQ(fast(-0.0, 2), "-0.00");
  EXPECT_EQ(fast(-0.001, 2), "-0.00");
  EXPECT_EQ(fast(-12.345678, 4), "-12.3457");
  EXPECT_EQ(fast(0.0001, 4), "0.0001");
  EXPECT_EQ(fast(7.0, 0), "7");
  EXPECT_EQ(fast(999.999, 2), "1000.00");
  EXPECT_EQ(fast(123456789012345.0, 0), "123456789012345");
}

TEST(FixedDecimal, DeclinesWhatItDoesNotCover) {
  EXPECT_EQ(fast(1.0, 5), "(declined)");
  EXPECT_EQ(fast(1.0, -1), "(declined)");
  EXPECT_EQ(fast(1e15, 2), "(declined)");
  EXPECT_EQ(fast(-2e300, 2), "(declined)");
  EXPECT_EQ(fast(std::nan(""), 2), "(declined)");
  EXPECT_EQ(fast(INFINITY, 2), "(declined)");
}

TEST(FixedDecimal, EqualsToCharsOnGridsAndRandomValues) {
  std::mt19937_64 rng(20261123);
  int mismatches = 0;
  auto check = [&](double v, int d) {
    if (fast(v, d) != reference(v, d) && ++mismatches <= 5)
      ADD_FAILURE() << "v=" << v << " decimals=" << d << ": " << fast(v, d) << " vs " << reference(v, d);
  };
  for (int d = 0; d <= kMaxFastDecimals; ++d) {
    // Grids dense in ties and near-ties: multiples of 1/8, 1/64, and of the decimal steps themselves.
    for (int64_t i = -20000; i <= 20000; ++i) {
      check(static_cast<double>(i) / 8.0, d);
      check(static_cast<double>(i) / 64.0, d);
      check(static_cast<double>(i) * 0.005, d);
      check(static_cast<double>(i) / 1000.0, d);
      check(static_cast<double>(i) / 100000.0, d);
    }
    // Random magnitudes from 1e-3 to 1e12, as doubles and as values that came from floats.
    for (int k = 0; k < 200000; ++k) {
      double x = std::ldexp(static_cast<double>(rng() >> 11), -53) *
                 std::pow(10.0, static_cast<double>(rng() % 16) - 3.0);
      if ((rng() & 1u) != 0) x = -x;
      check(x, d);
      check(static_cast<double>(static_cast<float>(x)), d);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace lpsim

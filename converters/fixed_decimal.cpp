#include "converters/fixed_decimal.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace lpsim {

// v * 10^d is exact in long double for d <= 4: 10^d is 5^d * 2^d, 5^4 needs 10 bits, and a double's 53
// bits times 10 bits fit in the 64-bit mantissa. Rounding that exact product to an integer in the default
// mode (to nearest, ties to even) is then the correctly rounded decimal text.
static_assert(std::numeric_limits<long double>::digits >= 64,
              "write_fixed_decimal needs a long double with a 64-bit mantissa (x86's extended precision)");

char* write_fixed_decimal(char* out, double v, int decimals) {
  static constexpr long double kScale[kMaxFastDecimals + 1] = {1.0L, 10.0L, 100.0L, 1000.0L, 10000.0L};
  if (decimals < 0 || decimals > kMaxFastDecimals || !(std::fabs(v) < 1e15)) return nullptr;
  const long double scaled = static_cast<long double>(std::fabs(v)) * kScale[decimals];
  // Rounded to nearest, ties to even, by hand: the truncation and its remainder are exact (the integer part
  // of a long double below 2^64 fits a uint64_t), and nearbyintl is a library call per number.
  uint64_t n = static_cast<uint64_t>(scaled);  // < 1e19: fits
  const long double rest = scaled - static_cast<long double>(n);
  if (rest > 0.5L || (rest == 0.5L && (n & 1u) != 0)) ++n;
  char digits[24];  // least significant first
  int len = 0;
  do {
    digits[len++] = static_cast<char>('0' + n % 10);
    n /= 10;
  } while (n != 0);
  while (len <= decimals) digits[len++] = '0';  // at least one digit before the point
  if (std::signbit(v)) *out++ = '-';
  for (int k = len - 1; k >= decimals; --k) *out++ = digits[k];
  if (decimals > 0) {
    *out++ = '.';
    for (int k = decimals - 1; k >= 0; --k) *out++ = digits[k];
  }
  return out;
}

}  // namespace lpsim

#pragma once
// Fixed-point text of a double with a few decimals, as std::to_chars(..., chars_format::fixed, decimals)
// writes it (the exact binary value rounded half to even, "-" for negative values and negative zero), for
// the common case only: decimals 0 to 4 and magnitudes below 1e15. Outputs write such numbers by the
// million; to_chars' general algorithm costs several hundred instructions each.

namespace lpsim {

constexpr int kMaxFastDecimals = 4;

/// Writes v with `decimals` digits after the point at `out` and returns the end of the text; returns nullptr
/// (writing nothing) where the fast path does not apply (decimals outside [0, kMaxFastDecimals], |v| >=
/// 1e15, NaN or infinite): the caller then uses std::to_chars. At most 22 characters are written.
char* write_fixed_decimal(char* out, double v, int decimals);

}  // namespace lpsim

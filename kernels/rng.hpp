#pragma once
// Counter-based random numbers: a value is a pure function of (seed, stream, counter), so any thread, any
// backend and any partitioning draws the same numbers for the same vehicle and step. The mixer is
// SplitMix64's finaliser applied to a combination of the keys (good avalanche, cheap on GPUs).
#include <cstdint>

#include "kernels/hd.hpp"

namespace lpsim {

LPSIM_HD uint64_t rng_mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// 64 random bits for (seed, stream, counter); stream is e.g. a vehicle index, counter a step number.
LPSIM_HD uint64_t rng_bits(uint64_t seed, uint64_t stream, uint64_t counter) {
  return rng_mix64(rng_mix64(rng_mix64(seed) ^ stream) ^ (counter * 0xD1B54A32D192ED03ull));
}

/// Uniform float in [0, 1) with 24 random bits (exact in float, identical on every backend).
LPSIM_HD float rng_uniform(uint64_t seed, uint64_t stream, uint64_t counter) {
  return static_cast<float>(rng_bits(seed, stream, counter) >> 40) * (1.0f / 16777216.0f);
}

/// Uniform double in [0, 1) with 53 random bits (demand draws while loading; departure draws).
LPSIM_HD double rng_uniform_double(uint64_t seed, uint64_t stream, uint64_t counter) {
  return static_cast<double>(rng_bits(seed, stream, counter) >> 11) * (1.0 / 9007199254740992.0);
}

/// Stable 64-bit hash of a string (FNV-1a), to key draws by a vehicle's id rather than its load order.
inline uint64_t rng_hash(const char* s, uint64_t n) {
  uint64_t h = 0xCBF29CE484222325ull;
  for (uint64_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 0x100000001B3ull;
  return h;
}

}  // namespace lpsim

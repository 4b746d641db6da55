#pragma once
// Random draws made while building demand. Every draw is a pure function of (seed, a hash of the id of
// the vehicle or flow it belongs to, a counter), so results do not depend on load order, threads or on
// which other vehicles exist. Counters for per-vehicle draws have the top bit set so they can never meet
// the small step counters that per-step draws (flow probabilities here, the engine's draws later) use.
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/demand_spec.hpp"
#include "kernels/rng.hpp"

namespace lpsim {

inline constexpr uint64_t kDrawVTypeMember = 0x8000000000000001ull;
inline constexpr uint64_t kDrawRouteMember = 0x8000000000000002ull;
inline constexpr uint64_t kDrawSpeedFactor = 0x8000000000000100ull;  // + 2 per attempt
inline constexpr uint64_t kDrawReroutingDevice = 0x8000000000000003ull;

/// Mixed into the seed of the random edge-cost factors (--weights.random-factor), whose counters are edge
/// indices: small numbers that per-step draws use too.
inline constexpr uint64_t kSeedRandomWeights = 0x5745494748545321ull;

/// SUMO's default bounds of the speed factor distribution normc(mean, dev, 0.2, 2.0).
inline constexpr double kSpeedFactorMin = 0.2, kSpeedFactorMax = 2.0;

/// Stream of the draws that belong to `id` (a vehicle id, or a flow id for its per-step draws).
inline uint64_t draw_stream(std::string_view id) { return rng_hash(id.data(), id.size()); }

/// Index of the member picked with probability proportional to `weights` (all >= 0, sum > 0).
uint32_t draw_weighted(const std::vector<double>& cumulative_weights, uint64_t seed, uint64_t stream,
                       uint64_t counter);

/// Speed factor from normal(mean, dev) truncated to [0.2, 2.0] like SUMO's normc: out-of-range values
/// are drawn again (a bounded number of times, then clamped). dev <= 0 gives the mean, as in SUMO.
double draw_speed_factor(double mean, double dev, uint64_t seed, uint64_t stream);

}  // namespace lpsim

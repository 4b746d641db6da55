#pragma once
// Expansion of a <flow> into the departure times of its vehicles, following SUMO 1.15:
//  - times are computed in integer milliseconds as SUMO does (period and 3600/vehsPerHour rounded to ms);
//  - period / vehsPerHour without number: vehicles at begin + n*period for n < ceil((end - begin) / period);
//  - period / vehsPerHour with number: `number` vehicles at begin + n*period (end may not be given);
//  - number alone: period = (end - begin) / number (integer ms division), end defaulting as below;
//  - probability p: one Bernoulli draw with p * step_length (p is per second, as SUMO scales it) at every
//    simulation step k*step_length in [begin, end), at most one vehicle per step, stopping after `number`
//    vehicles when number is given (then end may not be given and the flow runs until number is reached);
//  - end not given and no (rate, number) pair that bounds the flow: begin + 24 h, SUMO's default.
// Vehicles are named "<flow id>.<n>", n from 0 (the caller builds the ids).
#include <cstdint>
#include <vector>

#include "core/demand_spec.hpp"

namespace lpsim {

/// Departure times (s, ascending) of the vehicles `flow` generates. The probability draws are keyed by
/// (seed, hash of the flow id, step index). InputError at the flow's location for inconsistent attributes
/// (several rates, end together with number, non-positive rate, probability outside (0, 1], end < begin,
/// negative begin or number) and for flows that would create more than a billion vehicles.
std::vector<double> flow_departures(const FlowSpec& flow, uint64_t seed, double step_length);

}  // namespace lpsim

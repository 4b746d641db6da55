#pragma once
// The emissions pass, run after the commit pass only when an emissions edgeData/laneData output is
// requested: each vehicle that was on the road as the step began adds its step to the emission sums of every
// lane its body covered in it, as SUMO 1.15 counts a vehicle's move in its emission meandata
// (MSMeanData_Emissions, Euler update; docs/MODELS.md "Emissions"):
//   - the rates are those of the step's new speed v and acceleration (v - v_old) / dt (emissions.hpp);
//   - each lane gets rate x the time any part of the body was on it (time_on_lane: front entering and back
//     leaving within the step interpolated at constant speed), and that time and time x v as the sampled
//     seconds and distance; a vehicle across a lane boundary counts on both lanes;
//   - a lane change counts on the old lanes in its step; from then on the lanes the back still covers no
//     longer count the vehicle (SUMO drops it there), only lanes entered later do;
//   - an arrival's step counts as if the vehicle drove on past its arrival point at its new speed;
//   - the engine is off (all rates 0) through a scheduled stop planned longer than the type's
//   shutOffStopDuration.
// The step's own columns are read as the commit pass left them; the pass keeps two of its own (the speed at
// the step's start, EmissionFlags).
#include <stdint.h>

#include "kernels/atomics.hpp"
#include "kernels/emissions.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

/// The lanes a vehicle's body may have covered in a step, in path order, each with the distance along the
/// path from the start of the lane its front was on as the step began to its own start.
struct PathLanes {
  static constexpr int kMax = 5;  // two tail lanes, the front's lane and up to two lanes entered
  int32_t lane[kMax];
  double start[kMax];
  int n = 0;

  LPSIM_HD void add(int32_t l, double s) {
    lane[n] = l;
    start[n] = s;
    ++n;
  }
};

/// An amount as the integer sums keep it: millionths, rounded (amounts are never negative).
LPSIM_HD int64_t millionths(double x) { return static_cast<int64_t>(x * 1e6 + 0.5); }

LPSIM_HD void count_vehicle_emissions(StepContext& s, uint32_t i, uint32_t slot) {
  const VehicleView& veh = s.veh;
  const int32_t lane = veh.old_lane[slot];
  if (lane < 0) return;  // not on the road as the step began (entered at its end, or left before it)
  const NetView& net = s.net;
  const EmissionView& em = s.em;
  const uint32_t type = veh.trip_type[slot];
  const double dt = s.params.dt;
  const double pos = veh.old_pos[slot];

  // Where the front ended. An arrival's plan was kept whole (a lost claim cancels the arrival); the lane
  // columns of an arrived vehicle no longer tell its path.
  const bool arrived = veh.status[slot] == kArrived;
  const int32_t nlane = arrived ? s.plan.new_lane[i] : veh.lane[slot];
  const int32_t nprev = arrived ? s.plan.new_prev[i] : veh.prev[slot];
  const int32_t nprev2 = arrived ? s.plan.new_prev2[i] : veh.prev2[slot];
  const double speed = arrived ? s.plan.new_speed[i] : veh.speed[slot];
  const bool lane_change = veh.lane_change_dir[slot] != 0;
  const int hops = nlane == lane || lane_change   ? 0
                   : nprev == lane                ? 1
                   : nprev2 == lane && nprev >= 0 ? 2
                                                  : 0;
  const double lane_length = net.lane_length[lane];
  double advance = speed * dt;  // an arrival: driving on at its speed
  if (!arrived) {
    const double npos = veh.pos[slot];
    advance = hops == 0   ? npos - pos
              : hops == 1 ? lane_length - pos + npos
                          : lane_length - pos + net.lane_length[nprev] + npos;
    advance = advance > 0.0 ? advance : 0.0;
  }

  uint8_t flags = veh.emission_flags[slot];
  const int tail = flags & kEmissionTailLanes;
  PathLanes path;
  const int32_t prev = veh.old_prev[slot], prev2 = veh.old_prev2[slot];
  if (tail >= 2 && prev >= 0 && prev2 >= 0)
    path.add(prev2, -static_cast<double>(net.lane_length[prev]) - net.lane_length[prev2]);
  if (tail >= 1 && prev >= 0) path.add(prev, -static_cast<double>(net.lane_length[prev]));
  path.add(lane, 0.0);
  if (hops >= 2) path.add(nprev, lane_length);
  if (hops >= 1) path.add(nlane, hops == 1 ? lane_length : lane_length + net.lane_length[nprev]);

  // The engine's state at a scheduled stop is decided when the vehicle gets there, from the stop's planned
  // length (its release step was set then).
  const uint32_t release = veh.stop_release[slot];
  if (release <= s.params.step) {
    flags &= static_cast<uint8_t>(~(kEmissionAtStop | kEmissionEngineOff));
  } else if ((flags & kEmissionAtStop) == 0) {
    const double planned = static_cast<double>(release - s.params.step) * dt;
    flags |= kEmissionAtStop | (planned > em.shut_off_stop[type] ? kEmissionEngineOff : 0);
  }
  double rate[kNumPollutants];
  emission_rates(em.model[type], em.coeff + static_cast<size_t>(type) * kCoefficientsPerClass,
                 CoastingParams{em.coast_incl[type], em.coast_mass_term[type]}, speed,
                 (speed - veh.emission_speed[slot]) / dt, (flags & kEmissionEngineOff) != 0,
                 em.fuel_divisor[type], rate);

  const double length = s.types.length[type];
  const size_t nl = em.num_lanes;
  for (int k = 0; k < path.n; ++k) {
    const int32_t l = path.lane[k];
    const double t =
        time_on_lane(pos - path.start[k], pos + advance - path.start[k], length, net.lane_length[l], dt);
    if (t <= 0.0) continue;
    int64_t* sums = em.sums + l;
    atomic_add_i64(sums + kEmissionMicroseconds * nl, millionths(t));
    atomic_add_i64(sums + kEmissionMicrometres * nl, millionths(t * speed));
    for (int p = 0; p < kNumPollutants; ++p)
      atomic_add_i64(sums + emission_mass_sum(p) * nl, millionths(rate[p] * t));
  }

  const int entered = tail + hops < 2 ? tail + hops : 2;
  flags = static_cast<uint8_t>((flags & ~kEmissionTailLanes) | (lane_change ? 0 : entered));
  veh.emission_flags[slot] = flags;
  veh.emission_speed[slot] = veh.speed[slot];
}

}  // namespace lpsim

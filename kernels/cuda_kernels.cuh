#pragma once
// The CUDA backend's kernels: thin __global__ wrappers over the same functions the CPU backend loops over
// (kernels/vehicle_step.hpp, kernels/emission_step.hpp, kernels/signal_step.hpp, kernels/insert_vehicle.hpp),
// one thread per active
// vehicle, per signal, per edge with waiting vehicles, or per entry of what the host hands over; and the few
// device-only steps of the backend's bookkeeping (the end-of-step tally, the slot sort's gathers). Included
// by the one CUDA translation unit, backends/cuda/cuda_stepper.cu, built by nvcc or against the host
// emulation in tests/cuda_emulation.
#include <stdint.h>

#include "kernels/emission_step.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/signal_step.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

constexpr uint32_t kBlock = 128;

__global__ void signals_kernel(SignalTable table, int64_t time_ms, SignalInputs in, char* link_state,
                               int64_t* next_switch_ms, ActuatedState st) {
  const uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s < table.num_signals) update_signal(table, s, time_ms, in, link_state, next_switch_ms, st);
}

// One thread per active vehicle, running one of the step's passes (the same functions the CPU backend loops
// over).
template <void (*VehiclePass)(StepContext&, uint32_t, uint32_t)>
__global__ void __launch_bounds__(kBlock, 8)
    pass_kernel(StepContext ctx, const uint32_t* active, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) VehiclePass(ctx, i, active[i]);
}

/// What the host reads after a step's passes (StepOutcome).
struct StepTally {
  uint32_t kept;
  uint32_t running;
  uint32_t ends;
};

// After the commit pass: records arrivals and teleports, flags the vehicles that stay active and counts
// them. Every thread of a block reaches the block-wide counts (no early return).
__global__ void finish_kernel(VehicleView veh, const uint32_t* active, uint32_t n, uint32_t steps_done,
                              uint32_t teleport_steps, uint8_t* keep, VehicleEnd* ends, StepTally* tally) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  bool kept = false, running = false;
  if (i < n) {
    const uint32_t k = active[i];
    const uint32_t kind = step_end_kind(veh, k, steps_done, teleport_steps);
    if (kind != kEndNone) ends[atomicAdd(&tally->ends, 1u)] = vehicle_end(veh, k, kind);
    kept = stays_active(veh, k);
    running = kept && veh.status[k] == kRunning;
    keep[i] = kept ? 1 : 0;
  }
#if defined(__CUDACC__)
  const int k = __syncthreads_count(kept), r = __syncthreads_count(running);
  if (threadIdx.x == 0) {
    if (k > 0) atomicAdd(&tally->kept, static_cast<uint32_t>(k));
    if (r > 0) atomicAdd(&tally->running, static_cast<uint32_t>(r));
  }
#else  // host emulation: a block's threads run one at a time, so there is no barrier to count at
  if (kept) atomicAdd(&tally->kept, 1u);
  if (running) atomicAdd(&tally->running, 1u);
#endif
}

__global__ void teleport_kernel(VehicleView veh, const TeleportMove* moves, uint32_t n, uint32_t steps_done) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) apply_teleport_move(veh, moves[i], steps_done);
}

__global__ void insert_kernel(StepContext ctx, DepartView depart, InsertParams p, uint8_t* map,
                              InsertBatch b) {
  const uint32_t slot = blockIdx.x * blockDim.x + threadIdx.x;
  if (slot < b.num_slots) insert_queue_head(ctx, depart, p, map, b, slot);
}

__global__ void activate_kernel(VehicleView veh, TripView trips, const SlotInit* inits, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) activate_slot(veh, trips, inits[i]);
}

__global__ void sample_kernel(VehicleView veh, const uint32_t* active, uint32_t n, uint32_t* vehicle,
                              uint8_t* status, int32_t* lane, float* pos, float* speed,
                              uint32_t* stop_release) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const uint32_t k = active[i];
  vehicle[i] = veh.vehicle[k];
  stop_release[i] = veh.stop_release[k];
  status[i] = veh.status[k];
  lane[i] = veh.lane[k];
  pos[i] = veh.pos[k];
  speed[i] = veh.speed[k];
}

// Slot sort (Simulation::sort_slots): each active slot's lane as an unsigned key (-1, off the road, last).
__global__ void lane_key_kernel(VehicleView veh, const uint32_t* active, uint32_t n, uint32_t* key) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) key[i] = static_cast<uint32_t>(veh.lane[active[i]]);
}

// to[i * per + e] = from[order[i] * per + e]: a slot column's entries in their new slots.
template <class T>
__global__ void gather_slots_kernel(const T* from, T* to, const uint32_t* order, uint32_t n, uint32_t per) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  for (uint32_t e = 0; e < per; ++e) to[size_t{i} * per + e] = from[size_t{order[i]} * per + e];
}

// inverse[order[i]] = i: the new number of each slot that was active.
__global__ void invert_order_kernel(const uint32_t* order, uint32_t n, uint32_t* inverse) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) inverse[order[i]] = i;
}

// Each asked slot's new number (kNotActive where it was not active or lies beyond the columns).
__global__ void renumber_kernel(const uint32_t* inverse, uint32_t capacity, uint32_t* slots, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) slots[i] = slots[i] < capacity ? inverse[slots[i]] : kNotActive;
}

__global__ void iota_kernel(uint32_t* out, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = i;
}

struct AscendingIndex {
  __device__ bool operator()(uint32_t a, uint32_t b) const { return a < b; }
};

__global__ void route_kernel(VehicleView veh, const SlotRoute* routes, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) set_slot_route(veh, routes[i]);
}

// Trips whose route changed: route_begin and route_length of vehicle changed[3i] become changed[3i+1] and
// changed[3i+2].
__global__ void trip_route_kernel(uint32_t* route_begin, uint32_t* route_length, const uint32_t* changed,
                                  uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  route_begin[changed[3 * i]] = changed[3 * i + 1];
  route_length[changed[3 * i]] = changed[3 * i + 2];
}

// The exchanges of a partitioned run: one launch for each, not one copy per lane or vehicle.
// to[i] = from[index[i]].
template <class T>
__global__ void gather_kernel(const T* from, const uint32_t* index, uint32_t n, T* to) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) to[i] = from[index[i]];
}

// to[index[i]] = from[i]; the indices are distinct, so no two threads write one entry.
template <class T>
__global__ void scatter_kernel(const T* from, const uint32_t* index, uint32_t n, T* to) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) to[index[i]] = from[i];
}

// to[index[i]] = max(to[index[i]], from[i]) for distinct indices: claims merged from another part.
__global__ void raise_kernel(const uint64_t* from, const uint32_t* index, uint32_t n, uint64_t* to) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n && from[i] > to[index[i]]) to[index[i]] = from[i];
}

// to[index[i]] = value for distinct indices.
template <class T>
__global__ void fill_at_kernel(T value, const uint32_t* index, uint32_t n, T* to) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) to[index[i]] = value;
}

// Vehicles packed row by row (each row one vehicle's entries of every column, `stride` bytes): the bytes
// [offset, offset + row) of row i go to slot slot[i] of a column whose slots are `row` bytes each.
__global__ void unpack_rows_kernel(const uint8_t* packed, uint32_t stride, uint32_t offset, uint32_t row,
                                   const uint32_t* slot, uint32_t n, uint8_t* column) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  for (uint32_t b = 0; b < row; ++b)
    column[size_t{slot[i]} * row + b] = packed[size_t{i} * stride + offset + b];
}

}  // namespace lpsim

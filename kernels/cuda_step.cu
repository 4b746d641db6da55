// CUDA backend: thin kernels over the same step functions the CPU backend runs (kernels/vehicle_step.hpp,
// kernels/signal_step.hpp), one thread per active vehicle or per signal, and the GpuStepper that owns the
// device arrays. Built with --fmad=false (and the CPU with -ffp-contract=off), so both compute bit-identical
// floats; the only read-modify-writes are integer atomics, whose result does not depend on thread order.
//
// What crosses the bus per step. This first integration keeps the host work of the CPU backend (arrivals,
// teleports, insertion, rebuilding the active list) on the host, so the stepper mirrors what it touches:
//   host -> device before the passes:
//     - the active list;
//     - the vehicle-state columns (VehicleView) over the index range [first active, last active]: the host
//       inserted vehicles there and moved teleporting ones on; the device touches no vehicle outside it;
//     - the lane map the step reads (the host wrote the footprints of inserted vehicles into it).
//   device -> host after the passes:
//     - the same vehicle-state range (arrivals, teleports, FCD, tripinfo and summary read it);
//     - the lane map the step wrote (insertion checks free cells in it);
//     - the step's per-lane counter increments, added to the host's counters.
// Uploaded once: network, signal programs, vehicle types, trips, the initial plan scratch, lane approaches,
// claims and merge requests. Link states, plan scratch, approaches, claims and merge requests then live on
// the device only.
// Next step (what the issue asks for): move insertion, teleports and the active-list compaction to the
// device, so that nothing but outputs (FCD samples, finished trips, counters at interval ends) is copied.
#include <cuda_runtime.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/gpu_stepper.hpp"
#include "kernels/signal_step.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

namespace {

constexpr uint32_t kBlock = 128;

uint32_t blocks_for(uint32_t n) { return (n + kBlock - 1) / kBlock; }

void check(cudaError_t rc, const char* call, const char* file, int line) {
  if (rc == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA call ") + call + " failed at " + file + ":" + std::to_string(line) +
                           ": " + cudaGetErrorName(rc) + " (" + cudaGetErrorString(rc) + ")");
}

#define LPSIM_CUDA_CHECK(call) check((call), #call, __FILE__, __LINE__)
// Launch errors (bad configuration, no kernel image) surface here; faults inside a kernel at the next sync.
#define LPSIM_CUDA_CHECK_LAUNCH(kernel) check(cudaGetLastError(), "launch of " #kernel, __FILE__, __LINE__)

__global__ void signals_kernel(SignalTable table, int64_t time_ms, char* link_state) {
  const uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s < table.num_signals) update_signal(table, s, time_ms, link_state);
}

// One thread per active vehicle, running one of the step's passes (the same functions the CPU backend loops over).
template <void (*VehiclePass)(StepContext&, uint32_t)>
__global__ void pass_kernel(StepContext ctx, const uint32_t* active, uint32_t n) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) VehiclePass(ctx, active[i]);
}

/// One cudaMalloc'd allocation, freed with its owner.
class DeviceBuffer {
 public:
  explicit DeviceBuffer(size_t bytes) { LPSIM_CUDA_CHECK(cudaMalloc(&ptr_, std::max<size_t>(bytes, 1))); }
  DeviceBuffer(DeviceBuffer&& other) noexcept : ptr_(other.ptr_) { other.ptr_ = nullptr; }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(DeviceBuffer&&) = delete;
  ~DeviceBuffer() {
    if (ptr_ != nullptr) cudaFree(ptr_);  // no throw from a destructor; a failed free leaks at worst
  }
  void* get() const { return ptr_; }

 private:
  void* ptr_ = nullptr;
};

template <class T>
void copy_to_device(T* dst, const T* src, size_t n) {
  if (n > 0) LPSIM_CUDA_CHECK(cudaMemcpy(dst, src, n * sizeof(T), cudaMemcpyHostToDevice));
}

template <class T>
void copy_to_host(T* dst, const T* src, size_t n) {
  if (n > 0) LPSIM_CUDA_CHECK(cudaMemcpy(dst, src, n * sizeof(T), cudaMemcpyDeviceToHost));
}

// The stepper lists every column of the views by hand: a column added to one of them must be added here.
static_assert(sizeof(VehicleView) == 22 * sizeof(void*), "VehicleView changed: update for_each_vehicle_column");
static_assert(sizeof(PlanView) == 13 * sizeof(void*), "PlanView changed: update the plan uploads in CudaStepper");
static_assert(sizeof(NetView) == 20 * sizeof(void*) + sizeof(void*), "NetView changed: update upload_network");
static_assert(sizeof(TypeView) == 8 * sizeof(void*) && sizeof(TripView) == 7 * sizeof(void*),
              "TypeView or TripView changed: update upload_demand");
static_assert(sizeof(StepContext) == sizeof(NetView) + sizeof(TypeView) + sizeof(TripView) + sizeof(VehicleView) +
                                         sizeof(PlanView) + sizeof(StepParams) + 16 * sizeof(void*),
              "StepContext changed: update CudaStepper");

/// Calls f(a.column, b.column) for every column of two vehicle views (a may be written: f gets references).
template <class A, class B, class F>
void for_each_vehicle_column(A& a, B& b, F&& f) {
  f(a.status, b.status);
  f(a.route_pos, b.route_pos);
  f(a.speed, b.speed);
  f(a.lane, b.lane);
  f(a.prev, b.prev);
  f(a.prev2, b.prev2);
  f(a.pos, b.pos);
  f(a.old_lane, b.old_lane);
  f(a.old_prev, b.old_prev);
  f(a.old_prev2, b.old_prev2);
  f(a.old_pos, b.old_pos);
  f(a.stopped_steps, b.stopped_steps);
  f(a.waiting_steps, b.waiting_steps);
  f(a.waiting_count, b.waiting_count);
  f(a.time_loss, b.time_loss);
  f(a.route_length, b.route_length);
  f(a.arrival_step, b.arrival_step);
  f(a.lane_change_dir, b.lane_change_dir);
  f(a.held_at_line, b.held_at_line);
  f(a.limit_reason, b.limit_reason);
  f(a.best_rp, b.best_rp);
  f(a.best_mask, b.best_mask);
}

constexpr int kNumCounters = 8;

class CudaStepper final : public GpuStepper {
 public:
  CudaStepper(const StepContext& host, const SignalTable& signals, const GpuStepSizes& sizes) {
    upload_network(host.net, sizes);
    upload_signals(signals);
    upload_demand(host, sizes);
    const uint32_t nv = sizes.num_vehicles, nl = host.net.num_lanes;

    for_each_vehicle_column(dev_.veh, host.veh, [&](auto*& dev, auto* h) { dev = upload(h, nv); });

    // Plan scratch carries nothing the host reads, but a pass may read an entry it did not write this step
    // (a claim priority, say): start from the host's values so both backends see the same ones.
    PlanView& plan = dev_.plan;
    plan.new_speed = upload(host.plan.new_speed, nv);
    plan.new_lane = upload(host.plan.new_lane, nv);
    plan.new_pos = upload(host.plan.new_pos, nv);
    plan.new_prev = upload(host.plan.new_prev, nv);
    plan.new_prev2 = upload(host.plan.new_prev2, nv);
    plan.claim_lane0 = upload(host.plan.claim_lane0, nv);
    plan.claim_lane1 = upload(host.plan.claim_lane1, nv);
    plan.stop_pos = upload(host.plan.stop_pos, nv);
    plan.stop_lane = upload(host.plan.stop_lane, nv);
    plan.arrives = upload(host.plan.arrives, nv);
    plan.new_rp = upload(host.plan.new_rp, nv);
    plan.first_rp = upload(host.plan.first_rp, nv);
    plan.claim_prio = upload(host.plan.claim_prio, nv);

    dev_.approach = upload(host.approach, nl);
    dev_.claims = upload(host.claims, nl);
    dev_.merge_requests = upload(host.merge_requests, nl);
    const size_t nc = sizes.num_connections;
    dev_.yielder_begin = upload(host.yielder_begin, nc + 1);
    dev_.yielder = upload(host.yielder, host.yielder_begin[nc]);

    // The counters of one step, contiguous so that one memset clears them and one copy fetches them.
    int64_t* counters = allocate<int64_t>(static_cast<size_t>(kNumCounters) * nl);
    int64_t** columns[kNumCounters] = {&dev_.cnt_sampled_steps, &dev_.cnt_travelled_mm,  &dev_.cnt_waiting_steps,
                                       &dev_.cnt_time_loss_ms,  &dev_.cnt_occupied_mm_steps, &dev_.cnt_entered,
                                       &dev_.cnt_left,          &dev_.cnt_arrived};
    for (int k = 0; k < kNumCounters; ++k) *columns[k] = counters + static_cast<size_t>(k) * nl;
    counters_ = counters;
    counter_delta_.resize(static_cast<size_t>(kNumCounters) * nl);

    cells_ = host.net.lane_cell_begin[nl];
    for (auto& m : map_) m = allocate<uint8_t>(cells_);
    active_ = allocate<uint32_t>(nv);
  }

  void step(const StepContext& host, const uint32_t* active, uint32_t n) override {
    StepContext ctx = dev_;
    ctx.params = host.params;
    ctx.map_now = device_map(host.map_now, true);
    ctx.map_next = device_map(host.map_next, false);
    if (signals_.num_signals > 0) {
      signals_kernel<<<blocks_for(signals_.num_signals), kBlock>>>(signals_, host.params.time_ms, link_state_);
      LPSIM_CUDA_CHECK_LAUNCH(signals_kernel);
    }
    if (n == 0) return;  // nothing on the road: no pass writes anything

    // Active vehicles are ascending, so [lo, hi) holds every vehicle the passes touch.
    const size_t lo = active[0], hi = static_cast<size_t>(active[n - 1]) + 1;
    copy_to_device(active_, active, n);
    for_each_vehicle_column(dev_.veh, host.veh, [&](auto* dev, auto* h) { copy_to_device(dev + lo, h + lo, hi - lo); });
    const size_t nl = host.net.num_lanes;
    LPSIM_CUDA_CHECK(cudaMemset(counters_, 0, kNumCounters * nl * sizeof(int64_t)));

    const uint32_t grid = blocks_for(n);
    pass_kernel<clear_old_footprint><<<grid, kBlock>>>(ctx, active_, n);
    LPSIM_CUDA_CHECK_LAUNCH(clear_old_footprint);
    pass_kernel<approach_vehicle><<<grid, kBlock>>>(ctx, active_, n);
    LPSIM_CUDA_CHECK_LAUNCH(approach_vehicle);
    pass_kernel<plan_vehicle><<<grid, kBlock>>>(ctx, active_, n);
    LPSIM_CUDA_CHECK_LAUNCH(plan_vehicle);
    pass_kernel<commit_vehicle><<<grid, kBlock>>>(ctx, active_, n);
    LPSIM_CUDA_CHECK_LAUNCH(commit_vehicle);
    LPSIM_CUDA_CHECK(cudaDeviceSynchronize());  // a fault inside the passes is reported here

    for_each_vehicle_column(dev_.veh, host.veh, [&](auto* dev, auto* h) { copy_to_host(h + lo, dev + lo, hi - lo); });
    copy_to_host(host.map_next, ctx.map_next, cells_);
    copy_to_host(counter_delta_.data(), counters_, counter_delta_.size());
    int64_t* const host_columns[kNumCounters] = {host.cnt_sampled_steps, host.cnt_travelled_mm,
                                                 host.cnt_waiting_steps, host.cnt_time_loss_ms,
                                                 host.cnt_occupied_mm_steps, host.cnt_entered,
                                                 host.cnt_left,          host.cnt_arrived};
    for (int k = 0; k < kNumCounters; ++k) {
      const int64_t* delta = counter_delta_.data() + static_cast<size_t>(k) * nl;
      for (size_t l = 0; l < nl; ++l) host_columns[k][l] += delta[l];
    }
  }

 private:
  template <class T>
  T* allocate(size_t n) {
    buffers_.emplace_back(n * sizeof(T));
    return static_cast<T*>(buffers_.back().get());
  }

  template <class T>
  T* upload(const T* host, size_t n) {
    T* dev = allocate<T>(n);
    copy_to_device(dev, host, n);
    return dev;
  }

  void upload_network(const NetView& h, const GpuStepSizes& sizes) {
    const uint32_t nl = h.num_lanes, ne = sizes.num_edges, nc = sizes.num_connections;
    NetView& d = dev_.net;
    d.num_lanes = nl;
    d.lane_cell_begin = upload(h.lane_cell_begin, nl + 1);
    d.lane_length = upload(h.lane_length, nl);
    d.lane_speed = upload(h.lane_speed, nl);
    d.lane_edge = upload(h.lane_edge, nl);
    d.lane_internal = upload(h.lane_internal, nl);
    d.lane_left = upload(h.lane_left, nl);
    d.lane_right = upload(h.lane_right, nl);
    d.lane_conn_begin = upload(h.lane_conn_begin, nl + 1);
    d.edge_first_lane = upload(h.edge_first_lane, ne);
    d.edge_num_lanes = upload(h.edge_num_lanes, ne);
    d.conn_to_lane = upload(h.conn_to_lane, nc);
    d.conn_via_lane = upload(h.conn_via_lane, nc);
    d.conn_to_edge = upload(h.conn_to_edge, nc);
    d.conn_from_lane = upload(h.conn_from_lane, nc);
    d.conn_signal = upload(h.conn_signal, nc);
    d.conn_link_index = upload(h.conn_link_index, nc);
    d.conn_state = upload(h.conn_state, nc);
    d.conn_foe_begin = upload(h.conn_foe_begin, static_cast<size_t>(nc) + 1);
    d.conn_foe = upload(h.conn_foe, h.conn_foe_begin[nc]);
  }

  void upload_signals(const SignalTable& h) {
    const uint32_t ns = h.num_signals;
    // NetView's signal_link_begin is the same table as the signal program's link_begin.
    dev_.net.signal_link_begin = upload(h.link_begin, static_cast<size_t>(ns) + 1);
    link_state_ = allocate<char>(h.link_begin[ns]);
    dev_.link_state = link_state_;
    signals_ = SignalTable{};
    signals_.num_signals = ns;
    if (ns == 0) return;
    const uint32_t phases = h.phase_begin[ns];
    size_t chars = 0;  // the state strings end after the last phase's links
    for (uint32_t s = 0; s < ns; ++s)
      for (uint32_t p = h.phase_begin[s]; p < h.phase_begin[s + 1]; ++p)
        chars = std::max<size_t>(chars, static_cast<size_t>(h.state_begin[p]) + static_cast<size_t>(h.num_links[s]));
    signals_.phase_begin = upload(h.phase_begin, static_cast<size_t>(ns) + 1);
    signals_.durations_ms = upload(h.durations_ms, phases);
    signals_.state_begin = upload(h.state_begin, phases);
    signals_.states = upload(h.states, chars);
    signals_.num_links = upload(h.num_links, ns);
    signals_.cycle_ms = upload(h.cycle_ms, ns);
    signals_.offset_ms = upload(h.offset_ms, ns);
    signals_.link_begin = dev_.net.signal_link_begin;
  }

  void upload_demand(const StepContext& h, const GpuStepSizes& sizes) {
    const uint32_t nt = sizes.num_types, nv = sizes.num_vehicles;
    dev_.types = TypeView{upload(h.types.length, nt), upload(h.types.min_gap, nt),
                          upload(h.types.accel, nt),  upload(h.types.decel, nt),
                          upload(h.types.emergency_decel, nt), upload(h.types.max_speed, nt),
                          upload(h.types.tau, nt),    upload(h.types.delta, nt)};
    dev_.trips = TripView{upload(h.trips.type, nv),         upload(h.trips.route_begin, nv),
                          upload(h.trips.route_length, nv), upload(h.trips.route_edges, sizes.num_route_edges),
                          upload(h.trips.speed_factor, nv), upload(h.trips.arrival_pos_kind, nv),
                          upload(h.trips.arrival_pos, nv)};
  }

  /// The device copy of one of the host's two lane maps. Both sides keep their copies equal: the map a step
  /// reads is uploaded (the host inserted into it), the one it writes is downloaded, and neither side
  /// changes a map between these points.
  uint8_t* device_map(const uint8_t* host, bool read_by_step) {
    int slot = host == host_map_[0] ? 0 : (host == host_map_[1] ? 1 : -1);
    bool first_use = false;
    if (slot < 0) {
      slot = host_map_[0] == nullptr ? 0 : (host_map_[1] == nullptr ? 1 : -1);
      if (slot < 0) throw std::logic_error("GpuStepper: the host switched to a third lane-map buffer");
      host_map_[slot] = host;
      first_use = true;
    }
    if (read_by_step || first_use) copy_to_device(map_[slot], host, cells_);
    return map_[slot];
  }

  std::vector<DeviceBuffer> buffers_;  // every allocation, freed in the stepper's destructor
  StepContext dev_{};                  // device pointers; params and lane maps filled per step
  SignalTable signals_{};
  char* link_state_ = nullptr;
  int64_t* counters_ = nullptr;
  std::vector<int64_t> counter_delta_;
  uint64_t cells_ = 0;
  uint8_t* map_[2] = {nullptr, nullptr};
  const uint8_t* host_map_[2] = {nullptr, nullptr};
  uint32_t* active_ = nullptr;
};

}  // namespace

CudaDeviceStatus cuda_device_status() {
  CudaDeviceStatus status;
  int count = 0;
  cudaError_t rc = cudaGetDeviceCount(&count);
  if (rc != cudaSuccess) {
    status.description = cudaGetErrorString(rc);
    // What this error means in practice: no libcuda at all is reported the same way as an old one.
    if (rc == cudaErrorInsufficientDriver)
      status.description += " (no NVIDIA driver, or one older than CUDA " + std::to_string(CUDART_VERSION / 1000) +
                            "." + std::to_string(CUDART_VERSION % 1000 / 10) + " needs)";
    cudaGetLastError();  // not sticky; clear it for later calls
    return status;
  }
  if (count == 0) {
    status.description = "no CUDA device found";
    return status;
  }
  cudaDeviceProp prop{};
  rc = cudaGetDeviceProperties(&prop, 0);
  if (rc != cudaSuccess) {
    status.description = std::string("device 0: ") + cudaGetErrorString(rc);
    cudaGetLastError();
    return status;
  }
  const std::string name = std::string(prop.name) + " (sm_" + std::to_string(prop.major) + std::to_string(prop.minor) + ")";
  int mode = cudaComputeModeDefault;
  if (cudaDeviceGetAttribute(&mode, cudaDevAttrComputeMode, 0) == cudaSuccess && mode == cudaComputeModeProhibited) {
    status.description = name + " is in compute-prohibited mode";
    return status;
  }
  // The kernels may lack an image for this architecture (built for sm_80 and sm_90 plus their PTX).
  cudaFuncAttributes attr{};
  rc = cudaFuncGetAttributes(&attr, pass_kernel<plan_vehicle>);
  if (rc != cudaSuccess) {
    status.description = name + " cannot run this build's kernels: " + cudaGetErrorString(rc);
    cudaGetLastError();
    return status;
  }
  status.usable = true;
  status.description = name;
  return status;
}

std::unique_ptr<GpuStepper> make_cuda_stepper(const StepContext& host, const SignalTable& signals,
                                              const GpuStepSizes& sizes) {
  return std::make_unique<CudaStepper>(host, signals, sizes);
}

}  // namespace lpsim

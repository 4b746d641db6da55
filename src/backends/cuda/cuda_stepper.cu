// The CUDA backend's host side: the CudaStepper that owns the run state on the device and launches the
// kernels of kernels/cuda_kernels.cuh (the same functions the CPU backend runs) for each phase of the step.
// Built with --fmad=false (and the CPU with -ffp-contract=off), so both compute bit-identical floats; the
// only read-modify-writes are integer atomics, whose result does not depend on thread order.
//
// The device holds the run state for the whole run: the trip table (grown as the host's grows), the slot
// columns of the vehicles on the road (grown when the host hands out a slot beyond them), plan scratch, both
// lane maps (a step clears only the cells its vehicles left), signal states, the active list (ascending
// slots, kept so by a stable compaction and a merge) and the edgeData counters. What crosses the bus per
// step:
//   device -> host: a tally (vehicles kept, running, ended) and the step's arrivals and teleports;
//   host -> device: the teleport decisions, the queue heads to insert, the vehicles inserted and their slots;
//   device -> host: how many of each queue head were inserted, and where.
// The host waits for the device twice per step, for those two answers (the first with as many of the ends
// as one copy guesses); the uploads are asynchronous, staged in page-locked memory.
// Outputs fetch more only when they sample: FCD and summary the active vehicles' positions, edgeData the
// counters at the end of an interval.
// Built by nvcc for the GPU, or by the host compiler against tests/cuda_emulation (a host emulation of the
// CUDA runtime and cub calls made here) so that the tests run this file's host logic without a GPU.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cub/device/device_merge.cuh>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_select.cuh>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "backends/backend_state.hpp"
#include "backends/cuda/cuda_stepper.hpp"
#include "backends/host_columns.hpp"
#include "backends/lane_records.hpp"
#include "kernels/cuda_kernels.cuh"

namespace lpsim {

namespace {

// Slots the device starts with, at least (grown by half again when the host hands out more). The host
// emulation starts from one, so that every test there runs the growth.
#ifndef LPSIM_GPU_INITIAL_SLOTS
#define LPSIM_GPU_INITIAL_SLOTS 1024
#endif

// Ends fetched with the step's tally at least (more when the last step had more). The host emulation
// fetches one, so that its tests also take the path that fetches the rest.
#ifndef LPSIM_GPU_MIN_ENDS_FETCHED
#define LPSIM_GPU_MIN_ENDS_FETCHED 64
#endif

#if defined(__CUDACC__)
#define LPSIM_LAUNCH(kernel, grid, block) kernel<<<(grid), (block)>>>
#else  // host emulation: the kernel's threads run one after another, in a shuffled order
#define LPSIM_LAUNCH(kernel, grid, block) ::cuda_emulation::launch((grid), (block), kernel)
#endif

uint32_t blocks_for(uint32_t n) { return (n + kBlock - 1) / kBlock; }

void check(cudaError_t rc, const char* call, const char* file, int line) {
  if (rc == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA call ") + call + " failed at " + file + ":" +
                           std::to_string(line) + ": " + cudaGetErrorName(rc) + " (" +
                           cudaGetErrorString(rc) + ")");
}

#define LPSIM_CUDA_CHECK(call) check((call), #call, __FILE__, __LINE__)
// Launch errors (bad configuration, no kernel image) surface here; faults inside a kernel at the next sync.
#define LPSIM_CUDA_CHECK_LAUNCH(kernel) check(cudaGetLastError(), "launch of " #kernel, __FILE__, __LINE__)

/// One cudaMalloc'd allocation (or none), freed with its owner.
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(size_t bytes) { LPSIM_CUDA_CHECK(cudaMalloc(&ptr_, std::max<size_t>(bytes, 1))); }
  DeviceBuffer(DeviceBuffer&& other) noexcept : ptr_(other.ptr_) { other.ptr_ = nullptr; }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(DeviceBuffer&& other) noexcept {
    std::swap(ptr_, other.ptr_);
    return *this;
  }
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

// The views the stepper copies to the device are walked through their column lists (visit_net_columns,
// visit_type_columns, visit_trip_columns, visit_depart_columns, visit_emission_columns,
// visit_signal_columns, visit_vehicle_columns, visit_plan_columns); the step context's other members are
// its own.
static_assert(sizeof(StepContext) == sizeof(NetView) + sizeof(TypeView) + sizeof(TripView) +
                                         sizeof(VehicleView) + sizeof(PlanView) + sizeof(StepParams) +
                                         sizeof(EmissionView) + 11 * sizeof(void*),
              "StepContext changed: update CudaStepper");

/// A device array that grows on demand (its contents are not kept when it grows).
template <class T>
class ScratchArray {
 public:
  T* get(size_t n) {
    if (n > capacity_) {
      capacity_ = std::max(n, capacity_ + capacity_ / 2);
      buffer_ = DeviceBuffer(capacity_ * sizeof(T));
    }
    return static_cast<T*>(buffer_.get());
  }

 private:
  DeviceBuffer buffer_;
  size_t capacity_ = 0;
};

/// Page-locked host memory that grows on demand (contents not kept): copies from and to it run at full
/// bus speed, with no staging copy inside the driver.
template <class T>
class PinnedArray {
 public:
  PinnedArray() = default;
  PinnedArray(const PinnedArray&) = delete;
  PinnedArray& operator=(const PinnedArray&) = delete;
  ~PinnedArray() {
    if (ptr_ != nullptr) cudaFreeHost(ptr_);
  }
  T* get(size_t n) {
    if (n > capacity_) {
      if (ptr_ != nullptr) cudaFreeHost(ptr_);
      ptr_ = nullptr;
      capacity_ = std::max(n, capacity_ + capacity_ / 2);
      LPSIM_CUDA_CHECK(cudaMallocHost(&ptr_, capacity_ * sizeof(T)));
    }
    return ptr_;
  }

 private:
  T* ptr_ = nullptr;
  size_t capacity_ = 0;
};

/// Copies n values to the device without waiting for the copy: through `staging`, page-locked, so that the
/// copy runs asynchronously and the caller's array may change at once. A staging array must not be written
/// again before the device has made the copy: each is used by one stepper call, which runs once per step,
/// and every step synchronises with the device (the tally) before the next such call.
template <class T>
void upload_async(T* dst, const T* src, size_t n, PinnedArray<T>& staging) {
  if (n == 0) return;
  T* staged = staging.get(n);
  std::copy_n(src, n, staged);
  LPSIM_CUDA_CHECK(cudaMemcpyAsync(dst, staged, n * sizeof(T), cudaMemcpyHostToDevice));
}

/// Where a run's time goes, printed at the end when LPSIM_GPU_TIMING is set: device time of each kernel
/// phase (events, read at the step's first synchronisation) and host wall time of each stepper call.
class PhaseTimer {
 public:
  static constexpr int kEvents = 7;  // start, signals, clear, approach, plan, commit, finish
  static constexpr int kCalls = 5;   // stepper calls timed on the host (add_host)
  PhaseTimer() : on_(std::getenv("LPSIM_GPU_TIMING") != nullptr) {
    if (on_)
      for (auto& e : events_) LPSIM_CUDA_CHECK(cudaEventCreate(&e));
  }
  ~PhaseTimer() {
    if (!on_) return;
    static const char* kernel[kEvents - 1] = {"signals", "clear", "approach", "plan", "commit", "finish"};
    std::fprintf(stderr, "GPU timing over %llu steps (ms total):", static_cast<unsigned long long>(steps_));
    for (int k = 0; k < kEvents - 1; ++k) std::fprintf(stderr, " %s %.1f", kernel[k], device_ms_[k]);
    // "step()": start_step and finish_step together (the host work between them is not counted).
    static const char* call[kCalls] = {"step()", "apply_teleports()", "insert()", "rebuild_active()",
                                       "sort_slots()"};
    for (int k = 0; k < kCalls; ++k) std::fprintf(stderr, " | %s %.1f", call[k], host_ms_[k]);
    std::fprintf(stderr, "\n");
    const double v = static_cast<double>(std::max<uint64_t>(vehicles_, 1));
    const double state = static_cast<double>(per_vehicle_) * v + static_cast<double>(slot_bytes_) +
                         static_cast<double>(plan_bytes_);
    std::fprintf(
        stderr,
        "GPU state: %.1f MiB in fixed allocations; %.1f B per loaded vehicle (%llu vehicles: %llu B of "
        "trip data each, slots %.1f MiB for %llu slots, plan scratch %.1f MiB), route edges %.1f MiB\n",
        static_cast<double>(bytes_total_) / 1048576.0, state / v, static_cast<unsigned long long>(vehicles_),
        static_cast<unsigned long long>(per_vehicle_), static_cast<double>(slot_bytes_) / 1048576.0,
        static_cast<unsigned long long>(slots_), static_cast<double>(plan_bytes_) / 1048576.0,
        static_cast<double>(route_bytes_) / 1048576.0);
    for (auto& e : events_) cudaEventDestroy(e);
  }
  void mark(int k) {
    if (on_) cudaEventRecord(events_[k]);
  }
  /// After a synchronisation that covers the last mark.
  void collect() {
    if (!on_) return;
    ++steps_;
    for (int k = 1; k < kEvents; ++k) {
      float ms = 0;
      if (cudaEventElapsedTime(&ms, events_[k - 1], events_[k]) == cudaSuccess) device_ms_[k - 1] += ms;
    }
  }
  void set_state_bytes(uint64_t total, uint64_t per_vehicle, uint64_t vehicles, uint64_t route_bytes) {
    bytes_total_ = total;
    per_vehicle_ = per_vehicle;
    vehicles_ = vehicles;
    route_bytes_ = route_bytes;
  }
  /// The per-slot columns and the plan scratch as they stand (their largest size is the one at the end).
  void set_slot_bytes(uint64_t slots, uint64_t slot_bytes, uint64_t plan_bytes) {
    slots_ = slots;
    slot_bytes_ = slot_bytes;
    plan_bytes_ = plan_bytes;
  }
  /// Host wall time of one stepper call, from its start (`t0`) to now.
  void add_host(int k, std::chrono::steady_clock::time_point t0) {
    if (on_)
      host_ms_[k] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }

 private:
  bool on_;
  uint64_t bytes_total_ = 0, per_vehicle_ = 0, vehicles_ = 0, route_bytes_ = 0;
  uint64_t slots_ = 0, slot_bytes_ = 0, plan_bytes_ = 0;
  cudaEvent_t events_[kEvents] = {};
  double device_ms_[kEvents - 1] = {};
  double host_ms_[kCalls] = {};
  unsigned long long steps_ = 0;
};

/// The trip table on the device: the per-trip columns (TripView, DepartView) and the route edges, each grown
/// by half again when the host's table outgrows it, keeping what it holds (Stepper::update_trips).
class DeviceTrips {
 public:
  TripView trips{};
  DepartView depart{};

  /// Brings the device copy up to `host` (the host's table now): entries from `first_vehicle` and route
  /// edges from `first_route_edge` on are copied, the others are as they were.
  void append(const TripTableView& host, uint32_t first_vehicle, uint64_t first_route_edge,
              bool stops_moved) {
    if (host.num_vehicles > vehicle_capacity_) {
      const size_t c = std::max<size_t>(host.num_vehicles, vehicle_capacity_ + vehicle_capacity_ / 2);
      size_t k = 0;
      each_column(trips, depart, [&](auto*& column) { regrow(column, k++, vehicle_capacity_, c); });
      vehicle_capacity_ = c;
    }
    if (host.num_route_edges > route_capacity_) {
      const size_t c = std::max<size_t>(host.num_route_edges, route_capacity_ + route_capacity_ / 2);
      regrow(trips.route_edges, kVehicleColumns, route_capacity_, c);
      route_capacity_ = c;
    }
    const size_t n = host.num_vehicles - std::min(first_vehicle, host.num_vehicles);
    TripView h = host.trips;
    DepartView hd = host.depart;
    // Walks the host's and the device's columns in the same order: the k-th of each is the same column.
    std::vector<const void*> from;
    each_column(h, hd, [&](auto*& column) { from.push_back(column); });
    size_t k = 0;
    each_column(trips, depart, [&](auto*& column) {
      using T = std::remove_const_t<std::remove_reference_t<decltype(*column)>>;
      copy_to_device(const_cast<T*>(column) + first_vehicle, static_cast<const T*>(from[k++]) + first_vehicle,
                     n);
    });
    const uint64_t first_edge = std::min<uint64_t>(first_route_edge, host.num_route_edges);
    copy_to_device(const_cast<uint32_t*>(trips.route_edges) + first_edge, host.trips.route_edges + first_edge,
                   host.num_route_edges - first_edge);
    if (host.num_stops != num_stops_ || stops_moved) upload_stops(host);
  }

  /// Bytes per trip and per route edge the device holds.
  static size_t bytes_per_vehicle() {
    size_t bytes = 0;
    TripView t{};
    DepartView d{};
    each_column(t, d, [&](auto*& column) { bytes += sizeof(*column); });
    return bytes;
  }

 private:
  static constexpr size_t kVehicleColumns = 12;  // each_column's count; the route edges are buffer 12

  /// Calls f(column) for every per-trip column of a trip and a depart view (not route_edges).
  template <class F>
  static void each_column(TripView& t, DepartView& d, F&& f) {
    visit_trip_columns(
        [&](TripExtent x, auto*& column) {
          if (x == TripExtent::kTrips) f(column);
        },
        t);
    visit_depart_columns(f, d);
  }

  // The stop table, whole: trips added during a run make no stops, so it is uploaded once, and again when
  // the rerouting device moved a vehicle's stops along its new route.
  void upload_stops(const TripTableView& host) {
    num_stops_ = host.num_stops;
    stop_buffers_.clear();
    auto up = [&](const auto* from, const auto*& to) {
      using T = std::remove_const_t<std::remove_reference_t<decltype(*from)>>;
      stop_buffers_.emplace_back(std::max<size_t>(num_stops_, 1) * sizeof(T));
      to = static_cast<const T*>(stop_buffers_.back().get());
      copy_to_device(static_cast<T*>(stop_buffers_.back().get()), from, num_stops_);
    };
    visit_trip_columns(
        [&](TripExtent x, auto* from, auto*& to) {
          if (x == TripExtent::kStops) up(from, to);
        },
        host.trips, trips);
  }

  template <class T>
  void regrow(const T*& column, size_t buffer, size_t old, size_t c) {
    DeviceBuffer fresh(c * sizeof(T));
    if (old > 0) LPSIM_CUDA_CHECK(cudaMemcpy(fresh.get(), column, old * sizeof(T), cudaMemcpyDeviceToDevice));
    column = static_cast<const T*>(fresh.get());
    if (buffers_.size() <= buffer) buffers_.resize(buffer + 1);
    buffers_[buffer] = std::move(fresh);
  }

  std::vector<DeviceBuffer> buffers_;
  size_t vehicle_capacity_ = 0, route_capacity_ = 0;
  std::vector<DeviceBuffer> stop_buffers_;
  uint64_t num_stops_ = ~uint64_t{0};
};

class CudaStepper final : public Stepper {
 public:
  explicit CudaStepper(const StepperSetup& setup) : host_net_(setup.net) {
    int devices = 1;
    LPSIM_CUDA_CHECK(cudaGetDeviceCount(&devices));
    LPSIM_CUDA_CHECK(cudaSetDevice(setup.device % std::max(devices, 1)));
    const uint32_t nl = setup.net.num_lanes;
    upload_network(setup);
    upload_signals(setup.signals);
    upload_types(setup.types, setup.num_types);
    update_trips(setup.trips, TripChanges{});

    grow_slots(LPSIM_GPU_INITIAL_SLOTS);
    const std::vector<LaneApproach> approach(nl, LaneApproach{0xFFFFFFFFu, -1, 0, 0, 0, 0, 0, 0});
    dev_.approach = upload(approach.data(), nl);
    dev_.claims = allocate<uint64_t>(nl);
    LPSIM_CUDA_CHECK(cudaMemset(dev_.claims, 0, nl * sizeof(uint64_t)));
    dev_.merge_requests = allocate<uint64_t>(kMergeSlots * nl);
    LPSIM_CUDA_CHECK(cudaMemset(dev_.merge_requests, 0, kMergeSlots * nl * sizeof(uint64_t)));
    const size_t nc = setup.num_connections;
    dev_.yielder_begin = upload(setup.yielder_begin, nc + 1);
    dev_.yielder = upload(setup.yielder, setup.yielder_begin[nc]);

    // The counters, contiguous so that one copy fetches them and one memset clears them.
    num_lanes_ = nl;
    if (setup.lane_counters) {
      counters_ = allocate<int64_t>(static_cast<size_t>(kNumTrafficCounters) * nl);
      LPSIM_CUDA_CHECK(
          cudaMemset(counters_, 0, kNumTrafficCounters * static_cast<size_t>(nl) * sizeof(int64_t)));
      // The lane records (cudaMalloc aligns them to a cache line), then the departed column.
      dev_.lane_counts = counters_;
      cnt_departed_ = counters_ + static_cast<size_t>(kLaneRecordCounters) * nl;
    }
    if (setup.emission_sums) upload_emissions(setup.emission_types, setup.num_types, nl);

    if (setup.junction_stands)
      for (auto& j : junction_stand_) {
        j = allocate<uint32_t>(nl);
        LPSIM_CUDA_CHECK(cudaMemset(j, 0xFF, nl * sizeof(uint32_t)));  // kNoJunctionStand
      }

    cells_ = setup.net.lane_cell_begin[nl];
    // With the host's kLaneMapPadding zero bytes after the last cell: the device scans stay within a lane,
    // but the host emulation (tests/cuda_emulation) runs the host scan, which reads past a lane's end.
    for (int b = 0; b < 2; ++b) {
      map_[b] = allocate<uint8_t>(cells_ + kLaneMapPadding);
      LPSIM_CUDA_CHECK(cudaMemset(map_[b], 0, cells_ + kLaneMapPadding));
    }
    timer_.set_state_bytes(bytes_total_, DeviceTrips::bytes_per_vehicle(), setup.trips.num_vehicles,
                           setup.trips.num_route_edges * sizeof(uint32_t));
  }

  void update_signals(int64_t time_ms, int64_t map_time_ms, int map_now) override {
    timer_.mark(0);
    if (signals_.num_signals > 0) {
      const SignalInputs in{map_[map_now], map_time_ms, time_ms - map_time_ms};
      LPSIM_LAUNCH(signals_kernel, blocks_for(signals_.num_signals), kBlock)
      (signals_, time_ms, in, link_state_, signal_next_switch_ms_, actuated_state_);
      LPSIM_CUDA_CHECK_LAUNCH(signals_kernel);
    }
    timer_.mark(1);
    ++version_;
  }

  void start_step(const StepParams& params, int map_now) override {
    t0_ = std::chrono::steady_clock::now();
    reserve_plan_slots(num_active_);
    ctx_ = dev_;
    ctx_.params = params;
    if (step_marks_wrap(params.step)) clear_step_marks();
    ctx_.map_now = map_[map_now];
    ctx_.map_next = map_[1 - map_now];
    ctx_.junction_stand_now = junction_stand_[map_now];  // null unless tracked
    ctx_.junction_stand_next = junction_stand_[1 - map_now];
    state_map_ = 1 - map_now;
    launched_ = num_active_;
    kept_count_ = 0;
    ++version_;
  }

  void clear_footprints() override { launch_pass<clear_old_footprint>(2); }
  void approach() override { launch_pass<approach_vehicle>(3); }
  void plan() override { launch_pass<plan_vehicle>(4); }
  void commit() override { launch_pass<commit_vehicle>(5); }
  void count_emissions() override { launch_pass<count_vehicle_emissions>(5); }  // timed with the commit

  // The tally and the step's ends share one buffer, so that one copy brings back the tally and as many
  // ends as the guess allows (twice the last step's, at least LPSIM_GPU_MIN_ENDS_FETCHED): the step's
  // first synchronisation. Ends beyond the guess take a second copy.
  void start_end_of_step(uint32_t steps_done) override {
    const uint32_t n = launched_;
    if (n > 0) {
      unsigned char* outcome = outcome_.get(kEndsOffset + sizeof(VehicleEnd) * static_cast<size_t>(n));
      StepTally* tally = reinterpret_cast<StepTally*>(outcome);
      VehicleEnd* ends = reinterpret_cast<VehicleEnd*>(outcome + kEndsOffset);
      LPSIM_CUDA_CHECK(cudaMemsetAsync(tally, 0, sizeof(StepTally)));
      LPSIM_LAUNCH(finish_kernel, blocks_for(n), kBlock)
      (ctx_.veh, active_[cur_active_], n, steps_done, first_teleport_steps(ctx_.params), keep_, ends, tally);
      LPSIM_CUDA_CHECK_LAUNCH(finish_kernel);
      timer_.mark(6);
      guess_ = std::min(n, std::max<uint32_t>(LPSIM_GPU_MIN_ENDS_FETCHED, 2 * last_ends_));
      const size_t fetched = kEndsOffset + sizeof(VehicleEnd) * static_cast<size_t>(guess_);
      LPSIM_CUDA_CHECK(cudaMemcpyAsync(outcome_host_.get(fetched), outcome, fetched, cudaMemcpyDeviceToHost));
    }
    timer_.add_host(0, t0_);
  }

  StepOutcome& finish_end_of_step() override {
    const auto t0 = std::chrono::steady_clock::now();
    StepOutcome& out = outcome_result_;
    out.ends.clear();
    out.kept = out.running = 0;
    if (launched_ > 0) {
      // Waits for the passes: a fault inside them is reported here.
      LPSIM_CUDA_CHECK(cudaStreamSynchronize(nullptr));
      timer_.collect();
      const unsigned char* host = outcome_host_.get(0);
      StepTally t;
      std::memcpy(&t, host, sizeof t);
      out.kept = kept_count_ = t.kept;
      out.running = t.running;
      out.ends.resize(t.ends);
      const uint32_t in_guess = std::min(t.ends, guess_);
      if (in_guess > 0) std::memcpy(out.ends.data(), host + kEndsOffset, sizeof(VehicleEnd) * in_guess);
      const VehicleEnd* ends = reinterpret_cast<const VehicleEnd*>(outcome_.get(0) + kEndsOffset);
      copy_to_host(out.ends.data() + in_guess, ends + in_guess, t.ends - in_guess);  // beyond the guess
      last_ends_ = t.ends;
    }
    timer_.add_host(0, t0);
    return out;
  }

  void apply_teleports(const std::vector<TeleportMove>& moves, uint32_t steps_done) override {
    const auto t0 = std::chrono::steady_clock::now();
    const uint32_t n = static_cast<uint32_t>(moves.size());
    if (n == 0) return;
    TeleportMove* dev = moves_.get(n);
    upload_async(dev, moves.data(), n, moves_host_);
    LPSIM_LAUNCH(teleport_kernel, blocks_for(n), kBlock)(dev_.veh, dev, n, steps_done);
    LPSIM_CUDA_CHECK_LAUNCH(teleport_kernel);
    ++version_;
    timer_.add_host(1, t0);
  }

  void insert(const InsertBatch& batch, uint32_t num_entries, const InsertParams& p, int map) override {
    const auto t0 = std::chrono::steady_clock::now();
    const uint32_t slots = batch.num_slots;
    if (slots == 0 || num_entries == 0) return;
    ++version_;
    // One upload of the slots' edges, bounds and entries; one download of what was inserted and where.
    const size_t in_words = 2 * static_cast<size_t>(slots) + 1 + 5 * static_cast<size_t>(num_entries);
    uint32_t* in = batch_in_.get(in_words);
    uint32_t* staged = staging_in_.get(in_words);
    std::copy_n(batch.edge, slots, staged);
    std::copy_n(batch.begin, slots + 1, staged + slots);
    std::copy_n(batch.entry, num_entries, staged + 2 * slots + 1);
    std::copy_n(batch.route_pos, num_entries, staged + 2 * slots + 1 + num_entries);
    std::memcpy(staged + 2 * slots + 1 + 2 * static_cast<size_t>(num_entries), batch.enter_speed,
                num_entries * sizeof(float));
    std::memcpy(staged + 2 * slots + 1 + 3 * static_cast<size_t>(num_entries), batch.enter_lane,
                num_entries * sizeof(int32_t));
    std::memcpy(staged + 2 * slots + 1 + 4 * static_cast<size_t>(num_entries), batch.enter_pos,
                num_entries * sizeof(float));
    LPSIM_CUDA_CHECK(cudaMemcpyAsync(in, staged, in_words * sizeof(uint32_t), cudaMemcpyHostToDevice));
    const size_t out_words = static_cast<size_t>(slots) + 3 * static_cast<size_t>(num_entries);
    uint32_t* out = batch_out_.get(out_words);
    InsertBatch dev{
        slots,
        in,
        in + slots,
        in + 2 * slots + 1,
        in + 2 * slots + 1 + num_entries,
        reinterpret_cast<const float*>(in + 2 * slots + 1 + 2 * static_cast<size_t>(num_entries)),
        reinterpret_cast<const int32_t*>(in + 2 * slots + 1 + 3 * static_cast<size_t>(num_entries)),
        reinterpret_cast<const float*>(in + 2 * slots + 1 + 4 * static_cast<size_t>(num_entries)),
        out,
        reinterpret_cast<int32_t*>(out + slots),
        reinterpret_cast<float*>(out + slots + num_entries),
        reinterpret_cast<float*>(out + slots + 2 * static_cast<size_t>(num_entries))};
    InsertParams params = p;
    params.cnt_departed = cnt_departed_;
    params.lane_counts = dev_.lane_counts;
    LPSIM_LAUNCH(insert_kernel, blocks_for(slots), kBlock)(dev_, trips_.depart, params, map_[map], dev);
    LPSIM_CUDA_CHECK_LAUNCH(insert_kernel);
    uint32_t* back = staging_out_.get(out_words);
    copy_to_host(back, out, out_words);
    std::copy_n(back, slots, batch.inserted);
    std::copy_n(reinterpret_cast<const int32_t*>(back + slots), num_entries, batch.out_lane);
    std::copy_n(reinterpret_cast<const float*>(back + slots + num_entries), num_entries, batch.out_pos);
    std::copy_n(reinterpret_cast<const float*>(back + slots + 2 * static_cast<size_t>(num_entries)),
                num_entries, batch.out_speed);
    timer_.add_host(2, t0);
  }

  void start_vehicles(const std::vector<SlotInit>& inits, const std::vector<uint32_t>& added) override {
    const auto t0 = std::chrono::steady_clock::now();
    ++version_;
    if (!added.empty()) grow_slots(static_cast<size_t>(added.back()) + 1);
    const uint32_t ni = static_cast<uint32_t>(inits.size());
    if (ni > 0) {
      SlotInit* dev = inits_.get(ni);
      upload_async(dev, inits.data(), ni, inits_host_);
      LPSIM_LAUNCH(activate_kernel, blocks_for(ni), kBlock)(dev_.veh, dev_.trips, dev, ni);
      LPSIM_CUDA_CHECK_LAUNCH(activate_kernel);
    }
    rebuild(added);
    timer_.add_host(3, t0);
  }

  void sort_slots(std::vector<uint32_t>& slots) override {
    const auto t0 = std::chrono::steady_clock::now();
    ++version_;
    const uint32_t n = num_active_;
    uint32_t* active = active_[cur_active_];
    uint32_t* keys = sort_keys_.get(2 * static_cast<size_t>(n));
    uint32_t* order = sort_order_.get(n);
    if (n > 0) {
      LPSIM_LAUNCH(lane_key_kernel, blocks_for(n), kBlock)(dev_.veh, active, n, keys);
      LPSIM_CUDA_CHECK_LAUNCH(lane_key_kernel);
      // The active list is ascending and the radix sort stable: ties stay in slot order, as on the host.
      size_t bytes = 0;
      LPSIM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys, keys + n, active, order, n));
      LPSIM_CUDA_CHECK(
          cub::DeviceRadixSort::SortPairs(temp_.get(bytes), bytes, keys, keys + n, active, order, n));
      visit_vehicle_columns(
          [&](uint32_t per, auto* column) {
            using T = std::remove_pointer_t<decltype(column)>;
            const size_t entries = static_cast<size_t>(n) * per;
            T* moved = reinterpret_cast<T*>(sort_moved_.get(entries * sizeof(T)));
            LPSIM_LAUNCH(gather_slots_kernel<T>, blocks_for(n), kBlock)(column, moved, order, n, per);
            LPSIM_CUDA_CHECK_LAUNCH(gather_slots_kernel);
            LPSIM_CUDA_CHECK(cudaMemcpyAsync(column, moved, entries * sizeof(T), cudaMemcpyDeviceToDevice));
          },
          dev_.veh);
      LPSIM_LAUNCH(iota_kernel, blocks_for(n), kBlock)(active, n);
      LPSIM_CUDA_CHECK_LAUNCH(iota_kernel);
    }
    // The new numbers of the host's slots: the inverse of the order, read where the host asks.
    const uint32_t ns = static_cast<uint32_t>(slots.size());
    if (ns > 0) {
      uint32_t* inverse = sort_inverse_.get(slot_capacity_);
      LPSIM_CUDA_CHECK(cudaMemsetAsync(inverse, 0xFF, slot_capacity_ * sizeof(uint32_t)));  // kNotActive
      if (n > 0) {
        LPSIM_LAUNCH(invert_order_kernel, blocks_for(n), kBlock)(order, n, inverse);
        LPSIM_CUDA_CHECK_LAUNCH(invert_order_kernel);
      }
      uint32_t* asked = sort_asked_.get(ns);
      copy_to_device(asked, slots.data(), ns);
      LPSIM_LAUNCH(renumber_kernel, blocks_for(ns), kBlock)
      (inverse, static_cast<uint32_t>(slot_capacity_), asked, ns);
      LPSIM_CUDA_CHECK_LAUNCH(renumber_kernel);
      copy_to_host(slots.data(), asked, ns);
    }
    timer_.add_host(4, t0);
  }

  void update_trips(const TripTableView& now, const TripChanges& changes) override {
    trips_.append(now, changes.first_new_vehicle, changes.first_new_route_edge, changes.stops_moved);
    dev_.trips = trips_.trips;
    const uint32_t n = static_cast<uint32_t>(changes.new_routes.size());
    if (n > 0) {
      std::vector<uint32_t> changed;
      for (const uint32_t v : changes.new_routes)
        changed.insert(changed.end(), {v, now.trips.route_begin[v], now.trips.route_length[v]});
      uint32_t* dev = trip_routes_.get(changed.size());
      copy_to_device(dev, changed.data(), changed.size());
      LPSIM_LAUNCH(trip_route_kernel, blocks_for(n), kBlock)
      (const_cast<uint32_t*>(dev_.trips.route_begin), const_cast<uint32_t*>(dev_.trips.route_length), dev, n);
      LPSIM_CUDA_CHECK_LAUNCH(trip_route_kernel);
    }
  }

  void set_routes(const std::vector<SlotRoute>& routes) override {
    const uint32_t n = static_cast<uint32_t>(routes.size());
    if (n == 0) return;
    ++version_;
    SlotRoute* dev = slot_routes_.get(n);
    copy_to_device(dev, routes.data(), n);
    LPSIM_LAUNCH(route_kernel, blocks_for(n), kBlock)(dev_.veh, dev, n);
    LPSIM_CUDA_CHECK_LAUNCH(route_kernel);
  }

  // A host copy of what is asked for, made at most once per state version (a Full copy serves a Sample).
  const HostState& fetch(StateParts parts, uint32_t num_slots) override {
    const bool full = parts == StateParts::Full, columns = parts != StateParts::Sample;
    const int level = full ? 2 : (columns ? 1 : 0);  // a copy serves any request of its level or below
    if (fetched_version_ == version_ && fetched_level_ >= level) return state_;
    const uint32_t n = num_active_;
    host_active_.resize(n);
    copy_to_host(host_active_.data(), active_[cur_active_], n);
    if (columns) {
      host_.reserve(std::max<size_t>(num_slots, 1), false);
      VehicleView h = host_.view();
      visit_vehicle_columns(
          [&](uint32_t per, auto* dev, auto* host) {
            copy_to_host(host, dev, static_cast<size_t>(num_slots) * per);
          },
          dev_.veh, h);
    }
    if (full) {
      host_map_.resize(cells_);
      copy_to_host(host_map_.data(), map_[state_map_], cells_);
      host_link_state_.resize(num_links_);
      copy_to_host(host_link_state_.data(), link_state_, num_links_);
    } else if (!columns && n > 0) {
      // Only what outputs read, gathered on the device, scattered into the host columns by slot.
      uint32_t max_slot = *std::max_element(host_active_.begin(), host_active_.end());
      host_.reserve(size_t{max_slot} + 1, false);
      uint32_t* vh = sample_vehicle_.get(n);
      uint8_t* st = sample_status_.get(n);
      int32_t* ln = sample_lane_.get(n);
      float* ps = sample_pos_.get(n);
      float* sp = sample_speed_.get(n);
      uint32_t* sr = sample_stop_release_.get(n);
      LPSIM_LAUNCH(sample_kernel, blocks_for(n), kBlock)
      (dev_.veh, active_[cur_active_], n, vh, st, ln, ps, sp, sr);
      LPSIM_CUDA_CHECK_LAUNCH(sample_kernel);
      sample_u32_.resize(2 * size_t{n});
      sample_u8_.resize(n);
      sample_i32_.resize(n);
      sample_f32_.resize(2 * size_t{n});
      copy_to_host(sample_u32_.data(), vh, n);
      copy_to_host(sample_u8_.data(), st, n);
      copy_to_host(sample_i32_.data(), ln, n);
      copy_to_host(sample_f32_.data(), ps, n);
      copy_to_host(sample_f32_.data() + n, sp, n);
      copy_to_host(sample_u32_.data() + n, sr, n);
      const VehicleView& h = host_.view();
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t k = host_active_[i];
        h.vehicle[k] = sample_u32_[i];
        h.status[k] = sample_u8_[i];
        h.lane[k] = sample_i32_[i];
        h.pos[k] = sample_f32_[i];
        h.speed[k] = sample_f32_[n + i];
        h.stop_release[k] = sample_u32_[n + i];
      }
    }
    fetched_version_ = version_;
    fetched_level_ = level;
    state_.active = host_active_.data();
    state_.num_active = n;
    state_.veh = host_.view();
    state_.map = full ? host_map_.data() : nullptr;
    state_.link_state = full ? host_link_state_.data() : nullptr;
    return state_;
  }

  // The exchanges of a partitioned run touch the few lanes and vehicles at the parts' borders, between
  // steps' passes: each is one gather or scatter launch over an uploaded index list, not a copy per entry
  // (one synchronous copy per lane cost more than the step's passes).
  void write_footprints(int map, const std::vector<FootprintWrite>& writes, const uint8_t* held) override {
    ++version_;
    // The cells in write order, then the last write of each cell (as the writes made one by one leave it).
    std::vector<std::pair<uint32_t, uint8_t>> cells;
    for (const FootprintWrite& w : writes)
      for_each_footprint_piece(host_net_, w.fp, w.length, [&](int32_t lane, uint32_t first, uint32_t last) {
        if (!held[lane] || last < first) return;
        const uint32_t base = host_net_.lane_cell_begin[lane];
        for (uint32_t c = first; c <= last; ++c) cells.emplace_back(base + c, w.value);
      });
    std::stable_sort(cells.begin(), cells.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<uint32_t> index;
    std::vector<uint8_t> value;
    for (size_t i = 0; i < cells.size(); ++i)
      if (i + 1 == cells.size() || cells[i + 1].first != cells[i].first) {
        index.push_back(cells[i].first);
        value.push_back(cells[i].second);
      }
    scatter(index, value.data(), map_[map]);
  }

  void read_approaches(const std::vector<uint32_t>& lanes, std::vector<LaneApproach>& out) override {
    gather(lanes, dev_.approach, out);
  }

  void read_claims(const std::vector<uint32_t>& lanes, std::vector<uint64_t>& out) override {
    gather(lanes, dev_.claims, out);
  }

  void write_approaches(const std::vector<uint32_t>& lanes, const std::vector<LaneApproach>& in) override {
    scatter(lanes, in.data(), dev_.approach);
  }

  void merge_claims(const std::vector<uint32_t>& lanes, const std::vector<uint64_t>& in) override {
    const uint32_t n = static_cast<uint32_t>(lanes.size());
    if (n == 0) return;
    uint32_t* index = upload_index(lanes);
    uint64_t* values = reinterpret_cast<uint64_t*>(border_values_.get(n * sizeof(uint64_t)));
    copy_to_device(values, in.data(), n);
    LPSIM_LAUNCH(raise_kernel, blocks_for(n), kBlock)(values, index, n, dev_.claims);
    LPSIM_CUDA_CHECK_LAUNCH(raise_kernel);
  }

  void read_link_states(uint32_t begin, uint32_t count, char* out) override {
    copy_to_host(out, link_state_ + begin, count);
  }

  void write_link_states(uint32_t begin, uint32_t count, const char* in) override {
    ++version_;
    copy_to_device(link_state_ + begin, in, count);
  }

  void adopt_vehicles(const std::vector<uint32_t>& slots, const std::vector<uint8_t>& packed) override {
    if (slots.empty()) return;
    ++version_;
    grow_slots(size_t{*std::max_element(slots.begin(), slots.end())} + 1);
    const uint32_t n = static_cast<uint32_t>(slots.size());
    const uint32_t stride = static_cast<uint32_t>(packed.size() / n);
    uint32_t* index = upload_index(slots);
    uint8_t* rows = reinterpret_cast<uint8_t*>(border_values_.get(packed.size()));
    copy_to_device(rows, packed.data(), packed.size());
    uint32_t offset = 0;
    visit_vehicle_columns(
        [&](uint32_t per, auto* column) {
          using T = std::remove_pointer_t<decltype(column)>;
          const uint32_t row = per * static_cast<uint32_t>(sizeof(T));
          LPSIM_LAUNCH(unpack_rows_kernel, blocks_for(n), kBlock)
          (rows, stride, offset, row, index, n, reinterpret_cast<uint8_t*>(column));
          LPSIM_CUDA_CHECK_LAUNCH(unpack_rows_kernel);
          offset += row;
        },
        dev_.veh);
    // The part they left clears their last footprint (their slot there stays one more step for it).
    LPSIM_LAUNCH(fill_at_kernel<int32_t>, blocks_for(n), kBlock)(int32_t{-1}, index, n, dev_.veh.old_lane);
    LPSIM_CUDA_CHECK_LAUNCH(fill_at_kernel);
  }

  void mark_migrated(const std::vector<uint32_t>& slots) override {
    ++version_;
    const uint32_t n = static_cast<uint32_t>(slots.size());
    if (n == 0) return;
    uint32_t* index = upload_index(slots);
    LPSIM_LAUNCH(fill_at_kernel<uint8_t>, blocks_for(n), kBlock)
    (uint8_t{kMigrated}, index, n, dev_.veh.status);
    LPSIM_CUDA_CHECK_LAUNCH(fill_at_kernel);
  }

  void drain_counters(int64_t* const* columns) override {
    drain_lane_records(columns);
    drain(dev_.em.sums, columns + kCountEmissionFirst, kNumEmissionSums);
  }

  // The run state's one list (backend_state.hpp), each table copied from and to the device whole, so that a
  // state moves between the backends.
  std::vector<uint8_t> save_state(uint32_t num_slots) override {
    LPSIM_CUDA_CHECK(cudaStreamSynchronize(nullptr));
    StateBytesOut out;
    out.value(state_map_);
    BackendTables<TableSpan> t = tables();
    visit_backend_tables(t, [&](auto& span, Kept kept) {
      using T = std::remove_pointer_t<decltype(span.data)>;
      std::vector<T> h(span.size);
      copy_to_host(h.data(), span.data, h.size());
      put_table(out, h.data(), h.size(), kept);
    });
    visit_vehicle_columns(
        [&](uint32_t per, auto*& c) {
          std::vector<std::remove_reference_t<decltype(*c)>> h(size_t{num_slots} * per);
          copy_to_host(h.data(), c, h.size());
          out.array(h.data(), h.size());
        },
        dev_.veh);
    return std::move(out.bytes());
  }

  void load_state(const std::vector<uint8_t>& state, uint32_t num_slots) override {
    LPSIM_CUDA_CHECK(cudaStreamSynchronize(nullptr));
    StateBytesIn in(state);
    in.value(state_map_);
    if (state_map_ != 0 && state_map_ != 1)
      throw std::runtime_error("backend state: no lane map " + std::to_string(state_map_));
    grow_slots(num_slots);
    BackendTables<TableSpan> t = tables();
    visit_backend_tables(t, [&](auto& span, Kept kept) {
      std::vector<std::remove_pointer_t<decltype(span.data)>> h;
      if (kept == Kept::kActive) {
        get_table(in, h, kept);
        if (h.size() > slot_capacity_)
          throw std::runtime_error("backend state: more active slots than slots");
        num_active_ = static_cast<uint32_t>(h.size());
      } else {
        h.resize(span.size);
        get_table(in, h.data(), h.size(), kept);
      }
      copy_to_device(span.data, h.data(), h.size());
    });
    visit_vehicle_columns(
        [&](uint32_t per, auto*& c) {
          std::vector<std::remove_reference_t<decltype(*c)>> h(size_t{num_slots} * per);
          in.array(h.data(), h.size());
          copy_to_device(c, h.data(), h.size());
        },
        dev_.veh);
    if (!in.done()) throw std::runtime_error("backend state: bytes left after its last array");
    // What the state leaves out, as the next step would find it after its own clearing (backend_state.hpp).
    LPSIM_CUDA_CHECK(cudaMemset(map_[1 - state_map_], 0, cells_ + kLaneMapPadding));
    if (junction_stand_[1 - state_map_] != nullptr)
      LPSIM_CUDA_CHECK(cudaMemset(junction_stand_[1 - state_map_], 0xFF, num_lanes_ * sizeof(uint32_t)));
    clear_step_marks();
    ++version_;
  }

 private:
  // Claims and merge requests count only in the step in their key (step_marks_wrap).
  void clear_step_marks() {
    const size_t nl = num_lanes_;
    LPSIM_CUDA_CHECK(cudaMemset(dev_.claims, 0, nl * sizeof(uint64_t)));
    LPSIM_CUDA_CHECK(cudaMemset(dev_.merge_requests, 0, kMergeSlots * nl * sizeof(uint64_t)));
  }

  // The exchanges' index lists and values, uploaded for one launch.
  uint32_t* upload_index(const std::vector<uint32_t>& index) {
    uint32_t* dev = border_index_.get(index.size());
    copy_to_device(dev, index.data(), index.size());
    return dev;
  }

  template <class T>
  void gather(const std::vector<uint32_t>& index, const T* from, std::vector<T>& out) {
    const uint32_t n = static_cast<uint32_t>(index.size());
    out.resize(n);
    if (n == 0) return;
    const uint32_t* dev_index = upload_index(index);
    T* values = reinterpret_cast<T*>(border_values_.get(n * sizeof(T)));
    LPSIM_LAUNCH(gather_kernel<T>, blocks_for(n), kBlock)(from, dev_index, n, values);
    LPSIM_CUDA_CHECK_LAUNCH(gather_kernel);
    copy_to_host(out.data(), values, n);
  }

  template <class T>
  void scatter(const std::vector<uint32_t>& index, const T* in, T* to) {
    const uint32_t n = static_cast<uint32_t>(index.size());
    if (n == 0) return;
    const uint32_t* dev_index = upload_index(index);
    T* values = reinterpret_cast<T*>(border_values_.get(n * sizeof(T)));
    copy_to_device(values, in, n);
    LPSIM_LAUNCH(scatter_kernel<T>, blocks_for(n), kBlock)(values, dev_index, n, to);
    LPSIM_CUDA_CHECK_LAUNCH(scatter_kernel);
  }

  // One of the step's passes over the active list (none when nothing is on the road: no pass would write).
  template <void (*VehiclePass)(StepContext&, uint32_t, uint32_t)>
  void launch_pass(int timer_event) {
    const uint32_t n = launched_;
    if (n == 0) return;
    LPSIM_LAUNCH(pass_kernel<VehiclePass>, blocks_for(n), kBlock)(ctx_, active_[cur_active_], n);
    LPSIM_CUDA_CHECK_LAUNCH(pass_kernel);
    timer_.mark(timer_event);
  }

  void rebuild(const std::vector<uint32_t>& added) {
    const uint32_t n = num_active_, kept = kept_count_, na = static_cast<uint32_t>(added.size());
    if (kept == n && na == 0) return;  // nobody left, nobody joined
    uint32_t* from = active_[cur_active_];
    uint32_t* to = active_[1 - cur_active_];
    if (n > 0) {
      size_t bytes = 0;
      LPSIM_CUDA_CHECK(
          cub::DeviceSelect::Flagged(nullptr, bytes, from, keep_, kept_, num_selected_.get(1), n));
      LPSIM_CUDA_CHECK(
          cub::DeviceSelect::Flagged(temp_.get(bytes), bytes, from, keep_, kept_, num_selected_.get(1), n));
    }
    uint32_t* add = added_.get(na);
    upload_async(add, added.data(), na, added_host_);
    size_t bytes = 0;
    LPSIM_CUDA_CHECK(cub::DeviceMerge::MergeKeys(nullptr, bytes, kept_, kept, add, na, to, AscendingIndex{}));
    LPSIM_CUDA_CHECK(
        cub::DeviceMerge::MergeKeys(temp_.get(bytes), bytes, kept_, kept, add, na, to, AscendingIndex{}));
    cur_active_ = 1 - cur_active_;
    num_active_ = kept + na;
  }

  /// Plan scratch, one entry per active-list position (PlanView): one allocation carved into the columns,
  /// regrown by half again when the active list outgrows it. The plan pass writes every entry the commit
  /// pass reads, so the contents need not survive a regrowth.
  void reserve_plan_slots(uint32_t n) {
    if (n <= plan_capacity_) return;
    const size_t c = std::max<size_t>(n, plan_capacity_ + plan_capacity_ / 2);
    size_t words = 0, bytes = 0;
    visit_plan_columns(
        [&](uint32_t, auto* column) { (sizeof(*column) == 1 ? bytes : words) += sizeof(*column) * c; },
        dev_.plan);
    words = (words + 255) / 256 * 256;  // keeps the byte columns aligned
    plan_bytes_ = words + bytes;
    plan_buffer_ = DeviceBuffer(plan_bytes_);
    char* word_base = static_cast<char*>(plan_buffer_.get());
    char* byte_base = word_base + words;  // the byte columns after the aligned words
    visit_plan_columns(
        [&](uint32_t, auto*& column) {
          char*& base = sizeof(*column) == 1 ? byte_base : word_base;
          column = reinterpret_cast<std::remove_reference_t<decltype(column)>>(base);
          base += sizeof(*column) * c;
        },
        dev_.plan);
    plan_capacity_ = c;
    timer_.set_slot_bytes(slot_capacity_, slot_bytes_, plan_bytes_);
  }

  /// Makes room for `need` slots: the slot columns, both active lists and the keep flags grow by half again
  /// or to `need`, keeping their contents (a rare copy: the slots in use stay dense).
  void grow_slots(size_t need) {
    if (need <= slot_capacity_) return;
    const size_t old = slot_capacity_, c = std::max(need, old + old / 2);
    size_t col = 0, bytes = 0;
    auto regrow = [&](auto*& column, uint32_t per) {
      using T = std::remove_reference_t<decltype(*column)>;
      DeviceBuffer fresh(c * per * sizeof(T));
      if (old > 0)
        LPSIM_CUDA_CHECK(cudaMemcpy(fresh.get(), column, old * per * sizeof(T), cudaMemcpyDeviceToDevice));
      column = static_cast<T*>(fresh.get());
      if (col == slot_buffers_.size()) slot_buffers_.emplace_back();
      slot_buffers_[col++] = std::move(fresh);
      bytes += c * per * sizeof(T);
    };
    visit_vehicle_columns([&](uint32_t per, auto*& column) { regrow(column, per); }, dev_.veh);
    regrow(active_[0], 1u);
    regrow(active_[1], 1u);
    regrow(kept_, 1u);
    regrow(keep_, 1u);
    slot_capacity_ = c;
    slot_bytes_ = bytes;
    timer_.set_slot_bytes(slot_capacity_, slot_bytes_, plan_bytes_);
  }

  template <class T>
  T* allocate(size_t n) {
    buffers_.emplace_back(n * sizeof(T));
    bytes_total_ += n * sizeof(T);
    return static_cast<T*>(buffers_.back().get());
  }

  template <class T>
  T* upload(const T* host, size_t n) {
    T* dev = allocate<T>(n);
    copy_to_device(dev, host, n);
    return dev;
  }

  void upload_network(const StepperSetup& setup) {
    const NetView& h = setup.net;
    const size_t nl = h.num_lanes, nc = setup.num_connections;
    auto length = [&](NetExtent x) -> size_t {
      switch (x) {
        case NetExtent::kLanes:
          return nl;
        case NetExtent::kLanesPlusOne:
          return nl + 1;
        case NetExtent::kEdges:
          return setup.num_edges;
        case NetExtent::kConnections:
          return nc;
        case NetExtent::kConnectionsPlusOne:
          return nc + 1;
        case NetExtent::kFoes:
          return h.conn_foe_begin[nc];
        case NetExtent::kSignalsPlusOne:
          return size_t{setup.signals.num_signals} + 1;
        case NetExtent::kRestrictions:
          return h.lane_restriction_begin ? h.lane_restriction_begin[nl] : 0;
      }
      return 0;
    };
    NetView& d = dev_.net;
    d.num_lanes = h.num_lanes;
    visit_net_columns([&](NetExtent x, auto*& dev,
                          auto* host) { dev = host == nullptr ? nullptr : upload(host, length(x)); },
                      d, h);
  }

  void upload_signals(const SignalTable& h) {
    const uint32_t ns = h.num_signals;
    num_links_ = h.link_begin[ns];
    link_state_ = allocate<char>(num_links_);
    dev_.link_state = link_state_;
    signals_ = SignalTable{};
    signals_.num_signals = ns;
    if (ns == 0) return;
    // The link characters start unset: every signal sets them at its first update.
    const std::vector<int64_t> never(ns, kSignalNeverSet);
    signal_next_switch_ms_ = upload(never.data(), ns);
    const uint32_t phases = h.phase_begin[ns];
    size_t chars = 0;  // the state strings end after the last phase's links
    for (uint32_t s = 0; s < ns; ++s)
      for (uint32_t p = h.phase_begin[s]; p < h.phase_begin[s + 1]; ++p)
        chars = std::max<size_t>(chars,
                                 static_cast<size_t>(h.state_begin[p]) + static_cast<size_t>(h.num_links[s]));
    const uint32_t loops = h.actuated.signal_det_begin[ns];
    num_loops_ = loops;
    auto length = [&](SignalExtent x) -> size_t {
      switch (x) {
        case SignalExtent::kSignals:
          return ns;
        case SignalExtent::kSignalsPlusOne:
        case SignalExtent::kLinksPlusOne:
          return size_t{ns} + 1;
        case SignalExtent::kPhases:
          return phases;
        case SignalExtent::kPhasesPlusOne:
          return size_t{phases} + 1;
        case SignalExtent::kStateChars:
          return chars;
        case SignalExtent::kLoops:
          return loops;
        case SignalExtent::kPhaseLoops:
          return h.actuated.phase_det_begin[phases];
      }
      return 0;
    };
    visit_signal_columns([&](SignalExtent x, auto*& dev, auto* host) { dev = upload(host, length(x)); },
                         signals_, h);
    // Zero, as the CPU backend starts them: a fixed-time signal never writes them, and a saved state holds
    // them (the same bytes on either backend).
    actuated_state_.phase = allocate<int32_t>(ns);
    LPSIM_CUDA_CHECK(cudaMemset(actuated_state_.phase, 0, ns * sizeof(int32_t)));
    actuated_state_.phase_start_ms = allocate<int64_t>(ns);
    LPSIM_CUDA_CHECK(cudaMemset(actuated_state_.phase_start_ms, 0, ns * sizeof(int64_t)));
    const std::vector<int64_t> never_detected(loops, kNeverDetected);
    actuated_state_.det_last_ms = upload(never_detected.data(), loops);
  }

  // The run state's tables (backend_state.hpp), of the lane map the state is in.
  BackendTables<TableSpan> tables() {
    const uint64_t nl = num_lanes_, ns = signals_.num_signals;
    return BackendTables<TableSpan>{
        {map_[state_map_], cells_ + kLaneMapPadding},
        {link_state_, num_links_},
        {signal_next_switch_ms_, ns},
        {actuated_state_.phase, ns},
        {actuated_state_.phase_start_ms, ns},
        {actuated_state_.det_last_ms, num_loops_},
        {counters_, counters_ != nullptr ? kNumTrafficCounters * nl : 0},
        {dev_.em.sums, dev_.em.sums != nullptr ? kNumEmissionSums * nl : 0},
        {junction_stand_[state_map_], junction_stand_[state_map_] != nullptr ? nl : 0},
        {active_[cur_active_], num_active_}};
  }

  // Adds the lane records and the departed column to `columns` (LaneCounter order) and zeroes them.
  void drain_lane_records(int64_t* const* columns) {
    if (counters_ == nullptr) return;
    const size_t nl = num_lanes_;
    const std::vector<int64_t> all = take_counts(counters_, static_cast<size_t>(kNumTrafficCounters) * nl);
    add_lane_records(all.data(), all.data() + kLaneRecordCounters * nl, nl, columns);
  }

  // Adds `n` device columns of num_lanes at `from` (none: null) to `columns` and zeroes them.
  void drain(int64_t* from, int64_t* const* columns, int n) {
    if (from == nullptr) return;
    const size_t nl = num_lanes_;
    const std::vector<int64_t> all = take_counts(from, static_cast<size_t>(n) * nl);
    for (int k = 0; k < n; ++k)
      for (size_t l = 0; l < nl; ++l) columns[k][l] += all[static_cast<size_t>(k) * nl + l];
  }

  // The `n` counts at `from` on the device, which start again from zero.
  std::vector<int64_t> take_counts(int64_t* from, size_t n) {
    std::vector<int64_t> all(n);
    copy_to_host(all.data(), from, n);
    LPSIM_CUDA_CHECK(cudaMemset(from, 0, n * sizeof(int64_t)));
    return all;
  }

  // The types' emission columns and the per-lane sums of the emissions pass, zeroed.
  void upload_emissions(const EmissionView& h, uint32_t nt, uint32_t nl) {
    dev_.em = EmissionView{};
    visit_emission_columns([&](int per, auto*& dev, auto* host) { dev = upload(host, size_t{nt} * per); },
                           dev_.em, h);
    dev_.em.sums = allocate<int64_t>(static_cast<size_t>(kNumEmissionSums) * nl);
    dev_.em.num_lanes = nl;
    LPSIM_CUDA_CHECK(
        cudaMemset(dev_.em.sums, 0, kNumEmissionSums * static_cast<size_t>(nl) * sizeof(int64_t)));
  }

  void upload_types(const TypeView& h, uint32_t nt) {
    visit_type_columns([&](auto*& dev, auto* host) { dev = upload(host, nt); }, dev_.types, h);
  }

  std::vector<DeviceBuffer> buffers_;  // every fixed allocation, freed in the stepper's destructor
  StepContext dev_{};                  // device pointers; params and lane maps filled per step
  StepContext ctx_{};                  // the step being run
  DeviceTrips trips_;
  SignalTable signals_{};
  char* link_state_ = nullptr;
  int64_t* signal_next_switch_ms_ = nullptr;
  ActuatedState actuated_state_{};
  uint32_t num_links_ = 0, num_lanes_ = 0, num_loops_ = 0;
  uint64_t bytes_total_ = 0;  // fixed allocations (scratch arrays not included)
  DeviceBuffer plan_buffer_;
  size_t plan_capacity_ = 0, plan_bytes_ = 0;
  // The slot columns (dev_.veh), the active lists and the keep flags, each its own buffer, regrown together.
  std::vector<DeviceBuffer> slot_buffers_;
  size_t slot_capacity_ = 0, slot_bytes_ = 0;
  int64_t* counters_ = nullptr;  // the lane records, then departed; null without lane counters
  int64_t* cnt_departed_ = nullptr;
  uint64_t cells_ = 0;
  uint8_t* map_[2] = {nullptr, nullptr};
  uint32_t* junction_stand_[2] = {nullptr, nullptr};  // per lane, with map_'s index; null unless tracked
  NetView host_net_;   // the host's columns (the Simulation's), for the exchanges' host-side work
  int state_map_ = 0;  // the lane map the state is in: the one the last step wrote
  // The active list, ping-ponged between two buffers by rebuild.
  uint32_t* active_[2] = {nullptr, nullptr};
  int cur_active_ = 0;
  uint32_t num_active_ = 0, kept_count_ = 0;
  uint32_t* kept_ = nullptr;  // the kept slots, compacted
  uint8_t* keep_ = nullptr;   // per active index: stays active
  // The step's tally, then (from kEndsOffset) its ends; the pinned copy of the part fetched each step.
  static constexpr size_t kEndsOffset = 16;
  ScratchArray<unsigned char> outcome_;
  PinnedArray<unsigned char> outcome_host_;
  StepOutcome outcome_result_;
  uint32_t last_ends_ = 0;
  // The step started last: its active vehicles, and the ends fetched with its tally.
  uint32_t launched_ = 0, guess_ = 0;
  std::chrono::steady_clock::time_point t0_;
  ScratchArray<TeleportMove> moves_;
  ScratchArray<uint32_t> batch_in_, batch_out_, added_, num_selected_, trip_routes_;
  ScratchArray<unsigned char> temp_;
  ScratchArray<SlotInit> inits_;
  ScratchArray<SlotRoute> slot_routes_;
  ScratchArray<uint32_t> sort_keys_, sort_order_, sort_inverse_, sort_asked_;  // sort_slots
  ScratchArray<unsigned char> sort_moved_;
  ScratchArray<uint32_t> sample_vehicle_, sample_stop_release_;
  ScratchArray<uint8_t> sample_status_;
  ScratchArray<int32_t> sample_lane_;
  ScratchArray<float> sample_pos_, sample_speed_;
  ScratchArray<uint32_t> border_index_;        // the exchanges' lanes, cells or slots
  ScratchArray<unsigned char> border_values_;  // and their values
  PinnedArray<uint32_t> staging_in_, staging_out_;
  // Staging of the uploads that nothing waits for (upload_async).
  PinnedArray<TeleportMove> moves_host_;
  PinnedArray<SlotInit> inits_host_;
  PinnedArray<uint32_t> added_host_;
  // The host's copy of the state (fetch), and the state version it shows: every call that changes the state
  // counts one.
  HostVehicleColumns host_;
  std::vector<uint32_t> host_active_, sample_u32_;
  std::vector<uint8_t> sample_u8_;
  std::vector<int32_t> sample_i32_;
  std::vector<float> sample_f32_;
  std::vector<uint8_t> host_map_;
  std::vector<char> host_link_state_;
  HostState state_;
  uint64_t version_ = 0, fetched_version_ = ~uint64_t{0};
  int fetched_level_ = 0;  // the last copy: 0 Sample, 1 Columns, 2 Full
  PhaseTimer timer_;
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
      status.description += " (no NVIDIA driver, or one older than CUDA " +
                            std::to_string(CUDART_VERSION / 1000) + "." +
                            std::to_string(CUDART_VERSION % 1000 / 10) + " needs)";
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
  const std::string name =
      std::string(prop.name) + " (sm_" + std::to_string(prop.major) + std::to_string(prop.minor) + ")";
  int mode = cudaComputeModeDefault;
  if (cudaDeviceGetAttribute(&mode, cudaDevAttrComputeMode, 0) == cudaSuccess &&
      mode == cudaComputeModeProhibited) {
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

std::unique_ptr<Stepper> make_cuda_stepper(const StepperSetup& setup) {
  return std::make_unique<CudaStepper>(setup);
}

}  // namespace lpsim

#include "backends/cpu/cpu_stepper.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "backends/backend_state.hpp"
#include "backends/cpu/parallel_for.hpp"
#include "backends/cpu/pass_prefetch.hpp"
#include "backends/host_columns.hpp"
#include "backends/lane_records.hpp"
#include "backends/vehicle_packing.hpp"
#include "kernels/emission_step.hpp"
#include "kernels/insert_vehicle.hpp"
#include "kernels/signal_step.hpp"
#include "kernels/vehicle_step.hpp"

namespace lpsim {

namespace {

// Fewer active vehicles than this run the passes on the calling thread.
constexpr int64_t kParallelMinVehicles = 2048;

class CpuStepper final : public Stepper {
  // Where the passes find their vehicles' lanes (for the prefetch): the lane columns every pass reads.
  auto lane_columns() const {
    return [net = ctx_.net](int32_t l) { prefetch_lane_columns(net, l); };
  }

  // Only running vehicles have a front to plan from.
  auto front() const {
    const StepContext& c = ctx_;
    const uint32_t* act = active_.data();
    return [&c, act](int64_t i) {
      const uint32_t k = act[i];
      return LaneAt{c.veh.status[k] == kRunning ? c.veh.lane[k] : -1, c.veh.pos[k]};
    };
  }

 public:
  explicit CpuStepper(const StepperSetup& setup) : setup_(setup), pool_(std::max(1, setup.threads)) {
    const uint32_t nl = setup.net.num_lanes;
    const uint64_t cells = setup.net.lane_cell_begin[nl];
    for (auto& m : map_) m.assign(cells + kLaneMapPadding, 0);
    const uint32_t ns = setup.signals.num_signals;
    link_state_.assign(setup.signals.link_begin[ns], 'r');
    signal_next_switch_ms_.assign(ns, kSignalNeverSet);
    actuated_phase_.assign(ns, 0);
    actuated_start_ms_.assign(ns, 0);
    det_last_ms_.assign(setup.signals.actuated.signal_det_begin[ns], kNeverDetected);
    approach_.assign(nl, LaneApproach{0xFFFFFFFFu, -1, 0, 0, 0, 0, 0, 0});
    claims_.assign(nl, 0);
    merge_requests_.assign(static_cast<size_t>(kMergeSlots) * nl, 0);
    if (setup.lane_counters) {
      // The records aligned to a cache line, so that each lane's record is one line; departed after them.
      counters_.assign(static_cast<size_t>(kNumTrafficCounters) * nl + kLaneRecordCounters, 0);
      const size_t misalign = reinterpret_cast<uintptr_t>(counters_.data()) % 64 / sizeof(int64_t);
      lane_records_ = counters_.data() + (misalign == 0 ? 0 : kLaneRecordCounters - misalign);
      departed_ = lane_records_ + static_cast<size_t>(kLaneRecordCounters) * nl;
    }
    if (setup.emission_sums) emission_sums_.assign(static_cast<size_t>(kNumEmissionSums) * nl, 0);
    if (setup.junction_stands)
      for (auto& j : junction_stand_) j.assign(nl, kNoJunctionStand);
    trips_ = setup.trips;
  }

  void update_signals(int64_t time_ms, int64_t map_time_ms, int map_now) override {
    const SignalTable& t = setup_.signals;
    const SignalInputs in{map_[map_now].data(), map_time_ms, time_ms - map_time_ms};
    const ActuatedState st{actuated_phase_.data(), actuated_start_ms_.data(), det_last_ms_.data()};
    for (uint32_t s = 0; s < t.num_signals; ++s)
      update_signal(t, s, time_ms, in, link_state_.data(), signal_next_switch_ms_.data(), st);
  }

  void start_step(const StepParams& params, int map_now) override {
    state_map_ = 1 - map_now;
    plan_.reserve(active_.size(), false);
    ctx_ = context(map_[map_now].data(), map_[1 - map_now].data());
    ctx_.params = params;
    if (step_marks_wrap(params.step)) clear_step_marks();
    if (setup_.junction_stands) {  // double-buffered as the lane map
      ctx_.junction_stand_now = junction_stand_[map_now].data();
      ctx_.junction_stand_next = junction_stand_[1 - map_now].data();
    }
  }

  // Each pass is one parallel loop over the active vehicles, finished before the next starts. Each names
  // where its vehicles are (the footprint it clears or writes, the front it plans from) for the prefetch.
  void clear_footprints() override {
    const StepContext& c = ctx_;
    const uint32_t* act = active_.data();
    auto old_front = [&](int64_t i) { return LaneAt{c.veh.old_lane[act[i]], c.veh.old_pos[act[i]]}; };
    pass(old_front, ctx_.map_next, lane_columns(),
         [](StepContext& s, uint32_t i, uint32_t k) { clear_old_footprint(s, i, k); });
  }

  // Approach reads the lane map only for vehicles within reach of their lane's end: no cells fetched for it.
  void approach() override {
    pass(front(), nullptr, lane_columns(),
         [](StepContext& s, uint32_t i, uint32_t k) { approach_vehicle(s, i, k); });
  }

  void plan() override {
    const StepContext& c = ctx_;
    // The plan also reads the lane's neighbours (lane changes), kind and merge request.
    auto plan_lane_columns = [&](int32_t l) {
      prefetch_lane_columns(c.net, l);
      __builtin_prefetch(&c.merge_requests[static_cast<size_t>(l) * kMergeSlots]);
      __builtin_prefetch(&c.net.lane_left[l]);
      __builtin_prefetch(&c.net.lane_right[l]);
      __builtin_prefetch(&c.net.lane_internal[l]);
      __builtin_prefetch(&c.net.lane_rank[l]);
    };
    pass(front(), ctx_.map_now, plan_lane_columns,
         [](StepContext& s, uint32_t i, uint32_t k) { plan_vehicle(s, i, k); });
  }

  void commit() override {
    const StepContext& c = ctx_;
    const uint32_t* act = active_.data();
    // Only running vehicles' plans were written this step.
    auto new_front = [&](int64_t i) {
      return LaneAt{c.veh.status[act[i]] == kRunning ? c.plan.new_lane[i] : -1, c.plan.new_pos[i]};
    };
    pass(new_front, ctx_.map_next, lane_columns(),
         [](StepContext& s, uint32_t i, uint32_t k) { commit_vehicle(s, i, k); });
  }

  // Reads the footprint each vehicle had as the step began (the commit pass kept it as the old one).
  void count_emissions() override {
    const StepContext& c = ctx_;
    const uint32_t* act = active_.data();
    auto old_front = [&](int64_t i) { return LaneAt{c.veh.old_lane[act[i]], c.veh.old_pos[act[i]]}; };
    pass(old_front, nullptr, lane_columns(),
         [](StepContext& s, uint32_t i, uint32_t k) { count_vehicle_emissions(s, i, k); });
  }

  // One walk over the active list: the vehicles whose trip or road time ended in this step, and the slots
  // that stay active (running, or left the road in this step: the next clear pass removes their footprint).
  void start_end_of_step(uint32_t steps_done) override {
    const VehicleView& veh = ctx_.veh;
    outcome_.ends.clear();
    kept_.resize(active_.size());
    size_t kept = 0;
    uint32_t running = 0;
    for (const uint32_t k : active_) {
      const uint32_t kind = step_end_kind(veh, k, steps_done, first_teleport_steps(ctx_.params));
      if (kind != kEndNone) outcome_.ends.push_back(vehicle_end(veh, k, kind));
      running += veh.status[k] == kRunning ? 1u : 0u;
      kept_[kept] = k;  // a branch on staying would be mispredicted
      kept += stays_active(veh, k) ? 1u : 0u;
    }
    kept_.resize(kept);
    outcome_.kept = static_cast<uint32_t>(kept);
    outcome_.running = running;
  }

  StepOutcome& finish_end_of_step() override { return outcome_; }

  void apply_teleports(const std::vector<TeleportMove>& moves, uint32_t steps_done) override {
    for (const TeleportMove& m : moves) apply_teleport_move(veh_.view(), m, steps_done);
  }

  void insert(const InsertBatch& batch, uint32_t num_entries, const InsertParams& p, int map) override {
    if (num_entries == 0) return;
    uint8_t* into = map_[map].data();
    const StepContext ctx = context(map_[1 - map].data(), into);
    InsertParams params = p;
    params.cnt_departed = departed_;
    params.lane_counts = lane_records_;
    for (uint32_t slot = 0; slot < batch.num_slots; ++slot)
      insert_queue_head(ctx, trips_.depart, params, into, batch, slot);
  }

  void start_vehicles(const std::vector<SlotInit>& inits, const std::vector<uint32_t>& added) override {
    if (!added.empty()) veh_.reserve(size_t{added.back()} + 1, true);
    for (const SlotInit& init : inits) activate_slot(veh_.view(), trips_.trips, init);
    // The kept slots (ascending) and the new ones (ascending) make the next active list, ascending.
    active_.resize(kept_.size() + added.size());
    std::merge(kept_.begin(), kept_.end(), added.begin(), added.end(), active_.begin());
  }

  void sort_slots(std::vector<uint32_t>& slots) override {
    const size_t n = active_.size();
    VehicleView& veh = veh_.view();
    keys_.resize(n);
    for (size_t i = 0; i < n; ++i)
      keys_[i] = uint64_t{static_cast<uint32_t>(veh.lane[active_[i]])} << 32 | active_[i];
    std::sort(keys_.begin(), keys_.end());
    order_.resize(n);  // order[new slot] = old slot
    for (size_t i = 0; i < n; ++i) order_[i] = static_cast<uint32_t>(keys_[i]);
    visit_vehicle_columns(
        [&](uint32_t per, auto* column) {
          using T = std::remove_pointer_t<decltype(column)>;
          moved_.resize(n * per * sizeof(T));
          T* to = reinterpret_cast<T*>(moved_.data());
          for (size_t i = 0; i < n; ++i)
            for (uint32_t e = 0; e < per; ++e) to[i * per + e] = column[size_t{order_[i]} * per + e];
          std::copy_n(to, n * per, column);
        },
        veh);
    new_slot_.assign(veh_.capacity(), kNotActive);
    for (size_t i = 0; i < n; ++i) {
      new_slot_[order_[i]] = static_cast<uint32_t>(i);
      active_[i] = static_cast<uint32_t>(i);
    }
    for (uint32_t& k : slots) k = k < new_slot_.size() ? new_slot_[k] : kNotActive;
  }

  void update_trips(const TripTableView& now, const TripChanges&) override { trips_ = now; }

  void set_routes(const std::vector<SlotRoute>& routes) override {
    for (const SlotRoute& r : routes) set_slot_route(veh_.view(), r);
  }

  const HostState& fetch(StateParts, uint32_t) override {
    state_.active = active_.data();
    state_.num_active = static_cast<uint32_t>(active_.size());
    state_.veh = veh_.view();
    state_.map = map_[state_map_].data();
    state_.link_state = link_state_.data();
    return state_;
  }

  void write_footprints(int map, const std::vector<FootprintWrite>& writes, const uint8_t* held) override {
    uint8_t* m = map_[map].data();
    const NetView& net = setup_.net;
    for (const FootprintWrite& w : writes)
      for_each_footprint_piece(net, w.fp, w.length, [&](int32_t lane, uint32_t first, uint32_t last) {
        if (held[lane]) fill_cells(m, net, lane, first, last, w.value);
      });
  }

  void read_approaches(const std::vector<uint32_t>& lanes, std::vector<LaneApproach>& out) override {
    out.resize(lanes.size());
    for (size_t i = 0; i < lanes.size(); ++i) out[i] = approach_[lanes[i]];
  }

  void read_claims(const std::vector<uint32_t>& lanes, std::vector<uint64_t>& out) override {
    out.resize(lanes.size());
    for (size_t i = 0; i < lanes.size(); ++i) out[i] = claims_[lanes[i]];
  }

  void write_approaches(const std::vector<uint32_t>& lanes, const std::vector<LaneApproach>& in) override {
    for (size_t i = 0; i < lanes.size(); ++i) approach_[lanes[i]] = in[i];
  }

  void merge_claims(const std::vector<uint32_t>& lanes, const std::vector<uint64_t>& in) override {
    for (size_t i = 0; i < lanes.size(); ++i) claims_[lanes[i]] = std::max(claims_[lanes[i]], in[i]);
  }

  void read_link_states(uint32_t begin, uint32_t count, char* out) override {
    std::copy_n(link_state_.data() + begin, count, out);
  }

  void write_link_states(uint32_t begin, uint32_t count, const char* in) override {
    std::copy_n(in, count, link_state_.data() + begin);
  }

  void adopt_vehicles(const std::vector<uint32_t>& slots, const std::vector<uint8_t>& packed) override {
    if (slots.empty()) return;
    veh_.reserve(size_t{*std::max_element(slots.begin(), slots.end())} + 1, true);
    size_t at = 0;
    for (const uint32_t k : slots) {
      at += unpack_vehicle(packed.data() + at, veh_.view(), k);
      // The part they left clears their last footprint (their slot there stays one more step for it).
      veh_.view().old_lane[k] = -1;
    }
  }

  void mark_migrated(const std::vector<uint32_t>& slots) override {
    for (const uint32_t k : slots) veh_.view().status[k] = kMigrated;
  }

  void drain_counters(int64_t* const* columns) override {
    if (lane_records_ != nullptr) {
      add_lane_records(lane_records_, departed_, setup_.net.num_lanes, columns);
      std::fill(counters_.begin(), counters_.end(), 0);
    }
    drain(emission_sums_, columns + kCountEmissionFirst, kNumEmissionSums);
  }

  std::vector<uint8_t> save_state(uint32_t num_slots) override {
    StateBytesOut out;
    out.value(state_map_);
    BackendTables<TableSpan> t = tables();
    visit_backend_tables(t, [&](auto& span, Kept kept) { put_table(out, span.data, span.size, kept); });
    visit_vehicle_columns([&](uint32_t per, auto*& c) { out.array(c, uint64_t{num_slots} * per); },
                          veh_.view());
    return std::move(out.bytes());
  }

  void load_state(const std::vector<uint8_t>& state, uint32_t num_slots) override {
    StateBytesIn in(state);
    in.value(state_map_);
    if (state_map_ != 0 && state_map_ != 1)
      throw std::runtime_error("backend state: no lane map " + std::to_string(state_map_));
    if (num_slots > 0) veh_.reserve(num_slots, false);
    BackendTables<TableSpan> t = tables();
    visit_backend_tables(t, [&](auto& span, Kept kept) {
      if (kept == Kept::kActive)
        get_table(in, active_, kept);  // of the saved length
      else
        get_table(in, span.data, span.size, kept);
    });
    visit_vehicle_columns([&](uint32_t per, auto*& c) { in.array(c, uint64_t{num_slots} * per); },
                          veh_.view());
    if (!in.done()) throw std::runtime_error("backend state: bytes left after its last array");
    // What the state leaves out, as the next step would find it after its own clearing.
    std::fill(map_[1 - state_map_].begin(), map_[1 - state_map_].end(), uint8_t{0});
    std::fill(junction_stand_[1 - state_map_].begin(), junction_stand_[1 - state_map_].end(),
              kNoJunctionStand);
    clear_step_marks();
  }

 private:
  // Claims and merge requests count only in the step in their key (step_marks_wrap).
  void clear_step_marks() {
    std::fill(claims_.begin(), claims_.end(), 0);
    std::fill(merge_requests_.begin(), merge_requests_.end(), 0);
  }

  template <class T>
  static TableSpan<T> span_of(std::vector<T>& v) {
    return TableSpan<T>{v.data(), v.size()};
  }
  // The run state's tables (backend_state.hpp), of the lane map the state is in.
  BackendTables<TableSpan> tables() {
    const uint64_t nl = setup_.net.num_lanes;
    return BackendTables<TableSpan>{
        span_of(map_[state_map_]),
        span_of(link_state_),
        span_of(signal_next_switch_ms_),
        span_of(actuated_phase_),
        span_of(actuated_start_ms_),
        span_of(det_last_ms_),
        TableSpan<int64_t>{lane_records_, lane_records_ != nullptr ? kNumTrafficCounters * nl : 0},
        span_of(emission_sums_),
        span_of(junction_stand_[state_map_]),
        span_of(active_)};
  }

  // Adds `n` columns of num_lanes kept in `from` (none when it is empty) to `columns` and zeroes them.
  void drain(std::vector<int64_t>& from, int64_t* const* columns, int n) const {
    if (from.empty()) return;
    const size_t nl = setup_.net.num_lanes;
    for (int k = 0; k < n; ++k)
      for (size_t l = 0; l < nl; ++l) {
        int64_t& c = from[static_cast<size_t>(k) * nl + l];
        columns[k][l] += c;
        c = 0;
      }
  }

  StepContext context(const uint8_t* map_now, uint8_t* map_next) {
    StepContext ctx{};
    ctx.net = setup_.net;
    ctx.types = setup_.types;
    ctx.trips = trips_.trips;
    ctx.veh = veh_.view();
    ctx.plan = plan_.view();
    ctx.map_now = map_now;
    ctx.map_next = map_next;
    ctx.link_state = link_state_.data();
    ctx.approach = approach_.data();
    ctx.claims = claims_.data();
    ctx.merge_requests = merge_requests_.data();
    ctx.yielder_begin = setup_.yielder_begin;
    ctx.yielder = setup_.yielder;
    ctx.lane_counts = lane_records_;  // null when no output wants them: the passes then skip their atomics
    ctx.em = setup_.emission_types;
    ctx.em.sums = emission_sums_.empty() ? nullptr : emission_sums_.data();
    ctx.em.num_lanes = setup_.net.num_lanes;
    return ctx;
  }

  template <class Where, class FetchLane, class VehiclePass>
  void pass(Where where, const uint8_t* map, FetchLane fetch_lane, VehiclePass vehicle_pass) {
    const int64_t n = static_cast<int64_t>(active_.size());
    const uint32_t* act = active_.data();
    StepContext& ctx = ctx_;
    pool_.run(
        n,
        [&](int64_t b, int64_t e) {
          run_prefetched(b, e, ctx.net, map, where, fetch_lane,
                         [&](int64_t i) { vehicle_pass(ctx, static_cast<uint32_t>(i), act[i]); });
        },
        kParallelMinVehicles);
  }

  StepperSetup setup_;
  TripTableView trips_;
  ParallelFor pool_;
  StepContext ctx_{};
  std::vector<uint8_t> map_[2];
  int state_map_ = 0;  // the lane map the state is in: the one the last step wrote
  std::vector<char> link_state_;
  std::vector<int64_t> signal_next_switch_ms_;  // per signal: when the phase link_state_ shows ends
  std::vector<int32_t> actuated_phase_;         // ActuatedState
  std::vector<int64_t> actuated_start_ms_, det_last_ms_;
  std::vector<LaneApproach> approach_;
  std::vector<uint64_t> claims_, merge_requests_;
  std::vector<int64_t> counters_;    // the lane records, then departed; empty without lane counters
  int64_t* lane_records_ = nullptr;  // into counters_, at a cache-line boundary
  int64_t* departed_ = nullptr;
  std::vector<int64_t> emission_sums_;  // kNumEmissionSums columns of num_lanes; empty without emission sums
  std::vector<uint32_t> junction_stand_[2];  // per lane, with map_'s buffer index; empty unless tracked
  HostVehicleColumns veh_;
  HostPlanColumns plan_;
  std::vector<uint32_t> active_;  // slots the passes visit, ascending
  std::vector<uint32_t> kept_;    // active slots that stay active after the step (member: no page faults)
  StepOutcome outcome_;
  HostState state_;
  // sort_slots' scratch.
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> order_, new_slot_;
  std::vector<uint8_t> moved_;
};

}  // namespace

std::unique_ptr<Stepper> make_cpu_stepper(const StepperSetup& setup) {
  return std::make_unique<CpuStepper>(setup);
}

}  // namespace lpsim

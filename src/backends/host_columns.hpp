#pragma once
// Host storage for a view of columns (VehicleView, PlanView): one buffer per column of the view's column
// list (visit_vehicle_columns, visit_plan_columns), regrown together. The view's pointers are the storage.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

#include "kernels/step_view.hpp"

namespace lpsim {

/// Visit: a functor type calling visit_vehicle_columns or visit_plan_columns with its arguments.
template <class View, class Visit>
class HostColumns {
 public:
  HostColumns() = default;
  HostColumns(const HostColumns&) = delete;
  HostColumns& operator=(const HostColumns&) = delete;

  View& view() { return view_; }
  const View& view() const { return view_; }
  /// Entries each column holds (times its entries per slot).
  size_t capacity() const { return capacity_; }

  /// Room for at least n entries, by half again at least (a slowly growing list does not regrow every step).
  /// With `keep` the contents stay; new entries are zero.
  void reserve(size_t n, bool keep) {
    if (n <= capacity_) return;
    const size_t c = std::max(n, capacity_ + capacity_ / 2);
    size_t k = 0;
    Visit{}(
        [&](uint32_t per, auto*& column) {
          using T = std::remove_reference_t<decltype(*column)>;
          auto fresh = std::make_unique<std::byte[]>(c * per * sizeof(T));  // zeroed
          if (keep && capacity_ > 0) std::memcpy(fresh.get(), column, capacity_ * per * sizeof(T));
          column = reinterpret_cast<T*>(fresh.get());
          if (k == buffers_.size()) buffers_.emplace_back();
          buffers_[k++] = std::move(fresh);
        },
        view_);
    capacity_ = c;
  }

 private:
  View view_{};
  std::vector<std::unique_ptr<std::byte[]>> buffers_;
  size_t capacity_ = 0;
};

struct VisitVehicleColumns {
  template <class F, class... V>
  void operator()(F&& f, V&... v) const {
    visit_vehicle_columns(f, v...);
  }
};
struct VisitPlanColumns {
  template <class F, class... V>
  void operator()(F&& f, V&... v) const {
    visit_plan_columns(f, v...);
  }
};

using HostVehicleColumns = HostColumns<VehicleView, VisitVehicleColumns>;
using HostPlanColumns = HostColumns<PlanView, VisitPlanColumns>;

}  // namespace lpsim

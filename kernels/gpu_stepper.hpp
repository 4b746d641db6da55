#pragma once
// The CUDA backend as host code sees it: plain C++, no CUDA types, so the engine includes it without nvcc.
// The implementation (kernels/cuda_step.cu) exists only in builds that define LPSIM_HAVE_CUDA; the engine
// reaches it through src/engine/device_select, which reports "built without CUDA" otherwise.
#include <cstdint>
#include <memory>
#include <string>

namespace lpsim {

struct StepContext;
struct SignalTable;

/// Whether a CUDA device can run the step's kernels, and which one (or why not).
struct CudaDeviceStatus {
  bool usable = false;
  std::string description;  // usable: device name and compute capability; otherwise the reason
};

/// Array sizes the step's views do not carry themselves (they are raw pointers).
struct GpuStepSizes {
  uint32_t num_vehicles = 0;
  uint32_t num_edges = 0;
  uint32_t num_connections = 0;
  uint32_t num_types = 0;
  uint64_t num_route_edges = 0;
};

/// Runs a step's passes on a device. Owns device copies of every array in a StepContext.
class GpuStepper {
 public:
  virtual ~GpuStepper() = default;
  /// One step, on the device: signal states, then clear / approach / plan / commit over `active`
  /// (ascending vehicle indices). `host` is the CPU backend's context for the same step: the stepper
  /// copies in what the host changed since the last step and leaves in `host` exactly what the CPU
  /// backend would have left there (vehicle state, the lane map written, lane counters added).
  virtual void step(const StepContext& host, const uint32_t* active, uint32_t num_active) = 0;
};

#if defined(LPSIM_HAVE_CUDA)
/// Checks device 0: present, driver recent enough, and able to run this build's kernels.
CudaDeviceStatus cuda_device_status();
/// A stepper on device 0 holding the network, types and trips of `host` and its initial vehicle state.
/// Throws std::runtime_error naming the failed CUDA call and its file:line.
std::unique_ptr<GpuStepper> make_cuda_stepper(const StepContext& host, const SignalTable& signals,
                                              const GpuStepSizes& sizes);
#endif

}  // namespace lpsim

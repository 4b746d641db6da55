#include "engine/device_select.hpp"

#include "core/error.hpp"

namespace lpsim {

CudaDeviceStatus gpu_status() { return cuda_device_status(); }

DeviceChoice select_device(ComputeDevice requested) {
  if (requested == ComputeDevice::Cpu) return DeviceChoice{false, "cpu (requested)"};
  const CudaDeviceStatus status = gpu_status();
  if (status.usable) return DeviceChoice{true, "gpu (" + status.description + ")"};
  if (requested == ComputeDevice::Gpu)
    throw InputError(SourceLoc{"command line", 0},
                     "--device gpu: no usable CUDA device: " + status.description);
  return DeviceChoice{false, "cpu (no usable CUDA device: " + status.description + ")"};
}

std::unique_ptr<GpuStepper> make_gpu_stepper(const StepContext& host, const SignalTable& signals,
                                             const GpuStepSizes& sizes, const DepartView& depart,
                                             const uint8_t* other_map, int map_now,
                                             const std::vector<uint32_t>& active, bool lane_counters) {
  return make_cuda_stepper(host, signals, sizes, depart, other_map, map_now, active, lane_counters);
}

}  // namespace lpsim

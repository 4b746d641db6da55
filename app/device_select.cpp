#include "app/device_select.hpp"

#include "backends/cuda/cuda_stepper.hpp"
#include "core/error.hpp"

namespace lpsim {

DeviceChoice select_device(ComputeDevice requested) {
  if (requested == ComputeDevice::Cpu) return DeviceChoice{make_cpu_stepper, "cpu (requested)"};
  const CudaDeviceStatus status = cuda_device_status();
  if (status.usable) return DeviceChoice{make_cuda_stepper, "gpu (" + status.description + ")"};
  if (requested == ComputeDevice::Gpu)
    throw InputError(SourceLoc{"command line", 0},
                     "--device gpu: no usable CUDA device: " + status.description);
  return DeviceChoice{make_cpu_stepper, "cpu (no usable CUDA device: " + status.description + ")"};
}

}  // namespace lpsim

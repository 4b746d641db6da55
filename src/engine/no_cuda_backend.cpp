// The GPU backend of a build without CUDA (linked instead of kernels/cuda_step.cu): no device is usable, and
// asking for a stepper is an error.
#include <stdexcept>

#include "kernels/gpu_stepper.hpp"

namespace lpsim {

CudaDeviceStatus cuda_device_status() { return CudaDeviceStatus{false, "built without CUDA"}; }

std::unique_ptr<GpuStepper> make_cuda_stepper(const StepContext&, const SignalTable&, const GpuStepSizes&,
                                              const DepartView&, const uint8_t*, int,
                                              const std::vector<uint32_t>&, bool) {
  throw std::runtime_error("the GPU backend was requested, but lpsim was built without CUDA");
}

}  // namespace lpsim

// The GPU backend of a build without CUDA (linked instead of backends/cuda/cuda_stepper.cu): no device is
// usable, and asking for a stepper is an error.
#include <stdexcept>

#include "backends/cuda/cuda_stepper.hpp"

namespace lpsim {

CudaDeviceStatus cuda_device_status() { return CudaDeviceStatus{false, "built without CUDA"}; }

std::unique_ptr<Stepper> make_cuda_stepper(const StepperSetup&) {
  throw std::runtime_error("the GPU backend was requested, but lpsim was built without CUDA");
}

}  // namespace lpsim

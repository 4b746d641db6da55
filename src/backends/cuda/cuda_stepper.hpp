#pragma once
// The CUDA backend as host code sees it: plain C++, no CUDA types, so the engine includes it without nvcc.
// The backend an executable links defines these two functions: backends/cuda/cuda_stepper.cu (built by
// nvcc, or against the host emulation in tests/cuda_emulation), or backends/cuda/no_cuda_backend.cpp
// ("built without CUDA").
#include <memory>
#include <string>

#include "backends/stepper.hpp"

namespace lpsim {

/// Whether a CUDA device can run the step's kernels, and which one (or why not).
struct CudaDeviceStatus {
  bool usable = false;
  std::string description;  // usable: device name and compute capability; otherwise the reason
};

/// Whether the step can run on a GPU here: this build has the CUDA backend, and device 0 is present, has a
/// recent enough driver and can run this build's kernels. `description` names the device, or says why not
/// ("built without CUDA", a driver error...).
CudaDeviceStatus cuda_device_status();
/// A stepper on device 0 with the network, types and trips of `setup` and an empty road. Throws
/// std::runtime_error naming the failed CUDA call and its file:line, or, in a build without CUDA, saying so.
std::unique_ptr<Stepper> make_cuda_stepper(const StepperSetup& setup);

}  // namespace lpsim

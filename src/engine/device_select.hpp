#pragma once
// Which backend steps a simulation: the CPU (ParallelFor over the kernels/ passes) or a CUDA device
// (kernels/cuda_step.cu). Host code asks here rather than calling CUDA, so a build without CUDA compiles
// and answers "built without CUDA".
#include <memory>
#include <string>

#include "core/config_spec.hpp"
#include "kernels/gpu_stepper.hpp"

namespace lpsim {

/// Whether the step can run on a GPU here: this build has the CUDA backend and device 0 can run its
/// kernels. `description` names the device, or says why not ("built without CUDA", a driver error...).
CudaDeviceStatus gpu_status();

struct DeviceChoice {
  bool gpu = false;
  std::string description;  // one line for the user: "gpu (<device>)" or "cpu (<why no GPU>)"
};

/// Resolves --device. auto: the GPU when usable, else the CPU; cpu: the CPU; gpu: the GPU, or InputError
/// naming why no GPU is usable.
DeviceChoice select_device(ComputeDevice requested);

/// The CUDA stepper (see kernels/gpu_stepper.hpp). Throws std::runtime_error in a build without CUDA.
std::unique_ptr<GpuStepper> make_gpu_stepper(const StepContext& host, const SignalTable& signals,
                                             const GpuStepSizes& sizes, const DepartView& depart,
                                             const uint8_t* other_map, int map_now,
                                             const std::vector<uint32_t>& active, bool lane_counters);

}  // namespace lpsim

#pragma once
// Which backend steps a simulation: the CPU (ParallelFor over the kernels/ passes) or a CUDA device
// (kernels/cuda_step.cu, reached through kernels/gpu_stepper.hpp: cuda_device_status, make_cuda_stepper; a
// build without CUDA links src/engine/no_cuda_backend.cpp instead, which answers "built without CUDA").
#include <string>

#include "core/config_spec.hpp"

namespace lpsim {

struct DeviceChoice {
  bool gpu = false;
  std::string description;  // one line for the user: "gpu (<device>)" or "cpu (<why no GPU>)"
};

/// Resolves --device. auto: the GPU when usable, else the CPU; cpu: the CPU; gpu: the GPU, or InputError
/// naming why no GPU is usable.
DeviceChoice select_device(ComputeDevice requested);

}  // namespace lpsim

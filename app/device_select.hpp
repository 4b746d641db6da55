#pragma once
// Which backend steps a simulation: the CPU (backends/cpu) or a CUDA device (backends/cuda/cuda_stepper.cu,
// reached through backends/cuda/cuda_stepper.hpp; a build without CUDA links
// backends/cuda/no_cuda_backend.cpp instead, which answers "built without CUDA").
#include <string>

#include "backends/cpu/cpu_stepper.hpp"
#include "core/config_spec.hpp"

namespace lpsim {

struct DeviceChoice {
  StepperFactory backend = make_cpu_stepper;  // make_cuda_stepper with the GPU
  std::string description;  // one line for the user: "gpu (<device>)" or "cpu (<why no GPU>)"
};

/// Resolves --device. auto: the GPU when usable, else the CPU; cpu: the CPU; gpu: the GPU, or InputError
/// naming why no GPU is usable.
DeviceChoice select_device(ComputeDevice requested);

}  // namespace lpsim

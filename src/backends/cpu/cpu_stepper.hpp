#pragma once
// The CPU backend: the run state in host arrays, each pass a parallel loop (ParallelFor) over the same
// kernels/ functions the CUDA backend launches.
#include <memory>

#include "backends/stepper.hpp"

namespace lpsim {

std::unique_ptr<Stepper> make_cpu_stepper(const StepperSetup& setup);

}  // namespace lpsim

// The CUDA backend as it is, built by the host compiler: <cuda_runtime.h> and <cub/...> resolve to this
// folder's emulation (see cuda_runtime.h there).
// Small starting sizes, so that the tests run the paths for growth and for more ends than guessed.
#define LPSIM_GPU_INITIAL_SLOTS 1
#define LPSIM_GPU_MIN_ENDS_FETCHED 1
#include "backends/cuda/cuda_stepper.cu"

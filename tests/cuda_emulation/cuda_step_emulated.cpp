// The CUDA backend as it is, built by the host compiler: <cuda_runtime.h> and <cub/...> resolve to this
// folder's emulation (see cuda_runtime.h there).
#define LPSIM_GPU_INITIAL_SLOTS 1
#include "kernels/cuda_step.cu"

#pragma once
// Host emulation of the part of the CUDA runtime that backends/cuda/cuda_stepper.cu uses, so that the host
// compiler builds that file unchanged and the tests run the CUDA backend's own host logic (buffers, copies,
// launches, compaction, merges, the slot sort, its growth) on a machine without a GPU. "Device" memory is
// host memory filled with a poison byte when allocated (a read of what was never written shows up as a
// difference from the CPU backend, or under AddressSanitizer); copies and launches run at once, in the order
// issued, as on CUDA's default stream; a launch runs every thread of its grid one after another in a shuffled
// order (the kernels must not depend on thread order). What it cannot check: device arithmetic, real
// concurrency between threads, and stream timing — those need a GPU (tests/gpu on the real build).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <utility>
#include <vector>

#define CUDART_VERSION 13000
#define __global__
#define __device__
#define __host__
#define __launch_bounds__(...)

enum cudaError {
  cudaSuccess = 0,
  cudaErrorInvalidValue = 1,
  cudaErrorMemoryAllocation = 2,
  cudaErrorInsufficientDriver = 35,
  cudaErrorInvalidDevice = 101
};
using cudaError_t = cudaError;
enum cudaMemcpyKind {
  cudaMemcpyHostToHost = 0,
  cudaMemcpyHostToDevice = 1,
  cudaMemcpyDeviceToHost = 2,
  cudaMemcpyDeviceToDevice = 3
};
enum cudaDeviceAttr { cudaDevAttrComputeMode = 20 };
enum cudaComputeMode { cudaComputeModeDefault = 0, cudaComputeModeProhibited = 2 };
using cudaStream_t = struct cuda_emulation_stream*;
using cudaEvent_t = struct cuda_emulation_event*;

struct cudaDeviceProp {
  char name[256];
  int major, minor;
};
struct cudaFuncAttributes {
  int numRegs;
};

struct dim3 {
  unsigned x = 1, y = 1, z = 1;
};
// The built-in indices of the thread being run (set by cuda_emulation::launch).
inline thread_local dim3 blockIdx, threadIdx, blockDim, gridDim;

namespace cuda_emulation {

constexpr unsigned char kPoison = 0xBE;

// A fixed-seed generator, so that a run's thread orders, and so its results, repeat.
inline uint64_t next_random() {
  static thread_local uint64_t state = 0x9E3779B97F4A7C15ull;
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return state;
}

/// kernel<<<grid, block>>>(args...): every thread of the grid, one at a time, blocks and threads shuffled.
template <class... Params>
struct Launch {
  unsigned grid, block;
  void (*kernel)(Params...);
  template <class... Args>
  void operator()(Args&&... args) const {
    std::vector<uint32_t> order(static_cast<size_t>(grid) * block);
    std::iota(order.begin(), order.end(), 0u);
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[next_random() % i]);
    blockDim = dim3{block, 1, 1};
    gridDim = dim3{grid, 1, 1};
    for (const uint32_t t : order) {
      blockIdx = dim3{t / block, 0, 0};
      threadIdx = dim3{t % block, 0, 0};
      kernel(args...);
    }
  }
};

template <class... Params>
Launch<Params...> launch(unsigned grid, unsigned block, void (*kernel)(Params...)) {
  return Launch<Params...>{grid, block, kernel};
}

}  // namespace cuda_emulation

// Device atomics: the emulated threads run one at a time.
inline unsigned atomicAdd(unsigned* p, unsigned v) {
  const unsigned old = *p;
  *p = old + v;
  return old;
}

inline cudaError_t cudaMalloc(void** p, size_t bytes) {
  *p = std::malloc(bytes == 0 ? 1 : bytes);
  if (*p == nullptr) return cudaErrorMemoryAllocation;
  std::memset(*p, cuda_emulation::kPoison, bytes);
  return cudaSuccess;
}
template <class T>
cudaError_t cudaMalloc(T** p, size_t bytes) {
  return cudaMalloc(reinterpret_cast<void**>(p), bytes);
}
inline cudaError_t cudaFree(void* p) {
  std::free(p);
  return cudaSuccess;
}
inline cudaError_t cudaMallocHost(void** p, size_t bytes) { return cudaMalloc(p, bytes); }
template <class T>
cudaError_t cudaMallocHost(T** p, size_t bytes) {
  return cudaMalloc(reinterpret_cast<void**>(p), bytes);
}
inline cudaError_t cudaFreeHost(void* p) { return cudaFree(p); }

inline cudaError_t cudaMemcpy(void* dst, const void* src, size_t bytes, cudaMemcpyKind) {
  if (bytes > 0) std::memmove(dst, src, bytes);
  return cudaSuccess;
}
inline cudaError_t cudaMemcpyAsync(void* dst, const void* src, size_t bytes, cudaMemcpyKind kind,
                                   cudaStream_t = nullptr) {
  return cudaMemcpy(dst, src, bytes, kind);
}
// Every call above runs at once: the emulated device has nothing in flight to wait for.
inline cudaError_t cudaStreamSynchronize(cudaStream_t) { return cudaSuccess; }
inline cudaError_t cudaMemset(void* p, int value, size_t bytes) {
  std::memset(p, value, bytes);
  return cudaSuccess;
}
inline cudaError_t cudaMemsetAsync(void* p, int value, size_t bytes, cudaStream_t = nullptr) {
  return cudaMemset(p, value, bytes);
}

inline cudaError_t cudaGetLastError() { return cudaSuccess; }
inline const char* cudaGetErrorName(cudaError_t rc) {
  return rc == cudaSuccess ? "cudaSuccess" : "cudaError";
}
inline const char* cudaGetErrorString(cudaError_t rc) {
  return rc == cudaSuccess ? "no error" : "emulated CUDA error";
}

inline cudaError_t cudaGetDeviceCount(int* count) {
  *count = 1;
  return cudaSuccess;
}
inline cudaError_t cudaSetDevice(int device) { return device == 0 ? cudaSuccess : cudaErrorInvalidDevice; }
inline cudaError_t cudaGetDeviceProperties(cudaDeviceProp* prop, int) {
  *prop = cudaDeviceProp{};
  std::strcpy(prop->name, "CUDA emulated on the host");
  prop->major = 9;
  prop->minor = 0;
  return cudaSuccess;
}
inline cudaError_t cudaDeviceGetAttribute(int* value, cudaDeviceAttr, int) {
  *value = cudaComputeModeDefault;
  return cudaSuccess;
}
template <class F>
cudaError_t cudaFuncGetAttributes(cudaFuncAttributes* attr, F*) {
  *attr = cudaFuncAttributes{};
  return cudaSuccess;
}

// Events time nothing here: a run with LPSIM_GPU_TIMING reports zero device time.
inline cudaError_t cudaEventCreate(cudaEvent_t* e) {
  *e = nullptr;
  return cudaSuccess;
}
inline cudaError_t cudaEventRecord(cudaEvent_t, cudaStream_t = nullptr) { return cudaSuccess; }
inline cudaError_t cudaEventElapsedTime(float* ms, cudaEvent_t, cudaEvent_t) {
  *ms = 0;
  return cudaSuccess;
}
inline cudaError_t cudaEventDestroy(cudaEvent_t) { return cudaSuccess; }

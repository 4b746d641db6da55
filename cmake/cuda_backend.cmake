# LPSIM_CUDA=AUTO builds the CUDA backend when nvcc is found; ON requires it; OFF never builds it.
# The backend is src/backends/cuda/*.cu, launching kernels/cuda_kernels.cuh: thin __global__ wrappers over
# the same step functions the CPU runs.
set(LPSIM_WITH_CUDA OFF)
if(NOT LPSIM_CUDA STREQUAL "OFF")
  if(NOT CMAKE_CUDA_COMPILER AND EXISTS /usr/local/cuda/bin/nvcc)
    set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc)
  endif()
  include(CheckLanguage)
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    set(LPSIM_WITH_CUDA ON)
  elseif(LPSIM_CUDA STREQUAL "ON")
    message(FATAL_ERROR "LPSIM_CUDA=ON but no CUDA compiler (nvcc) was found")
  endif()
endif()

file(GLOB LPSIM_CUDA_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/backends/cuda/*.cu)
if(LPSIM_WITH_CUDA AND NOT LPSIM_CUDA_SOURCES)
  set(LPSIM_WITH_CUDA OFF)
  message(STATUS "LPSim CUDA backend: nvcc found, but no src/backends/cuda/*.cu to build yet")
elseif(LPSIM_WITH_CUDA)
  # Set before enable_language, which otherwise fills in nvcc's own default (sm_52 up to CUDA 12, sm_75 in
  # CUDA 13). A -DCMAKE_CUDA_ARCHITECTURES given by the user wins.
  if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
    set(CMAKE_CUDA_ARCHITECTURES 80 90)
  endif()
  enable_language(CUDA)
  find_package(CUDAToolkit REQUIRED)
  add_library(lpsim_cuda OBJECT ${LPSIM_CUDA_SOURCES})
  target_link_libraries(lpsim_cuda PUBLIC lpsim_backends)
  # The project-wide add_compile_options are host-compiler flags nvcc rejects ("Unknown option '-Wall'"):
  # replace them on this target with their nvcc spelling.
  # --fmad=false: identical arithmetic to the CPU build (which uses -ffp-contract=off).
  # CMake before 3.26 knows no C++20 dialect flag for nvcc ("requires the language dialect CUDA20"): tell it.
  if(NOT DEFINED CMAKE_CUDA20_STANDARD_COMPILE_OPTION)
    set(CMAKE_CUDA20_STANDARD_COMPILE_OPTION "-std=c++20")
    set(CMAKE_CUDA20_EXTENSION_COMPILE_OPTION "-std=c++20")
  endif()
  set_target_properties(lpsim_cuda PROPERTIES CUDA_STANDARD 20 CUDA_STANDARD_REQUIRED ON CUDA_EXTENSIONS OFF)
  set_property(TARGET lpsim_cuda PROPERTY COMPILE_OPTIONS "")
  target_compile_options(lpsim_cuda PRIVATE
    $<$<COMPILE_LANGUAGE:CUDA>:--fmad=false -Xcompiler=-Wall,-Wextra,-ffp-contract=off>)
  # What links it (LPSIM_BACKEND, in CMakeLists.txt) sees LPSIM_HAVE_CUDA.
  target_link_libraries(lpsim_cuda PUBLIC CUDA::cudart_static)
  target_compile_definitions(lpsim_cuda INTERFACE LPSIM_HAVE_CUDA=1)
  message(STATUS "LPSim CUDA backend: ON (${CMAKE_CUDA_COMPILER}, sm ${CMAKE_CUDA_ARCHITECTURES})")
else()
  message(STATUS "LPSim CUDA backend: OFF")
endif()

#!/usr/bin/env bash
# Builds LPSim and its tests with AddressSanitizer and UndefinedBehaviorSanitizer (float-to-int overflow
# included) into build-sanitize/, without the CUDA backend (but with its host emulation), and runs the CPU
# tests there: memory errors and undefined behaviour (which the optimised build may hide, and which the CPU
# and the GPU can resolve differently) fail the run. tools/test.sh runs it when CI=true; on two cores about
# seven minutes on a quiet VM, fourteen (700 s build, 152 s tests) on the slow one of 2026-12-01.
# Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# -Wno-maybe-uninitialized: with the sanitizers' instrumentation g++ 12 warns falsely inside libstdc++'s
# <regex> (used by tests); the optimised build stays warning-clean with every warning on.
# -g1: line tables only, which is what the sanitizers' reports print (file:line of each frame); full debug
# information made the build about a third slower (11.5 s against 7.5 s for src/engine/simulation.cpp).
flags="-O1 -g1 -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all"
flags+=" -Wno-maybe-uninitialized"
# Configured on every run (cheap), so that a changed flag reaches an existing build-sanitize/.
[ -f build-sanitize/CMakeCache.txt ] && generator=()
cmake -S . -B build-sanitize "${generator[@]}" -DCMAKE_BUILD_TYPE=Debug -DLPSIM_CUDA=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-sanitize -j "$(nproc)"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/tools/lsan_suppressions.txt}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
cd build-sanitize
# The format check does not depend on the build; the GPU tests skip without a GPU anyway. The emulated GPU
# tests (label gpu_emulation) run: each emulated device allocation is its own heap block, so the sanitizers
# see the CUDA backend's host logic overrun or reuse one.
# Label mpi is left out: LeakSanitizer reports OpenMPI's own allocations, which MPI_Finalize keeps, as leaks;
# the transport's logic runs under the sanitizers in its in-process form (label unit).
ctest --output-on-failure -j "$(nproc)" -E '^clang_format_clean$' -LE '^(gpu|mpi)$' "$@"

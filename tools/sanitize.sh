#!/usr/bin/env bash
# Builds LPSim and its tests with AddressSanitizer and UndefinedBehaviorSanitizer (float-to-int overflow
# included) into build-sanitize/, without the CUDA backend (but with its host emulation), and runs the CPU
# tests there: memory errors and undefined behaviour (which the optimised build may hide, and which the CPU
# and the GPU can resolve differently) fail the run. tools/test.sh runs it when CI=true.
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
# Only what the sanitizer pass runs: not the GPU tests (without the CUDA backend they only skip), the MPI
# tests (left out below) or the benchmarks. gtest_discover_tests lists each executable left unbuilt as one
# test named <target>_NOT_BUILT, which the run below leaves out.
cmake --build build-sanitize -j "$(nproc)" --target lpsim lpsim_emulated lpsim_unit_tests lpsim_sumo_tests \
  lpsim_slow_tests lpsim_cosim_tests lpsim_gpu_emulated_tests
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/tools/lsan_suppressions.txt}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
cd build-sanitize
# The format check does not depend on the build; the GPU tests skip without a GPU anyway. The emulated GPU
# tests (label gpu_emulation) run: each emulated device allocation is its own heap block, so the sanitizers
# see the CUDA backend's host logic overrun or reuse one.
# Label mpi is left out: LeakSanitizer reports OpenMPI's own allocations, which MPI_Finalize keeps, as leaks;
# the transport's logic runs under the sanitizers in its in-process form (label unit). Left out for CI's time
# (each starts lpsim a dozen times, slowest under the sanitizers): label slow (longer runs of what the unit
# tests run) and the determinism tests, which compare whole runs across thread and part counts. Both run in
# the optimised pass before; the code they reach runs here in the invariants, outputs and emulated GPU
# identity tests (parts included).
ctest --output-on-failure -j "$(nproc)" -E '^(clang_format_clean|EngineDeterminismTest\..*|.*_NOT_BUILT)$' \
  -LE '^(gpu|mpi|slow)$' "$@"

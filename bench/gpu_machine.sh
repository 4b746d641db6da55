#!/usr/bin/env bash
# Runs the GPU checks and benchmarks on a lent GPU machine that has CUDA but no package registry, from a
# CUDA build made elsewhere and carried along (bench/prepare_gpu_build.sh makes it and lists what to carry):
#   build-gpu/: cmake -DLPSIM_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90, Ninja, Release;
#   build-gpu/libs/: the shared libraries lpsim needs that such a machine may lack (zlib)
#                    and GNU time as gnu-time;  build-gpu/bayarea/lpsim_bayarea_tertiary: the base network.
# The tests have the repository's absolute path compiled in: where the copy lies elsewhere, a link stands in.
#
# Usage: bench/gpu_machine.sh tests|bench [regional_bench.sh options...]
set -uo pipefail
cd "$(dirname "$0")/.."
here=$PWD
build=${BUILD:-build-gpu}
export LD_LIBRARY_PATH=$here/$build/libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export GNU_TIME=$here/$build/libs/gnu-time
origin=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
if [[ -n "$origin" && "$origin" != "$here" && ! -e "$origin" ]]; then
  mkdir -p "$(dirname "$origin")" && ln -s "$here" "$origin"
fi
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv
what=${1:-tests}
shift || true
case "$what" in
  tests)
    "$build/lpsim" run -c scenarios/grid_tls/grid_tls.sumocfg --device gpu --end 5 | head -n 3
    "$build/tests/lpsim_gpu_tests" --gtest_color=no
    ;;
  bench)
    bench/regional_bench.sh --lpsim "$build/lpsim" --bayarea "$build/bayarea/lpsim_bayarea_tertiary" "$@"
    ;;
  *) echo "usage: $0 tests|bench [options]" >&2; exit 2 ;;
esac

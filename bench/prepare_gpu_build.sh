#!/usr/bin/env bash
# Prepares build-gpu/ here (where nvcc compiles but no GPU runs) for a lent GPU machine, which has CUDA,
# cmake and ninja but no package registry: the CUDA build of lpsim (without `cosim`) and of the GPU tests, the shared libraries
# lpsim needs that such a machine may lack (every one but the C and C++ runtimes, packed), GNU time as
# gnu-time, and
# the Bay Area base network the regional benchmark grows. Then pass the device tool
#   carry: build-gpu/lpsim build-gpu/tests/lpsim_gpu_tests build-gpu/libs.tar.xz build-gpu/bayarea
#          build-gpu/CMakeCache.txt build-gpu/COMMIT
# and run `bench/gpu_machine.sh all` there (or `tests`, then `bench ...`). COMMIT names the commit built
# (with "+changes" when the working tree differed), for the reports.
#
# Usage: bench/prepare_gpu_build.sh [CUDA architectures, default 90 (H100/H200)]
set -euo pipefail
cd "$(dirname "$0")/.."
arch=${1:-90}
build=${BUILD:-build-gpu}
# Without the co-simulation: libsumocpp's libraries would not fit the device tool's 64 MiB carry.
generator=()
[[ -f "$build/CMakeCache.txt" ]] || generator=(-G Ninja)
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DLPSIM_CUDA=ON \
  -DCMAKE_CUDA_ARCHITECTURES="$arch" -DLPSIM_COSIM=OFF
cmake --build "$build" --target lpsim lpsim_gpu_tests
commit=$(git rev-parse --short HEAD)
git diff --quiet HEAD -- . ':!bench/work' || commit="$commit+changes"
echo "$commit" >"$build/COMMIT"

mkdir -p "$build/libs"
# The C and C++ runtimes are on any machine with CUDA; the rest may not be: the XML reader's libraries and
# zlib, the partitioners' (METIS, igraph with its LAPACK and GLPK) and cairo's (the partition map). About
# 56 MiB, so they travel packed (libs.tar.xz) and gpu_machine.sh unpacks them into libs/.
rm -rf "$build/libs" "$build/libs.tar.xz"
mkdir -p "$build/libs"
ldd "$build/lpsim" | awk '$2 == "=>" && $3 ~ /^\// {print $3}' |
  grep -vE '/lib(c|m|stdc\+\+|gcc_s|pthread|dl|rt)\.so' | while read -r lib; do cp -L "$lib" "$build/libs/"; done
cp -L /usr/bin/time "$build/libs/gnu-time"
tar -C "$build" -cJf "$build/libs.tar.xz" libs

network=../shared/lpsim_bayarea_tertiary
if [[ -d "$network" ]]; then
  mkdir -p "$build/bayarea"
  cp -r "$network" "$build/bayarea/"
else
  echo "prepare_gpu_build: $network not found; the regional benchmark will need it" >&2
fi
du -sch "$build/lpsim" "$build/tests/lpsim_gpu_tests" "$build/libs.tar.xz" "$build/bayarea" "$build/CMakeCache.txt" \
  "$build/COMMIT" 2>/dev/null

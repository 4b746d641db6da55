#!/usr/bin/env bash
# Configures and builds LPSim into build/ (Release). LPSIM_CUDA=AUTO|ON|OFF picks the CUDA backend (AUTO:
# built when nvcc is found). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DLPSIM_CUDA="${LPSIM_CUDA:-AUTO}" "$@"
fi
cmake --build build -j "$(nproc)"

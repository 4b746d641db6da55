#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, runs every test (GPU tests skip without a GPU).
# With CI=true the CPU tests then run again under ASan/UBSan (tools/sanitize.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
tools/build.sh
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
(cd build && ctest --output-on-failure -j "$(nproc)" "$@")
if [[ "${CI:-}" == true ]]; then tools/sanitize.sh; fi

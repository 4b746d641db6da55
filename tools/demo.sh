#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and simulates a bundled scenario (a 5x5
# signalised grid with 1000 vehicles) on the GPU when a usable one is present, else on the CPU (it says
# which), writing SUMO-format outputs to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
tools/build.sh
mkdir -p out/demo
scenario=${1:-scenarios/grid_tls/grid_tls.sumocfg}
build/lpsim info -c "$scenario"
build/lpsim run -c "$scenario" --device auto --threads "$(nproc)" \
  --tripinfo-output out/demo/tripinfo.xml --edgedata-output out/demo/edgedata.xml \
  --summary-output out/demo/summary.xml --fcd-output out/demo/fcd.xml.gz
echo "outputs in out/demo/: tripinfo.xml edgedata.xml summary.xml fcd.xml.gz"

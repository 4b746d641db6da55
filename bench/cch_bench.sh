#!/usr/bin/env bash
# The contraction hierarchy's router (routing issue) on the original LPSim's Bay Area network (66k edges),
# side by side with the Dijkstra router in the same run: ordering and contraction, customization, random
# origin-destination queries per second on 1 and 2 threads (paths unpacked), Dijkstra's on a sample, and
# that sample's costs compared (exit 1 if any differs). Builds nothing: run tools/build.sh first.
#
# Usage: bench/cch_bench.sh [--queries N] [--dijkstra N] [--threads T] [--net DIR (nodes.csv, edges.csv)]
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
net="$repo/../shared/lpsim_bayarea_tertiary"
args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --net) net="$2"; shift 2 ;;
    --queries|--dijkstra|--threads|--seed) args+=("$1" "$2"); shift 2 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "cch_bench.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
echo "$(date -u +%Y-%m-%d) $(git -C "$repo" rev-parse --short HEAD) $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$repo/build/lpsim_cch_bench" "${args[@]}" --lpsim-nodes "$net/nodes.csv" --lpsim-edges "$net/edges.csv"

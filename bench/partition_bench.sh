#!/usr/bin/env bash
# Partition quality (partitioned-engine issue): `lpsim partition` with METIS, Leiden + k-means and the random
# baseline for each K on one scenario (default the regional 529k-edge network with 1M trips, a snapshot from
# bench/regional_bench.sh or `lpsim convert`). Per method and K: cut roads and lanes (the roads whose two
# junctions lie in different parts), ghost cells (the lane-map cells of the lanes of other parts each part must
# see: 1,000 m downstream, the longest vehicle upstream; src/partition/partition_layout.hpp) and the largest
# part's cells, ghosts included, over the network's (what a rank's lane map would hold),
# expected migrations (route uses of cut roads: vehicles crossing a cut over the demand) and per simulated
# step, imbalance (the largest part's expected vehicle-steps over the mean part's), the partitioner's wall time
# (graph building included, loading excluded) and the run's peak RSS. Writes bench/work/partition/results.md.
#
# Usage: bench/partition_bench.sh [--scenario FILE.lpsim|FILE.sumocfg] [--parts "2 4 8 16 32 64"]
#          [--methods "metis leiden random"] [--steps N (simulated steps the demand spans, for migrations per
#          step; default 86400: 12 h at 0.5 s)] [--lpsim PATH]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
scenario=bench/work/regional/1000000/regional.lpsim
parts_list="2 4 8 16 32 64"
methods="metis leiden random"
steps=86400
lpsim=build/lpsim
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenario) scenario="$2"; shift 2 ;;
    --parts) parts_list="$2"; shift 2 ;;
    --methods) methods="$2"; shift 2 ;;
    --steps) steps="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    *) echo "partition_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -f "$scenario" ]] || { echo "partition_bench: $scenario not found" >&2; exit 2; }
work=bench/work/partition
mkdir -p "$work"
input=(-c "$scenario")
[[ "$scenario" == *.lpsim ]] && input=("$scenario")
rows=()
for k in $parts_list; do
  for m in $methods; do
    log "K=$k $m"
    measured=$(measure "$work/$m-$k.log" "$lpsim" partition "${input[@]}" --parts "$k" --partition-method "$m" \
      -o "$work/$m-$k.txt") || { log "failed, see $work/$m-$k.log"; continue; }
    read -r _ _ rss <<<"$measured"
    secs=$(sed -n 's/.*, \([0-9.]*\) s (graph and partitioner).*/\1/p' "$work/$m-$k.log")
    line=$(grep '^parts ' "$work/$m-$k.log")
    roads=$(sed 's/.*cut roads \([0-9]*\),.*/\1/' <<<"$line")
    lanes=$(sed 's/.*cut lanes \([0-9]*\),.*/\1/' <<<"$line")
    cells=$(sed 's/.*ghost cells \([0-9]*\),.*/\1/' <<<"$line")
    share=$(sed 's/.*largest part \([0-9.]*\) of.*/\1/' <<<"$line")
    mig=$(sed 's/.*expected migrations \([0-9]*\),.*/\1/' <<<"$line")
    imb=$(sed 's/.*imbalance \([0-9.]*\) .*/\1/' <<<"$line")
    per_step=$(awk -v m="$mig" -v s="$steps" 'BEGIN { printf "%.1f", m / s }')
    rows+=("| $k | $m | $roads | $lanes | $cells | $share | $mig | $per_step | $imb | $secs | $rss |")
  done
done
{
  echo "Partition quality: \`bench/partition_bench.sh --scenario $scenario --parts \"$parts_list\"\`,"
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git rev-parse --short HEAD), $(nproc) cores."
  echo
  echo "| K | method | cut roads | cut lanes | ghost cells | largest part's cells / network's | expected migrations | per step ($steps steps) | imbalance | partition wall s | peak RSS MiB |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} | tee "$work/results.md"

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
# With --run-end T, the scenario is first run for T simulated seconds (K = 1, edgeData output) and the
# migrations that run made across each partition's cuts are counted too (trajectories do not depend on the
# partition), per step of that run.
#
# Usage: bench/partition_bench.sh [--scenario FILE.lpsim|FILE.sumocfg] [--parts "2 4 8 16 32 64"] [--run-end T [--run-step 0.5]]
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
run_end=
run_step=0.5
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenario) scenario="$2"; shift 2 ;;
    --parts) parts_list="$2"; shift 2 ;;
    --methods) methods="$2"; shift 2 ;;
    --steps) steps="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    --run-end) run_end="$2"; shift 2 ;;
    --run-step) run_step="$2"; shift 2 ;;
    *) echo "partition_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -f "$scenario" ]] || { echo "partition_bench: $scenario not found" >&2; exit 2; }
work=bench/work/partition
mkdir -p "$work"
input=(-c "$scenario")
[[ "$scenario" == *.lpsim ]] && input=("$scenario")
rows=()
measured_args=()
run_steps=
if [[ -n "$run_end" ]]; then
  log "running $scenario to $run_end s for the measured migrations"
  "$lpsim" run "${input[@]}" --end "$run_end" --step-length "$run_step" --threads "$(nproc)" \
    --edgedata-output "$work/run-edgedata.xml" --no-step-log --no-warnings >"$work/run.log" 2>&1
  measured_args=(--migrations-from "$work/run-edgedata.xml")
  run_steps=$(awk -v e="$run_end" -v s="$run_step" 'BEGIN { printf "%d", e / s }')
fi
for k in $parts_list; do
  for m in $methods; do
    log "K=$k $m"
    measured=$(measure "$work/$m-$k.log" "$lpsim" partition "${input[@]}" --parts "$k" --partition-method "$m" \
      -o "$work/$m-$k.txt" "${measured_args[@]}") || { log "failed, see $work/$m-$k.log"; continue; }
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
    measured=-
    if [[ -n "$run_end" ]]; then
      n=$(sed -n 's/^measured migrations \([0-9]*\) .*/\1/p' "$work/$m-$k.log")
      measured="$n ($(awk -v n="$n" -v s="$run_steps" 'BEGIN { printf "%.2f", n / s }') per step)"
    fi
    rows+=("| $k | $m | $roads | $lanes | $cells | $share | $mig | $per_step | $measured | $imb | $secs | $rss |")
  done
done
{
  echo "Partition quality: \`bench/partition_bench.sh --scenario $scenario --parts \"$parts_list\"\`,"
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git rev-parse --short HEAD), $(nproc) cores."
  echo
  echo "| K | method | cut roads | cut lanes | ghost cells | largest part's cells / network's | expected migrations | per step ($steps steps) | measured in a run to ${run_end:-(none)} s | imbalance | partition wall s | peak RSS MiB |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} | tee "$work/results.md"

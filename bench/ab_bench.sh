#!/usr/bin/env bash
# Two lpsim binaries side by side on the same run, in alternated rounds (A B, B A, A B, ...) so that both
# meet the same machine load, with CPU seconds (user + sys) of each run and the median of each binary's
# rounds: how a change's speed is measured against the commit before it (docs/PERFORMANCE.md).
#
# Usage: bench/ab_bench.sh [--rounds N] [--label NAME] BIN_A BIN_B -- LPSIM_RUN_ARGS...
#   e.g. bench/ab_bench.sh --rounds 5 ../base/build/lpsim build/lpsim -- run -c bologna/run.sumocfg --threads 1
# Prints a markdown table row per round and the medians with their ratio (B / A). Runs in a scratch folder
# (outputs a scenario's add-files name land there).
set -euo pipefail
rounds=5
label=run
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --label) label="$2"; shift 2 ;;
    *) break ;;
  esac
done
a=$(realpath "$1")
b=$(realpath "$2")
shift 2
[[ "${1:-}" == -- ]] && shift
scratch=$(mktemp -d /tmp/lpsim_ab.XXXXXX)
trap 'rm -rf "$scratch"' EXIT

cpu_seconds() {  # binary args... -> user+sys seconds of one run
  local bin=$1
  shift
  (cd "$scratch" && /usr/bin/time -f '%U %S' -o "$scratch/time" "$bin" "$@" > "$scratch/out" 2> "$scratch/err") ||
    { echo "ab_bench: $bin failed:" >&2; tail -5 "$scratch/err" >&2; exit 1; }
  awk '{ printf "%.2f", $1 + $2 }' "$scratch/time"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| $label round | A CPU s | B CPU s | order |"
echo "|---|---:|---:|---|"
ta=() tb=()
for ((r = 1; r <= rounds; ++r)); do
  if ((r % 2)); then
    x=$(cpu_seconds "$a" "$@"); y=$(cpu_seconds "$b" "$@"); order="A B"
  else
    y=$(cpu_seconds "$b" "$@"); x=$(cpu_seconds "$a" "$@"); order="B A"
  fi
  ta+=("$x") tb+=("$y")
  echo "| $r | $x | $y | $order |"
done
ma=$(printf '%s\n' "${ta[@]}" | median)
mb=$(printf '%s\n' "${tb[@]}" | median)
echo "| median | $ma | $mb | B/A = $(awk -v a="$ma" -v b="$mb" 'BEGIN { printf "%.3f", b / a }') |"

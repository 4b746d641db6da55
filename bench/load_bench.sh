#!/usr/bin/env bash
# Load benchmark: how long SUMO and LPSim take (and how much memory they hold) to load a 100k-edge
# signalised grid with 1M vehicles on explicit routes. Prints a markdown table on stdout (also saved
# as bench/work/load/results.md); progress goes to stderr.
#
# Usage: bench/load_bench.sh [--runs N] [--force] [--lpsim PATH] [--cases abcd]
#                            [--grid N] [--vehicles N] [--out DIR]   (smaller scenarios for smoke runs)
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/bench/lib.sh"

runs=3
force=()
lpsim="$repo/build/lpsim"
cases=abcd  # letters of the cases to run: a, b (SUMO), c, d (LPSim)
gen_args=()
work=bench/work/load
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --force) force=(--force); shift ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --out) work="$2"; shift 2 ;;
    --grid|--vehicles|--seed|--duration) gen_args+=("$1" "$2"); shift 2 ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) echo "unknown option: $1" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "--runs needs a positive integer" >&2; exit 2; }
[[ "$cases" =~ ^[abcd]+$ ]] || { echo "--cases takes letters among a, b, c, d" >&2; exit 2; }
wants() { [[ "$cases" == *"$1"* ]]; }

cd "$repo"
config="$work/load.sumocfg"
snapshot="$work/load.lpsim"
logs="$work/logs"
mkdir -p "$logs"

log "scenario: $work"
gen_start=$SECONDS
/usr/bin/python3 bench/make_load_scenario.py --out "$work" ${force[@]+"${force[@]}"} ${gen_args[@]+"${gen_args[@]}"}
gen_seconds=$((SECONDS - gen_start))
log "scenario ready (${gen_seconds} s)"

declare -A WALL CPU RSS CMD NOTE LOADED
order=()

# bench_case KEY CMD...: runs CMD $runs times and keeps the medians; returns non-zero if a run failed.
bench_case() {
  local key="$1"; shift
  local walls=() cpus=() rsss=() i out status
  CMD[$key]="$*"
  order+=("$key")
  for ((i = 1; i <= runs; i++)); do
    log "$key run $i/$runs: $*"
    status=0
    out=$(measure "$logs/$key.$i.log" "$@") || status=$?
    if [[ $status -ne 0 ]]; then
      NOTE[$key]="failed (exit $status): $(tail -n 1 "$logs/$key.$i.log" | cut -c1-160)"
      log "$key failed with exit status $status; log: $logs/$key.$i.log"
      tail -n 5 "$logs/$key.$i.log" >&2 || true
      return 1
    fi
    read -r w c r <<<"$out"
    log "  wall ${w} s, cpu ${c} s, peak RSS ${r} MiB"
    walls+=("$w"); cpus+=("$c"); rsss+=("$r")
  done
  WALL[$key]=$(median "${walls[@]}")
  CPU[$key]=$(median "${cpus[@]}")
  RSS[$key]=$(median "${rsss[@]}")
  # SUMO's statistics line "Inserted: 0 (Loaded: N)" says how many vehicles it actually read.
  LOADED[$key]=$(sed -n 's/.*(Loaded: \([0-9]*\)).*/\1/p' "$logs/$key.1.log" | tail -n 1)
}

if wants a; then
  bench_case sumo_all sumo -c "$config" --end 0 --no-step-log --route-steps 0 --duration-log.statistics || true
fi
if wants b; then
  bench_case sumo_default sumo -c "$config" --end 0 --no-step-log --duration-log.statistics || true
fi

lpsim_state="not run"
if ! wants c && ! wants d; then
  lpsim_state="not requested (--cases $cases)"
elif [[ ! -x "$lpsim" ]]; then
  lpsim_state="$lpsim does not exist or is not executable: LPSim rows skipped (build it with tools/build.sh)"
elif wants c && ! bench_case lpsim_full "$lpsim" info -c "$config"; then
  lpsim_state="lpsim info -c failed: ${NOTE[lpsim_full]}"
else
  lpsim_state="ok"
  if ! wants d; then
    :
  elif bench_case lpsim_convert "$lpsim" convert -c "$config" -o "$snapshot" &&
     bench_case lpsim_snapshot "$lpsim" info "$snapshot"; then
    :
  else
    lpsim_state="snapshot path failed: ${NOTE[lpsim_convert]:-${NOTE[lpsim_snapshot]:-}}"
  fi
fi
[[ "$lpsim_state" == ok ]] || log "$lpsim_state"

declare -A LABEL=(
  [sumo_all]="(a) SUMO, all routes loaded (--route-steps 0)"
  [sumo_default]="(b) SUMO, default --route-steps 200 (loads routes lazily while it runs; with --end 0 see 'vehicles loaded')"
  [lpsim_full]="(c) LPSim full load + build (info -c)"
  [lpsim_convert]="(d1) LPSim convert to snapshot"
  [lpsim_snapshot]="(d2) LPSim snapshot load (info load.lpsim)"
)

report() {
  local base_wall="${WALL[sumo_all]:-}" base_rss="${RSS[sumo_all]:-}"
  echo "## Load benchmark: $(grep -c '<vehicle ' "$work/routes.rou.xml") vehicles," \
       "$(grep -c '<edge id="[^:]' "$work/net.xml") edges"
  echo
  machine_info
  echo "- runs per case: $runs (medians shown); scenario check/generation before the runs: ${gen_seconds} s"
  echo "- lpsim: $lpsim_state"
  echo
  echo "| case | wall s | CPU s | peak RSS MiB | vehicles loaded | SUMO(a) CPU / case CPU | SUMO(a) wall / case wall | case RSS / SUMO(a) RSS |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  local key time_ratio cpu_ratio mem_ratio
  for key in "${order[@]}"; do
    if [[ -z "${WALL[$key]:-}" ]]; then
      echo "| ${LABEL[$key]} | ${NOTE[$key]:-failed} | | | | | | |"
      continue
    fi
    time_ratio="-"; cpu_ratio="-"; mem_ratio="-"
    if [[ "$key" == lpsim_full || "$key" == lpsim_snapshot ]]; then
      time_ratio=$(ratio "$base_wall" "${WALL[$key]}")
      cpu_ratio=$(ratio "${CPU[sumo_all]:-}" "${CPU[$key]}")
      mem_ratio=$(ratio "${RSS[$key]}" "$base_rss")
    fi
    echo "| ${LABEL[$key]} | ${WALL[$key]} | ${CPU[$key]} | ${RSS[$key]} | ${LOADED[$key]:--} | $cpu_ratio | $time_ratio | $mem_ratio |"
  done
  echo
  echo "Commands (run from the repository root; SUMO_HOME=$SUMO_HOME; timed with /usr/bin/time -v):"
  echo
  echo '```'
  for key in "${order[@]}"; do echo "${CMD[$key]}"; done
  echo '```'
}

report | tee "$work/results.md"
log "results saved to $work/results.md"

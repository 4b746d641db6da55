#!/usr/bin/env bash
# Routing benchmark: duarouter vs LPSim's free-flow router on ~100k random trips over a 40x40 grid.
# Throughput is trips per CPU second (user+sys from /usr/bin/time -v); route quality is the total
# free-flow travel time of the routes, both evaluated by LPSim on the same net. Prints a markdown table
# on stdout (also saved as bench/work/routing/results.md); progress goes to stderr.
#
# Usage: bench/routing_bench.sh [--runs N] [--force] [--lpsim PATH] [--threads N]
#                               [--algorithm NAME]   (duarouter --routing-algorithm; default: its own)
#                               [--grid N] [--period S] [--out DIR]   (smaller scenarios for smoke runs)
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/bench/lib.sh"

runs=1
gen_args=()
lpsim="$repo/build/lpsim"
threads=2
algorithm=""
work=bench/work/routing
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --force) gen_args+=(--force); shift ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --algorithm) algorithm="$2"; shift 2 ;;
    --grid|--period|--end) gen_args+=("$1" "$2"); shift 2 ;;
    --out) work="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "unknown option: $1" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "--runs needs a positive integer" >&2; exit 2; }

cd "$repo"
net="$work/net.xml"
trips="$work/trips.xml"
routes="$work/duarouter.rou.xml"
logs="$work/logs"

gen_start=$SECONDS
bench/make_routing_scenario.sh --out "$work" ${gen_args[@]+"${gen_args[@]}"}
gen_seconds=$((SECONDS - gen_start))
mkdir -p "$logs"
trip_count=$(grep -c '<trip ' "$trips")

# The algorithm duarouter uses when none is given, as its own option template states it.
default_algorithm=$(duarouter --save-template /dev/stdout 2>/dev/null |
  sed -n 's/.*<routing-algorithm value="\([^"]*\)".*/\1/p')
duarouter_cmd=(duarouter -n "$net" -r "$trips" -o "$routes" --ignore-errors --no-step-log)
if [[ -n "$algorithm" ]]; then
  duarouter_cmd+=(--routing-algorithm "$algorithm")
else
  algorithm="$default_algorithm (default)"
fi

# timed_runs NAME CMD...: runs CMD $runs times; sets T_WALL/T_CPU/T_RSS to medians; log of run 1 kept.
timed_runs() {
  local name="$1"; shift
  local walls=() cpus=() rsss=() i out w c r
  for ((i = 1; i <= runs; i++)); do
    log "$name run $i/$runs: $*"
    out=$(measure "$logs/$name.$i.log" "$@") || {
      log "$name failed (exit $?); log: $logs/$name.$i.log"
      tail -n 5 "$logs/$name.$i.log" >&2 || true
      return 1
    }
    read -r w c r <<<"$out"
    log "  wall ${w} s, cpu ${c} s, peak RSS ${r} MiB"
    walls+=("$w"); cpus+=("$c"); rsss+=("$r")
  done
  T_WALL=$(median "${walls[@]}"); T_CPU=$(median "${cpus[@]}"); T_RSS=$(median "${rsss[@]}")
}

# Values printed by `lpsim info` (empty when the line is absent).
# `routing: N trips (M distinct requests)` and `load time: T s (routing S s, X trips/s)` -> "N S X".
routing_rate() {
  local n rest
  n=$(sed -n 's/^routing: \([0-9]*\) trips.*$/\1/p' "$1" | tail -n 1)
  rest=$(sed -n 's/^load time: .*(routing \([0-9.eE+-]*\) s, \([0-9.eE+-]*\) trips\/s).*$/\1 \2/p' "$1" | tail -n 1)
  [[ -n "$n" && -n "$rest" ]] && echo "$n $rest"
}
free_flow_cost() { sed -n 's/^.*free-flow route cost: \([0-9.eE+-]*\) s.*$/\1/p' "$1" | tail -n 1; }

timed_runs duarouter "${duarouter_cmd[@]}"
dua_wall=$T_WALL dua_cpu=$T_CPU dua_rss=$T_RSS
dua_routed=$(grep -c '<vehicle ' "$routes" || true)
dua_rate=$(awk -v n="$dua_routed" -v c="$dua_cpu" 'BEGIN { if (c > 0) printf "%.0f", n / c; else print "n/a" }')

lpsim_state="ok"
lp_wall="" lp_cpu="" lp_rss="" lp_routed="" lp_route_s="" lp_rate="" lp_cost="" dua_cost=""
lpsim_cmd=("$lpsim" info -n "$net" -r "$trips" --threads "$threads")
eval_cmd=("$lpsim" info -n "$net" -r "$routes")
if [[ ! -x "$lpsim" ]]; then
  lpsim_state="$lpsim does not exist or is not executable: LPSim rows skipped (build it with tools/build.sh)"
elif ! timed_runs lpsim "${lpsim_cmd[@]}"; then
  lpsim_state="lpsim info -n -r trips failed: $(tail -n 1 "$logs/lpsim.1.log" | cut -c1-160)"
else
  lp_wall=$T_WALL lp_cpu=$T_CPU lp_rss=$T_RSS
  read -r lp_routed lp_route_s lp_rate < <(routing_rate "$logs/lpsim.1.log"; echo) || true
  lp_cost=$(free_flow_cost "$logs/lpsim.1.log")
  [[ -n "$lp_rate" ]] || lpsim_state="lpsim info printed no 'routing: N trips' / 'load time: ... (routing S s, X trips/s)' lines"
  log "free-flow cost of duarouter's routes: ${eval_cmd[*]}"
  if "${eval_cmd[@]}" >"$logs/lpsim_eval.log" 2>&1; then
    dua_cost=$(free_flow_cost "$logs/lpsim_eval.log")
  else
    log "evaluating duarouter's routes with lpsim failed; log: $logs/lpsim_eval.log"
  fi
fi
[[ "$lpsim_state" == ok ]] || log "$lpsim_state"

# LPSim's whole-process rate (load + route + report) is the figure comparable to duarouter's.
lp_total_rate=$(awk -v n="${lp_routed:-}" -v c="${lp_cpu:-}" \
  'BEGIN { if (n != "" && c > 0) printf "%.0f", n / c; else print "n/a" }')

report() {
  echo "## Routing benchmark: $trip_count trips on $(grep -c '<edge id="[^:]' "$net") edges"
  echo
  machine_info
  echo "- runs per case: $runs (medians shown); scenario check/generation: ${gen_seconds} s"
  echo "- duarouter routing algorithm: $algorithm"
  echo "- lpsim: $lpsim_state"
  echo
  echo "| router | trips routed | wall s | CPU s (user+sys) | peak RSS MiB | trips per CPU s (whole process) | trips/s (routing only, as reported) | total free-flow cost s |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  echo "| duarouter | $dua_routed | $dua_wall | $dua_cpu | $dua_rss | $dua_rate | - | ${dua_cost:-n/a} |"
  if [[ -n "$lp_wall" ]]; then
    echo "| lpsim (--threads $threads) | ${lp_routed:-n/a} | $lp_wall | $lp_cpu | $lp_rss | $lp_total_rate | ${lp_rate:-n/a} | ${lp_cost:-n/a} |"
  fi
  echo
  echo "- lpsim / duarouter trips per CPU s (whole process): $(ratio "$lp_total_rate" "$dua_rate")"
  echo "- lpsim routing-only trips/s / duarouter trips per CPU s: $(ratio "${lp_rate:-}" "$dua_rate")"
  echo "- lpsim / duarouter total free-flow cost: $(ratio "${lp_cost:-}" "${dua_cost:-}") (both costs computed by lpsim on the same net)"
  echo
  echo "Commands (run from the repository root; SUMO_HOME=$SUMO_HOME; timed with /usr/bin/time -v):"
  echo
  echo '```'
  echo "${duarouter_cmd[*]}"
  echo "${lpsim_cmd[*]}"
  echo "${eval_cmd[*]}"
  echo '```'
}

report | tee "$work/results.md"
log "results saved to $work/results.md"

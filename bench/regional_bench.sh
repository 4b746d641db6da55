#!/usr/bin/env bash
# Regional-scale benchmark (CUDA issue): the Bay Area tertiary network tiled 8x (tools/make_regional_scenario.py:
# ~249k nodes, ~529k edges) with 1M / 3M / 9M OD trips over 12 h, simulated at 0.5 s steps on the CPU backend
# (--threads nproc) and, when `lpsim run --device gpu` works here, on the CUDA backend, in the same run.
#
# Per trip count: the CSV scenario is generated (if missing) and converted once into a snapshot with its routes
# (`lpsim convert`: CSV load + routing, timed and reported apart); the runs load the snapshot. Per case:
#   vehicle-updates  sum over steps of the vehicles the passes visited (the run's own count, no output files),
#   sim wall s       the run's own "Duration" (simulation only: load excluded),
#   sim CPU s        CPU s of the run minus CPU s of `lpsim info` on the same snapshot (the load),
#   updates/s        vehicle-updates / sim wall s;  sim s per wall s: simulated seconds / sim wall s,
#   peak RSS, and on a GPU peak GPU memory (nvidia-smi sampled every 100 ms, minus the idle level).
# GPU runs set LPSIM_GPU_TIMING=1: the run prints where its time goes and the CUDA backend's device state per
# loaded vehicle, counted from its own allocations (reported below the table).
# Writes bench/work/regional/results.md.
#
# Usage: bench/regional_bench.sh [--trips "1000000 3000000 9000000"] [--devices "cpu gpu"] [--threads N]
#          [--end T] [--cpu-end T] [--step-length 0.5] [--runs N] [--warmup N] [--seed 42] [--tiles 8] [--lpsim PATH]
#          [--bayarea DIR (the base network; default ../shared/lpsim_bayarea_tertiary)]
#        bench/regional_bench.sh --selftest    (generator determinism + a tiny scenario loads; ~1 min)
# --end caps the simulated time (default: the whole 12 h), --cpu-end that of the CPU runs alone; capped runs
# are marked "capped" in the table.
# --runs: medians over N timed runs; --warmup: untimed runs before them (default 1 on a GPU, 0 on the CPU).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh

trips_list="1000000 3000000 9000000"
devices="cpu gpu"
threads=$(nproc)
hours=12
end=""
cpu_end=""
step=0.5
runs=1
warmup=""
seed=42
tiles=8
lpsim=build/lpsim
bayarea=()
selftest=0
python=${PYTHON:-python3}
while [[ $# -gt 0 ]]; do
  case "$1" in
    --trips) trips_list="$2"; shift 2 ;;
    --devices) devices="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --end) end="$2"; shift 2 ;;
    --cpu-end) cpu_end="$2"; shift 2 ;;
    --step-length) step="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --warmup) warmup="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --tiles) tiles="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    --bayarea) bayarea=(--bayarea "$2"); shift 2 ;;
    --selftest) selftest=1; shift ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
full=$(awk -v h="$hours" 'BEGIN { printf "%d", h * 3600 }')
[[ -n "$end" ]] || end=$full
capped=$(awk -v e="$end" -v f="$full" 'BEGIN { print (e < f) ? "yes" : "no" }')
gen=tools/make_regional_scenario.py
work=bench/work/regional
mkdir -p "$work"

# --- self test: same seed -> same bytes, other seed -> other demand, the result loads and routes fully. ---
if [[ $selftest == 1 ]]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  small=(--tiles 2 --scale 0.25 --trips 3000 --hours 1)
  "$python" "$gen" "${small[@]}" --seed 7 --out "$tmp/a" 2>/dev/null
  "$python" "$gen" "${small[@]}" --seed 7 --out "$tmp/b" 2>/dev/null
  "$python" "$gen" "${small[@]}" --seed 8 --out "$tmp/c" 2>/dev/null
  fail=0
  for f in nodes.csv edges.csv od.csv; do
    cmp -s "$tmp/a/$f" "$tmp/b/$f" || { echo "FAIL: $f differs between two runs with seed 7"; fail=1; }
  done
  cmp -s "$tmp/a/od.csv" "$tmp/c/od.csv" && { echo "FAIL: seeds 7 and 8 gave the same od.csv"; fail=1; }
  rows=$(($(wc -l <"$tmp/a/od.csv") - 1))
  [[ $rows == 3000 ]] || { echo "FAIL: od.csv has $rows trips, expected 3000"; fail=1; }
  if [[ -x "$lpsim" ]]; then
    "$lpsim" info --lpsim-nodes "$tmp/a/nodes.csv" --lpsim-edges "$tmp/a/edges.csv" --lpsim-od "$tmp/a/od.csv" \
      >"$tmp/info.txt" 2>&1 || { echo "FAIL: lpsim info on the generated scenario"; cat "$tmp/info.txt"; fail=1; }
    grep -q '^unrouted or skipped vehicles: 0$' "$tmp/info.txt" ||
      { echo "FAIL: some generated trips have no route:"; grep -i 'unrouted' "$tmp/info.txt"; fail=1; }
  else
    echo "note: $lpsim missing, load check skipped"
  fi
  [[ $fail == 0 ]] && echo "selftest: ok (deterministic, seeds differ, 3000 trips load and route)"
  exit "$fail"
fi

# "wall_s cpu_s rss_mib" from a GNU time -v report written earlier (as measure prints them).
measure_report() {
  awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); w = 0; for (i = 1; i <= n; i++) w = w * 60 + p[i] }
    /User time/ { c += $2 } /System time/ { c += $2 } /Maximum resident/ { m = $2 / 1024 }
    END { printf "%.2f %.2f %.1f\n", w, c, m }' "$1"
}

gpu_works() {
  local probe
  probe=$(find scenarios -name '*.sumocfg' | sort | head -n 1)
  [[ -n "$probe" ]] && "$lpsim" run -c "$probe" --device gpu --end 2 >"$work/gpu_probe.log" 2>&1
}

# Peak of `nvidia-smi memory.used` (MiB) while CMD runs, minus the level before it: "<peak_mib>" on fd 3.
gpu_sampler_start() {
  nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 100 >"$1" 2>/dev/null &
  sampler=$!
}
gpu_sampler_stop() {
  kill "$sampler" 2>/dev/null || true
  wait "$sampler" 2>/dev/null || true
  awk -v idle="$2" 'NF { if ($1 > m) m = $1 } END { printf "%.0f", (m > idle ? m - idle : 0) }' "$1"
}

[[ -x "$lpsim" ]] || { echo "no $lpsim: build it first (tools/build.sh)" >&2; exit 2; }
gpu_ok=no
if [[ " $devices " == *" gpu "* ]]; then
  if gpu_works; then gpu_ok=yes; else log "GPU backend not usable here: $(tail -n 1 "$work/gpu_probe.log")"; fi
fi

rows=()
states=()
prep=()
sizes=()
for trips in $trips_list; do
  dir="$work/$trips"
  want="tiles=$tiles .*trips=$trips hours=$hours seed=$seed scale=1$"
  if ! grep -qE "$want" "$dir/scenario.txt" 2>/dev/null; then
    log "generating $dir"
    rm -f "$dir/regional.lpsim"
    read -r gw gc gm < <(measure "$dir.gen.log" "$python" "$gen" --trips "$trips" --seed "$seed" \
      --tiles "$tiles" --hours "$hours" "${bayarea[@]}" --out "$dir") || { log "generation failed, see $dir.gen.log"; continue; }
    prep+=("| $trips | generate (tools/make_regional_scenario.py) | $gw | $gc | $gm |")
  fi
  snap="$dir/regional.lpsim"
  if [[ ! -f "$snap" ]]; then
    log "converting $dir to a snapshot (CSV load + routing)"
    read -r cw cc cm < <(measure "$dir/convert.log" "$lpsim" convert --lpsim-nodes "$dir/nodes.csv" \
      --lpsim-edges "$dir/edges.csv" --lpsim-od "$dir/od.csv" --threads "$threads" -o "$snap") ||
      { log "convert failed, see $dir/convert.log"; continue; }
    prep+=("| $trips | convert to snapshot, routes included (--threads $threads) | $cw | $cc | $cm |")
  elif [[ -f "$dir/convert.log.time" ]]; then
    read -r cw cc cm < <(measure_report "$dir/convert.log.time")
    prep+=("| $trips | convert to snapshot, routes included (earlier run, $(date -ur "$snap" '+%Y-%m-%d %H:%M UTC')) | $cw | $cc | $cm |")
  fi
  read -r lw lc lm < <(measure "$dir/info.log" "$lpsim" info "$snap") || { log "info failed, see $dir/info.log"; continue; }
  prep+=("| $trips | load the snapshot (lpsim info) | $lw | $lc | $lm |")
  sizes+=("- $trips trips: $(sed -n 's/^junctions: \([0-9]*\).*/\1 nodes/p; s/^edges: \([0-9]*\) normal.*/\1 edges/p;
    s/^lanes: \([0-9]*\) car lanes on normal edges (\([0-9.]*\) lane-km).*/\1 lanes, \2 lane-km/p;
    s/^lane map: .*(\(.*\))/lane map \1/p; s/^vehicles: \([0-9]*\)$/\1 vehicles/p;
    s/^routing: [0-9]* trips (\([0-9]*\) distinct requests)/\1 distinct routes/p' "$dir/info.log" |
    paste -sd, | sed 's/,[[:space:]]*/, /g')")

  for dev in $devices; do
    [[ $dev == gpu && $gpu_ok != yes ]] && continue
    nwarm=${warmup:-$([[ $dev == gpu ]] && echo 1 || echo 0)}
    dev_end=$end
    [[ $dev == cpu && -n "$cpu_end" ]] && dev_end=$cpu_end
    dev_capped=$(awk -v e="$dev_end" -v f="$full" 'BEGIN { print (e < f) ? "yes" : "no" }')
    run_env=()
    [[ $dev == gpu ]] && run_env=(env LPSIM_GPU_TIMING=1)
    cmd=("${run_env[@]}" "$lpsim" run "$snap" --device "$dev" --threads "$threads" --step-length "$step"
         --end "$dev_end")
    walls=(); cpus=(); rsss=(); gmems=()
    for ((r = 1 - nwarm; r <= runs; r++)); do
      log "$trips $dev run $r/$runs${r:+}: ${cmd[*]}"
      if [[ $dev == gpu ]]; then
        idle=$(nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits | head -n 1)
        gpu_sampler_start "$dir/gpu_mem.txt"
      fi
      status=0
      read -r w c m < <(measure "$dir/$dev.log" "${cmd[@]}") || status=$?
      [[ $dev == gpu ]] && gm=$(gpu_sampler_stop "$dir/gpu_mem.txt" "$idle")
      [[ $status == 0 ]] || { log "$dev run failed, see $dir/$dev.log"; break; }
      ((r >= 1)) || continue  # warm-up
      walls+=("$(sed -n 's/^ Duration: \([0-9.]*\)s.*/\1/p' "$dir/$dev.log")")
      cpus+=("$(awk -v c="$c" -v l="$lc" 'BEGIN { printf "%.2f", c - l }')")
      rsss+=("$m")
      [[ $dev == gpu ]] && gmems+=("$gm")
    done
    [[ ${#walls[@]} -gt 0 ]] || continue
    wall=$(median "${walls[@]}"); cpu=$(median "${cpus[@]}"); rss=$(median "${rsss[@]}")
    gmem=$([[ $dev == gpu ]] && median "${gmems[@]}" || echo "-")
    read -r n peak < <(sed -n 's/^ Vehicle updates: \([0-9]*\) (peak running \([0-9]*\))/\1 \2/p' "$dir/$dev.log")
    simulated=$(sed -n 's/^Simulation ended at time: //p' "$dir/$dev.log")
    ups=$(awk -v n="$n" -v w="$wall" 'BEGIN { printf "%.3g", n / w }')
    upc=$(awk -v n="$n" -v c="$cpu" 'BEGIN { if (c > 0) printf "%.3g", n / c; else print "n/a" }')
    rtf=$(awk -v s="$simulated" -v w="$wall" 'BEGIN { printf "%.1f", s / w }')
    label=$dev; [[ $dev == cpu ]] && label="cpu ($threads threads)"
    [[ $dev == gpu ]] && states+=("- $trips trips: $(sed -n 's/^GPU state: //p' "$dir/$dev.log")")
    rows+=("| $trips | $label | $simulated$([[ $dev_capped == yes ]] && echo ' (capped)' || true) | $n | $peak | $wall | $cpu | $ups | $upc | $rtf | $rss | $gmem |")
  done
done

{
  echo "### Regional benchmark: Bay Area x$tiles, trips ${trips_list// /, }, step $step s, end $end s"
  echo
  machine_info
  echo "- devices: $devices (GPU backend usable here: $gpu_ok); threads: $threads; runs: $runs (medians)"
  [[ $capped == yes ]] && echo "- **capped**: simulated only 0..$end s of the ${hours} h demand (--end $end)"
  [[ -n "$cpu_end" ]] && echo "- CPU runs **capped** at 0..$cpu_end s (--cpu-end $cpu_end)"
  printf '%s\n' "${sizes[@]}"
  echo
  echo "| trips | step | wall s | CPU s | peak RSS MiB |"
  echo "|---|---|---:|---:|---:|"
  printf '%s\n' "${prep[@]}"
  echo
  echo "| trips | device | simulated s | vehicle-updates | peak running | sim wall s | sim CPU s | updates/s | updates/CPU-s | sim s / wall s | peak RSS MiB | peak GPU MiB |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  if [[ ${#states[@]} -gt 0 ]]; then
    echo "CUDA backend device state, counted by the runs (target ≤ 64 B per vehicle + 4 B per route edge):"
    printf '%s\n' "${states[@]}"
  fi
  echo
  echo "Commands: \`bench/regional_bench.sh --trips \"$trips_list\" --devices \"$devices\" --threads $threads --end $end --runs $runs\`"
} | tee "$work/results.md"

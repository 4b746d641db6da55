#!/usr/bin/env bash
# Engine benchmark: vehicle-updates per CPU-second and peak memory of `lpsim run --threads 2` against SUMO
# (microscopic) and SUMO --mesosim on the same files in the same run; SUMO and LPSim both run the IDM
# (--default.carfollowmodel IDM: binaries before Krauss was implemented refuse that option).
#   scenario grid40: 40x40 signalised grid (netgenerate, 200 m, 2 lanes), 100k vehicles on explicit routes
#                    (random walks of 10-40 edges, departures over 3600 s), simulated for --end seconds;
#   scenario bologna: ../shared/scenarios/bologna_acosta (largest demand among the shared scenarios).
# Vehicle-updates are counted the same way for every simulator: the sum over steps of running vehicles,
# from each run's summary output. Prints a markdown table (also bench/work/engine/results.md).
#
# Usage: bench/engine_bench.sh [--end T] [--vehicles N] [--runs N] [--lpsim-repeats N]
#                              [--scenarios "grid40 bologna"] [--lpsim PATH]
# --runs N: rounds (sumo, meso, lpsim in turn); --lpsim-repeats N: LPSim runs per round, mean CPU time taken.
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh

end=1200
vehicles=100000
runs=1
lpsim_repeats=5
scenarios="grid40 bologna"
lpsim=build/lpsim
while [[ $# -gt 0 ]]; do
  case "$1" in
    --end) end="$2"; shift 2 ;;
    --vehicles) vehicles="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --lpsim-repeats) lpsim_repeats="$2"; shift 2 ;;
    --scenarios) scenarios="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done

work=bench/work/engine
mkdir -p "$work"

# Sum over steps of running vehicles in a SUMO-format summary file.
updates_of() {
  /usr/bin/python3 - "$1" <<'PY'
import sys, xml.etree.ElementTree as ET
total = 0
for _, el in ET.iterparse(sys.argv[1]):
    if el.tag == "step":
        total += int(el.get("running"))
        el.clear()
print(total)
PY
}

cfg_of() {
  case "$1" in
    grid40)
      /usr/bin/python3 bench/make_load_scenario.py --grid 40 --vehicles "$vehicles" --out "$work/grid40" >&2
      echo "$work/grid40/load.sumocfg" ;;
    bologna)
      # A copy in the work folder: the scenario's add-files name output files (detectors) that SUMO writes
      # beside them, and ../shared is not ours to write into.
      local src=../shared/scenarios/bologna_acosta
      [[ -d "$src" ]] || { echo "$src/run.sumocfg"; return; }
      mkdir -p "$work/bologna_src"
      cp -f "$src"/* "$work/bologna_src/"
      chmod u+w "$work/bologna_src"/*
      echo "$work/bologna_src/run.sumocfg" ;;
    *) echo "unknown scenario $1" >&2; exit 2 ;;
  esac
}

rows=()
notes=()
for sc in $scenarios; do
  cfg=$(cfg_of "$sc")
  [[ -f "$cfg" ]] || { log "skipping $sc: $cfg missing"; continue; }
  out="$work/$sc"
  mkdir -p "$out"
  declare -A cpus=() rsss=() cpu=() rss=() ups=() n=()
  # A tripinfo output the cfg names (Bologna's does) goes to the scenario's work folder, for all three
  # simulators, so they write the same files there. (SUMO also writes the detector files Bologna's add-file
  # names, beside the copy of the scenario.)
  extra=()
  if grep -q "tripinfo-output" "$cfg"; then extra=(--tripinfo-output "$out/tripinfo.xml"); fi
  # Rounds of sumo, meso, lpsim in turn, so that the three see the same machine load (these machines are
  # shared; a run of SUMO and one of LPSim minutes apart can see different loads). Within a round LPSim,
  # much the shortest run, is repeated and its mean CPU time taken, so that it is timed over a window
  # closer to SUMO's and above the 10 ms resolution of the timer.
  loads=()
  probes=()
  for ((r = 1; r <= runs; r++)); do
    loads+=("$(cut -d' ' -f1 /proc/loadavg)")
    # The L3 share this VM gets varies with its neighbours; SUMO's CPU time follows it, LPSim's far less.
    probes+=("$(host_probe | sed -n 's/.*, 4 MiB \([0-9.]*\) ns.*/\1/p')")
    for sim in sumo meso lpsim; do
      summary="$out/$sim.summary.xml"
      case "$sim" in
        sumo) cmd=(sumo -c "$cfg" --default.carfollowmodel IDM --end "$end" --no-step-log --summary-output "$summary") ;;
        meso) cmd=(sumo -c "$cfg" --mesosim --end "$end" --no-step-log --summary-output "$summary") ;;
        lpsim) cmd=("$lpsim" run -c "$cfg" --default.carfollowmodel IDM --threads 2 --end "$end" --summary-output "$summary") ;;
      esac
      cmd+=("${extra[@]}")
      # SUMO's log file too (LPSim writes none).
      if [[ "$sim" != lpsim ]] && grep -q "<log " "$cfg"; then cmd+=(--log "$out/$sim.sumo_log.txt"); fi
      reps=1
      [[ "$sim" == lpsim ]] && reps=$lpsim_repeats
      total=0
      for ((k = 1; k <= reps; k++)); do
        log "$sc round $r/$runs $sim run $k/$reps: ${cmd[*]}"
        read -r wall c m < <(measure "$out/$sim.log" "${cmd[@]}") || { log "$sim failed, see $out/$sim.log"; }
        total=$(awk -v t="$total" -v c="$c" 'BEGIN { print t + c }')
      done
      cpus[$sim]+="$(awk -v t="$total" -v k="$reps" 'BEGIN { printf "%.3f", t / k }') "
      rsss[$sim]+="$m "
    done
  done
  for sim in sumo meso lpsim; do
    # shellcheck disable=SC2086
    cpu[$sim]=$(median ${cpus[$sim]})
    # shellcheck disable=SC2086
    rss[$sim]=$(median ${rsss[$sim]})
    n[$sim]=$(updates_of "$out/$sim.summary.xml" 2>/dev/null || echo nan)
    ups[$sim]=$(awk -v n="${n[$sim]}" -v c="${cpu[$sim]}" 'BEGIN { if (c > 0) printf "%.0f", n / c; else print "nan" }')
    rows+=("| $sc | $sim | ${n[$sim]} | ${cpus[$sim]% } | ${ups[$sim]} | ${rss[$sim]} |")
  done
  # Ratio of each round (same updates every round: the runs are deterministic), and their median.
  per_round=()
  read -r -a cs <<<"${cpus[sumo]}"
  read -r -a cl <<<"${cpus[lpsim]}"
  for ((r = 0; r < runs; r++)); do
    per_round+=("$(awk -v ns="${n[sumo]}" -v nl="${n[lpsim]}" -v s="${cs[$r]}" -v l="${cl[$r]}" \
      'BEGIN { if (s > 0 && l > 0) printf "%.2f", (nl / l) / (ns / s); else print "nan" }')")
  done
  rows+=("| $sc | **lpsim / sumo** | | | **$(ratio "${ups[lpsim]}" "${ups[sumo]}")×** | $(ratio "${rss[lpsim]}" "${rss[sumo]}")× |")
  rows+=("| $sc | **lpsim / meso** | | | **$(ratio "${ups[lpsim]}" "${ups[meso]}")×** | $(ratio "${rss[lpsim]}" "${rss[meso]}")× |")
  notes+=("- $sc: lpsim / sumo in each round: ${per_round[*]} (median $(median "${per_round[@]}")×); load average at each round's start: ${loads[*]}; ns per load of a 4 MiB pointer chase (bench/host_probe.cpp) at each round's start: ${probes[*]}")
  unset cpus rsss cpu rss ups n
done

{
  echo "### Engine: vehicle-updates per CPU-second (end $end s, $runs rounds, LPSim $lpsim_repeats runs per round)"
  echo
  machine_info
  echo
  echo "| scenario | simulator | vehicle-updates | CPU s (each round) | updates / CPU-s (median) | peak RSS MiB |"
  echo "|---|---|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  printf '%s\n' "${notes[@]}"
} | tee "$work/results.md"

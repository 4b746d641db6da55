#!/usr/bin/env bash
# Checkpoints: the size of a saved state, the cost of saving it and whether a resumed run writes the same
# outputs, for LPSim (--save-state.times / --load-state) and, on a .sumocfg, for SUMO beside it
# (--save-state.times with --save-state.rng, then --load-state --begin T). Each simulator runs the scenario
# whole, then again saving at --at, then resumes from that state; the resumed trips are compared with the
# whole run's: LPSim's outputs byte for byte, SUMO's tripinfo line by line for the trips that
# end after the save. Works in copies (bench/work/state/), as add-file outputs land beside their files.
#
# --parts K runs LPSim's three runs in K parts in one process (one thread each), --mpi K as K MPI ranks:
# the state then holds every part's. --resume-parts K / --resume-mpi K resume it in other parts than those
# that saved it (in one process / as MPI ranks; --resume-parts 1: one part), the state re-cut for them. --all-outputs adds FCD, unfinished trips' tripinfo, edgeData, laneData and
# the statistic output to the tripinfo and summary compared.
#
# Usage: bench/state_bench.sh --scenario CFG_OR_SNAPSHOT --at T [--end T] [--threads 2] [--no-sumo]
#                             [--parts K | --mpi K] [--resume-parts K | --resume-mpi K] [--all-outputs]
#                             [--lpsim PATH]
# e.g.   bench/state_bench.sh --scenario ../shared/scenarios/bologna_acosta/run.sumocfg --at 1800
#        bench/state_bench.sh --scenario bench/work/regional/1000000/regional.lpsim --at 1800 --end 2400
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh

scenario=""
at=""
end=""
threads=2
sumo=1
parts=()
launch=()
more=()
resume_parts=()
resume_launch=()
resume_set=0
lpsim="$PWD/build/lpsim"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenario) scenario="$(realpath "$2")"; shift 2 ;;
    --at) at="$2"; shift 2 ;;
    --end) end="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --no-sumo) sumo=0; shift ;;
    --all-outputs) more=(--fcd-output fcd.xml --tripinfo-output.write-unfinished --edgedata-output edges.xml
                         --lanedata-output lanes.xml --statistic-output stats.xml); shift ;;
    --parts) parts=(--parts "$2" --parts.min-vehicles 0); threads=1; shift 2 ;;
    --mpi) parts=(--parts "$2"); launch=(mpirun --allow-run-as-root --oversubscribe -n "$2"); threads=1; shift 2 ;;
    --resume-parts) resume_parts=(--parts "$2" --parts.min-vehicles 0); resume_launch=(); resume_set=1
                    [[ "$2" == 1 ]] && resume_parts=(); shift 2 ;;
    --resume-mpi) resume_parts=(--parts "$2"); resume_launch=(mpirun --allow-run-as-root --oversubscribe -n "$2")
                  resume_set=1; shift 2 ;;
    --lpsim) lpsim="$(realpath "$2")"; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
[[ -n "$scenario" && -n "$at" ]] || { echo "usage: $0 --scenario CFG_OR_SNAPSHOT --at T [--end T]" >&2; exit 2; }

if [[ "$resume_set" == 0 ]]; then
  resume_parts=("${parts[@]}")
  resume_launch=("${launch[@]}")
fi
work="$PWD/bench/work/state"
rm -rf "$work" && mkdir -p "$work"
end_args=()
[[ -n "$end" ]] && end_args=(--end "$end")
# A .sumocfg's folder is copied (its add-file outputs land there); a snapshot is read where it is.
input() {
  if [[ "$scenario" == *.sumocfg ]]; then
    cp -r "$(dirname "$scenario")" "$work/$1"
    echo "-c $work/$1/$(basename "$scenario")"
  else
    mkdir -p "$work/$1"
    echo "$scenario"
  fi
}

common=(--tripinfo-output trip.xml --summary-output sum.xml "${more[@]}" --no-step-log -W --threads "$threads")
outputs=("${common[@]}" "${parts[@]}")
for run in whole saved; do
  # shellcheck disable=SC2046
  set -- $(input "lpsim_$run")
  scenario_args=("$@")  # the saved run's: the resumed run continues its outputs, add-file ones included
  args=(run "$@" "${end_args[@]}" "${outputs[@]}")
  [[ "$run" == saved ]] && args+=(--save-state.times "$at")
  (cd "$work/lpsim_$run" && echo "$run $(measure "$work/lpsim_$run.log" "${launch[@]}" "$lpsim" "${args[@]}")") >>"$work/lpsim.times"
done
state=$(ls "$work"/lpsim_saved/*.lpstate)
(cd "$work/lpsim_saved" &&
  echo "resumed $(measure "$work/lpsim_resumed.log" "${resume_launch[@]}" "$lpsim" run "${scenario_args[@]}" \
    "${end_args[@]}" "${common[@]}" "${resume_parts[@]}" --load-state "$state")") >>"$work/lpsim.times"
# Every file of the whole run's folder: its outputs (the scenario's add-file outputs too) and the inputs.
identical=yes
for f in "$work"/lpsim_whole/*; do
  cmp -s "$f" "$work/lpsim_saved/$(basename "$f")" || identical="no ($(basename "$f") differs)"
done
at_state=$(grep -o "<step time=\"$at.00\"[^>]*" "$work/lpsim_whole/sum.xml" | grep -oE 'running="[0-9]+" waiting="[0-9]+"' || true)
echo "LPSim: state $(stat -c %s "$state") bytes at $at s ($at_state); resumed (${resume_launch[*]:-one process} ${resume_parts[*]:-one part}) outputs identical: $identical"
# The target: at most 100 bytes per vehicle running or waiting, plus its route (4 bytes per edge; the
# scenario's mean route, from lpsim info, stands for theirs).
# shellcheck disable=SC2046
mean_edges=$("$lpsim" info $(input lpsim_info) 2>/dev/null | sed -n 's/^  routes: \([0-9.]*\) edges per vehicle.*/\1/p')
python3 - "$(stat -c %s "$state")" "$at_state" "${mean_edges:-0}" <<'EOF2'
import re, sys
size, counts, edges = int(sys.argv[1]), sys.argv[2], float(sys.argv[3])
n = sum(int(x) for x in re.findall(r'"([0-9]+)"', counts))
if n:
    allowance = n * (100 + 4 * edges)
    print(f"  {size / n:.0f} bytes per vehicle running or waiting ({n}); target {100 + 4 * edges:.0f} "
          f"(100 + 4 x {edges:.1f} route edges): {'met' if size <= allowance else 'not met'}")
EOF2
awk '{ printf "  %-8s %8s s wall %8s CPU-s %8s MiB\n", $1, $2, $3, $4 }' "$work/lpsim.times"

if [[ "$sumo" == 1 && "$scenario" == *.sumocfg ]]; then
  for run in whole saved resumed; do cp -r "$(dirname "$scenario")" "$work/sumo_$run"; done
  cfg="$(basename "$scenario")"
  sumo_end=()
  [[ -n "$end" ]] && sumo_end=(--end "$end")
  (cd "$work/sumo_whole" && measure "$work/sumo_whole.log" sumo -c "$cfg" "${sumo_end[@]}" \
    --tripinfo-output trip.xml --no-step-log true >/dev/null)
  (cd "$work/sumo_saved" && measure "$work/sumo_saved.log" sumo -c "$cfg" "${sumo_end[@]}" \
    --tripinfo-output trip.xml --no-step-log true --save-state.times "$at" --save-state.rng true \
    --save-state.files state.xml.gz >/dev/null)
  (cd "$work/sumo_resumed" && measure "$work/sumo_resumed.log" sumo -c "$cfg" "${sumo_end[@]}" \
    --tripinfo-output trip.xml --no-step-log true --load-state "$work/sumo_saved/state.xml.gz" \
    --begin "$at" >/dev/null)
  python3 - "$work/sumo_whole/trip.xml" "$work/sumo_resumed/trip.xml" "$work/sumo_saved/state.xml.gz" <<'EOF'
import os, re, sys
def trips(path):
    out = {}
    for line in open(path):
        m = re.search(r'<tripinfo id="([^"]+)"', line)
        if m: out[m.group(1)] = line.strip()
    return out
whole, resumed = trips(sys.argv[1]), trips(sys.argv[2])
same = sum(1 for k, v in resumed.items() if whole.get(k) == v)
print(f"SUMO: state {os.path.getsize(sys.argv[3])} bytes (gzip XML); of {len(resumed)} trips ending after the "
      f"save, {same} have the whole run's tripinfo line")
EOF
fi

#!/usr/bin/env bash
# Digests of the outputs (tripinfo, FCD, edgeData, summary) of every bundled and ../shared scenario, on the
# CPU backend with 1, 2 and 4 threads and, when given, on a second binary (the emulated CUDA backend,
# build/tests/lpsim_emulated). Two runs of this script on two commits, diffed, say whether a change kept the
# outputs byte for byte:
#
#   tools/output_digests.sh build/lpsim build/tests/lpsim_emulated > after.txt
#   diff before.txt after.txt
#
# The scenarios are copied to a scratch folder first (their add-files may name outputs of their own). A run
# refused as bad input (exit 2) gives one line "NAME LABEL refused DIGEST" (the digest of its error line).
# The summary's duration attribute (wall time) is masked. Options: --end T (default: each scenario's own);
# --model M: --default.carfollowmodel M for every run (default: LPSim's, Krauss; IDM gives the outputs of
# commits before Krauss was implemented, when every vehicle ran the IDM); --parts "2 3 4 8": also runs the
# network split into each of these numbers of parts (METIS, in one process, one thread per part), labelled
# cpu-kK (and emulated-kK on the second binary); --mpi "2 4": also as that many MPI ranks (mpirun, one part
# per rank), labelled cpu-mpiK; tools/check_digests.py says whether every run of a scenario gave the same
# bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
end_args=()
parts=()
ranks=()
while [[ "${1:-}" == --end || "${1:-}" == --model || "${1:-}" == --parts || "${1:-}" == --mpi ]]; do
  if [[ $1 == --end ]]; then end_args+=(--end "$2");
  elif [[ $1 == --parts ]]; then read -r -a parts <<< "$2";
  elif [[ $1 == --mpi ]]; then read -r -a ranks <<< "$2";
  else end_args+=(--default.carfollowmodel "$2"); fi
  shift 2
done
lpsim=$(realpath "${1:?usage: tools/output_digests.sh [--end T] [--model M] LPSIM [LPSIM_EMULATED]}")
emulated=${2:+$(realpath "$2")}
shared=../shared
work=$(mktemp -d /tmp/lpsim_digests.XXXXXX)
trap 'rm -rf "$work"' EXIT

cases=()  # name|folder|config (relative to the folder, or "csv")
for cfg in scenarios/*/*.sumocfg; do cases+=("$(basename "$(dirname "$cfg")")|$(dirname "$cfg")|$(basename "$cfg")"); done
cases+=("lpsim_csv_small|scenarios/lpsim_csv_small|csv")
if [ -d "$shared/scenarios" ]; then
  for cfg in "$shared"/scenarios/*/*.sumocfg; do
    cases+=("$(basename "$(dirname "$cfg")")|$(dirname "$cfg")|$(basename "$cfg")")
  done
fi

run_case() {  # binary label name folder config threads [parts [mpi ranks]]
  local bin=$1 label=$2 name=$3 folder=$4 config=$5 threads=$6 k=${7:-1} mpi=${8:-0}
  local dir=$work/$name/$label
  mkdir -p "$dir"
  cp -r "$folder"/. "$dir"/
  local input=(-c "$dir/$config")
  if [[ $config == csv ]]; then
    input=(--lpsim-nodes "$dir/nodes.csv" --lpsim-edges "$dir/edges.csv" --lpsim-od "$dir/od.csv")
  fi
  local part_args=() launch=()
  if (( k > 1 )); then part_args=(--parts "$k" --parts.min-vehicles 0); fi
  if (( mpi > 0 )); then launch=(mpirun --allow-run-as-root --oversubscribe -n "$mpi"); fi
  (cd "$dir" && "${launch[@]}" "$bin" run "${input[@]}" "${end_args[@]}" "${part_args[@]}" --threads "$threads" --no-warnings \
    --tripinfo-output out_tripinfo.xml --fcd-output out_fcd.xml --edgedata-output out_edgedata.xml \
    --summary-output out_summary.xml > out_stdout.txt 2> out_stderr.txt) || {
    local status=$?
    if (( status == 2 )); then  # refused as bad input: the refusal is the result to compare
      printf '%s %s refused %s\n' "$name" "$label" "$(grep -m1 'lpsim: error' "$dir/out_stderr.txt" | sed "s|$dir/||g" | md5sum | cut -d' ' -f1)"
      rm -rf "$dir"
      return 0
    fi
    if (( k > 1 )) && grep -q "parts need at least as many junctions" "$dir/out_stderr.txt"; then
      echo "$name $label: skipped, the network has fewer junctions than parts" >&2
      rm -rf "$dir"
      return 0
    fi
    echo "$name $label: lpsim failed" >&2
    cat "$dir/out_stderr.txt" >&2
    return 1
  }
  sed -i 's/ duration="[^"]*"/ duration="masked"/' "$dir/out_summary.xml"
  for f in tripinfo fcd edgedata summary; do
    printf '%s %s %s %s\n' "$name" "$label" "$f" "$(md5sum < "$dir/out_$f.xml" | cut -d' ' -f1)"
  done
  rm -rf "$dir"
}

for c in "${cases[@]}"; do
  IFS='|' read -r name folder config <<< "$c"
  for t in 1 2 4; do run_case "$lpsim" "cpu-t$t" "$name" "$folder" "$config" "$t"; done
  if [ -n "$emulated" ]; then run_case "$emulated" "emulated" "$name" "$folder" "$config" 1; fi
  for k in "${parts[@]}"; do
    run_case "$lpsim" "cpu-k$k" "$name" "$folder" "$config" 1 "$k"
    if [ -n "$emulated" ]; then run_case "$emulated" "emulated-k$k" "$name" "$folder" "$config" 1 "$k"; fi
  done
  for r in "${ranks[@]}"; do run_case "$lpsim" "cpu-mpi$r" "$name" "$folder" "$config" 1 "$r" "$r"; done
done

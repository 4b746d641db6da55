#!/usr/bin/env bash
# Strong scaling of the partitioned engine (issue 25): one scenario (default the regional 1M trips' first hour)
# run in one part on one thread, in K parts in one process (one thread each) and as K MPI ranks (one thread
# each), in alternated rounds (the machine is shared: ratios of medians, not single timings). Per variant:
# wall time of the run (lpsim's "Duration": the simulation built and stepped, loading excluded), vehicle
# updates per wall second, and per part its step time, its time in the step's exchanges (waiting for slower
# parts included) and the bytes it sent. Then the peak RSS of each rank of K = 4 MPI ranks against one part's
# (memory per rank). No outputs are written (the engine alone). Speed-ups are given for the whole run and for
# its steps alone (lpsim's "Steps" line: building the simulation and its first insertions does not shrink
# with more parts). Writes bench/work/scaling/results.md.
#
# Usage: bench/scaling_bench.sh [--scenario FILE.lpsim|FILE.sumocfg] [--end 3600] [--parts 2] [--rounds 3]
#          [--memory-parts 4] [--lpsim PATH]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
scenario=bench/work/regional/1000000/regional.lpsim
end=3600
parts=2
rounds=3
memory_parts=4
lpsim=build/lpsim
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenario) scenario="$2"; shift 2 ;;
    --end) end="$2"; shift 2 ;;
    --parts) parts="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --memory-parts) memory_parts="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    *) echo "scaling_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
lpsim=$(realpath "$lpsim")
input=("$scenario")
[[ $scenario == *.sumocfg ]] && input=(-c "$scenario")
mpirun=(mpirun --allow-run-as-root --oversubscribe)
out=bench/work/scaling
mkdir -p "$out"
common=(run "${input[@]}" --end "$end" --threads 1 --no-step-log --no-warnings)

variant() {  # name log: runs one variant
  case "$1" in
    one) "$lpsim" "${common[@]}" ;;
    inprocess) "$lpsim" "${common[@]}" --parts "$parts" --parts.min-vehicles 0 ;;
    mpi) "${mpirun[@]}" -n "$parts" "$lpsim" "${common[@]}" --parts "$parts" --parts.min-vehicles 0 ;;
  esac
}

for r in $(seq 1 "$rounds"); do
  for v in one inprocess mpi; do
    log "round $r: $v"
    variant "$v" > "$out/$v.$r.log" 2>&1 || { cat "$out/$v.$r.log" >&2; exit 1; }
  done
done

log "memory: one part, and $memory_parts MPI ranks"
measure "$out/memory_one.log" "$lpsim" "${common[@]}" > "$out/memory_one.measure"
rm -f "$out"/memory_rank.*
# Each rank's peak RSS in a file of its own (ranks' stderr lines interleave).
"${mpirun[@]}" -n "$memory_parts" sh -c "/usr/bin/time -f '%M' -o $out/memory_rank.\$OMPI_COMM_WORLD_RANK \"\$0\" \"\$@\"" \
  "$lpsim" "${common[@]}" --parts "$memory_parts" > "$out/memory_mpi.log" 2>&1

python3 - "$out" "$rounds" "$parts" "$memory_parts" "$scenario" "$end" <<'PY'
import re, statistics, sys
out, rounds, parts, memory_parts, scenario, end = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5], sys.argv[6]
def parse(path):
    text = open(path).read()
    d = {"wall": float(re.search(r"Duration: ([0-9.]+)s", text).group(1)),
         "ups": float(re.search(r"UPS: ([0-9.]+)", text).group(1)),
         "steps": float(re.search(r"Steps: ([0-9.]+)s", text).group(1)),
         "step_ups": float(re.search(r"UPS of the steps ([0-9.]+)", text).group(1)), "parts": []}
    for m in re.finditer(r"Part (\d+): vehicle updates (\d+), migrations out (\d+), exchanged ([0-9.]+) MB in (\d+) rounds, step ([0-9.]+)s of which exchanges ([0-9.]+)s", text):
        d["parts"].append(dict(updates=int(m[2]), migrations=int(m[3]), mb=float(m[4]), rounds=int(m[5]), step=float(m[6]), exchange=float(m[7])))
    return d
runs = {v: [parse(f"{out}/{v}.{r}.log") for r in range(1, rounds + 1)] for v in ("one", "inprocess", "mpi")}
med = lambda xs: statistics.median(xs)
one_ups = med([d["ups"] for d in runs["one"]]); one_step_ups = med([d["step_ups"] for d in runs["one"]])
lines = [f"Scenario `{scenario}`, `--end {end}`, one thread per part, {rounds} alternated rounds, medians.", "",
         "| variant | wall s | updates/s | speed-up | steps' wall s | updates/s of the steps | speed-up of the steps | per part: step s, exchanges s (share of step), MB sent, migrations out |",
         "|---|---|---|---|---|---|---|---|"]
for v, name in (("one", "1 part"), ("inprocess", f"{parts} parts in one process"), ("mpi", f"{parts} MPI ranks")):
    ds = runs[v]
    wall = med([d["wall"] for d in ds]); ups = med([d["ups"] for d in ds])
    steps = med([d["steps"] for d in ds]); step_ups = med([d["step_ups"] for d in ds])
    per = []
    if ds[0]["parts"]:
        for p in range(len(ds[0]["parts"])):
            step = med([d["parts"][p]["step"] for d in ds]); ex = med([d["parts"][p]["exchange"] for d in ds])
            per.append(f"part {p}: {step:.2f}, {ex:.2f} ({100 * ex / step:.1f} %), {ds[0]['parts'][p]['mb']:.2f} MB, {ds[0]['parts'][p]['migrations']}")
    lines.append(f"| {name} | {wall:.2f} | {ups:.3g} | {ups / one_ups:.2f} | {steps:.2f} | {step_ups:.3g} | "
                 f"{step_ups / one_step_ups:.2f} | {'; '.join(per) or '—'} |")
rss_one = float(open(f"{out}/memory_one.measure").read().split()[2])
rss_ranks = [int(open(f"{out}/memory_rank.{r}").read().split()[-1]) / 1024 for r in range(memory_parts)]
lines += ["", f"Peak RSS: one part {rss_one:.0f} MiB; {memory_parts} MPI ranks " + ", ".join(f"{x:.0f}" for x in rss_ranks) +
          f" MiB (largest {max(rss_ranks) / rss_one:.2f}× one part's)."]
open(f"{out}/results.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

#!/usr/bin/env bash
# Two parts on a real or congested network, balanced on the routes in free flow and on a run's measured load
# (`--partition.load-from`). The scenario (--scenario):
#   grid     resco_grid4x4 (../shared: a RESCO benchmark grid, 3 lanes, 300 m blocks, 50 km/h, right-on-red
#            signals) scaled up with netgenerate to 28 x 7 junctions, with randomTrips' demand heavy enough to
#            congest it (one every --period s for an hour, fringe factor 10, routed by duarouter; all seeded);
#   bayarea  the Bay Area tertiary network itself (../shared/lpsim_bayarea_tertiary, one copy, not tiled) with
#            1M OD trips over 12 h (tools/make_regional_scenario.py --tiles 1, seeded), its first hour.
# One run in one part writes the edgeData the measured variant is balanced on; then in alternated
# rounds (the machine is shared: ratios of medians): one part, and two parts on the free-flow weights and on
# the measured load, each in one process and as two MPI ranks, one thread per part, no outputs. Reported per variant: the steps' wall time
# (lpsim's "Steps" line), its speed-up over one part, and per part its vehicle updates and its share of the
# step spent in exchanges (waiting for the other part included). Writes bench/work/rebalance/<scenario>/results.md.
#
# Usage: bench/rebalance_bench.sh [--scenario grid|bayarea] [--rounds 3] [--period 0.08] [--lpsim PATH]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
scenario=grid
rounds=3
period=0.08
lpsim=build/lpsim
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenario) scenario="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --period) period="$2"; shift 2 ;;
    --lpsim) lpsim="$2"; shift 2 ;;
    *) echo "rebalance_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
lpsim=$(realpath "$lpsim")
out=bench/work/rebalance/$scenario
mkdir -p "$out"
if [[ $scenario == bayarea ]]; then
  snapshot=$out/bayarea_1m.lpsim
  if [[ ! -f $snapshot ]]; then
    log "Bay Area, one copy, 1M OD trips, routed into a snapshot"
    python3 tools/make_regional_scenario.py --bayarea ../shared/lpsim_bayarea_tertiary --out "$out/csv" \
      --trips 1000000 --tiles 1 --seed 42 >/dev/null 2>&1
    "$lpsim" convert --lpsim-nodes "$out/csv/nodes.csv" --lpsim-edges "$out/csv/edges.csv" \
      --lpsim-od "$out/csv/od.csv" --threads 2 -o "$snapshot" >/dev/null 2>&1
  fi
  common=(run "$snapshot" --end 3600 --threads 1 --no-step-log --no-warnings)
  title="The Bay Area tertiary network, one copy, 1M OD trips over 12 h, the first hour"
elif [[ $scenario != grid ]]; then
  echo "rebalance_bench: --scenario grid or bayarea" >&2
  exit 2
fi
net=$out/grid.net.xml
routes=$out/grid_$period.rou.xml
if [[ $scenario == grid && ! -f $net ]]; then
  log "netgenerate 28x7 grid as resco_grid4x4's"
  netgenerate --grid --grid.x-number 28 --grid.y-number 7 --grid.length 300 --grid.attach-length 300 \
    --default.lanenumber 3 --default.speed 13.89 --tls.guess true -j traffic_light_right_on_red \
    --no-turnarounds true -o "$net" >/dev/null 2>&1
fi
if [[ $scenario == grid && ! -f $routes ]]; then
  log "randomTrips every $period s and duarouter"
  python3 "$SUMO_HOME/tools/randomTrips.py" -n "$net" -o "$out/trips.xml" -b 0 -e 3600 -p "$period" \
    --fringe-factor 10 --seed 42 >/dev/null
  # randomTrips' header comment holds "--" (its options), which duarouter's parser refuses.
  python3 - "$out/trips.xml" <<'PY'
import sys
p = sys.argv[1]; s = open(p).read(); a = s.find("<!--")
if a >= 0: s = s[:a] + s[s.index("-->", a) + 3:]
open(p, "w").write(s)
PY
  duarouter -n "$net" --route-files "$out/trips.xml" -o "$routes" --seed 42 --ignore-errors --no-warnings \
    --xml-validation never --xml-validation.net never >/dev/null
fi
if [[ $scenario == grid ]]; then
  common=(run -n "$net" -r "$routes" --begin 0 --end 3600 --threads 1 --no-step-log --no-warnings)
  title="28 x 7 signalised grid (resco_grid4x4 scaled up), a vehicle every $period s for an hour"
fi
log "one part, with edgeData: the measured load"
"$lpsim" "${common[@]}" --edgedata-output "$out/measured.xml" --summary-output "$out/summary.xml" \
  > "$out/measure.log" 2>&1

mpirun=(mpirun --allow-run-as-root --oversubscribe -n 2)
measured=(--partition.load-from "$out/measured.xml")
variant() {
  case "$1" in
    one) "$lpsim" "${common[@]}" ;;
    free) "$lpsim" "${common[@]}" --parts 2 --parts.min-vehicles 0 ;;
    measured) "$lpsim" "${common[@]}" --parts 2 --parts.min-vehicles 0 "${measured[@]}" ;;
    mpi_free) "${mpirun[@]}" "$lpsim" "${common[@]}" --parts 2 ;;
    mpi_measured) "${mpirun[@]}" "$lpsim" "${common[@]}" --parts 2 "${measured[@]}" ;;
  esac
}
variants=(one free measured mpi_free mpi_measured)
for r in $(seq 1 "$rounds"); do
  for v in "${variants[@]}"; do
    log "round $r: $v"
    variant "$v" > "$out/$v.$r.log" 2>&1 || { cat "$out/$v.$r.log" >&2; exit 1; }
  done
done

python3 - "$out" "$rounds" "$title" <<'PY'
import re, statistics, sys
out, rounds, title = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def parse(path):
    text = open(path).read()
    d = {"steps": float(re.search(r"Steps: ([0-9.]+)s", text).group(1)),
         "updates": int(re.search(r"Vehicle updates: (\d+)", text).group(1)), "parts": []}
    for m in re.finditer(r"Part (\d+): vehicle updates (\d+), .*? step ([0-9.]+)s of which exchanges ([0-9.]+)s", text):
        d["parts"].append(dict(updates=int(m[2]), step=float(m[3]), exchange=float(m[4])))
    return d
running = [int(x) for x in re.findall(r'running="(\d+)"', open(f"{out}/summary.xml").read())]
names = {"one": "1 part", "free": "2 parts in one process, free-flow weights",
         "measured": "2 parts in one process, measured load (`--partition.load-from`)",
         "mpi_free": "2 MPI ranks, free-flow weights", "mpi_measured": "2 MPI ranks, measured load"}
runs = {v: [parse(f"{out}/{v}.{r}.log") for r in range(1, rounds + 1)] for v in names}
med = statistics.median
one = med([d["steps"] for d in runs["one"]])
lines = [f"{title}: "
         f"{runs['one'][0]['updates']:,} vehicle updates, {statistics.mean(running):,.0f} vehicles running on "
         f"average (at most {max(running):,}); one thread per part, {rounds} alternated rounds, medians.", "",
         "| variant | steps' wall s | speed-up over one part | per part: vehicle updates, exchanges' share of its step |",
         "|---|---|---|---|"]
for v, name in names.items():
    ds = runs[v]
    steps = med([d["steps"] for d in ds])
    per = []
    for p in range(len(ds[0]["parts"])):
        share = med([d["parts"][p]["exchange"] / d["parts"][p]["step"] for d in ds])
        per.append(f"part {p}: {ds[0]['parts'][p]['updates']:,}, {100 * share:.1f} %")
    lines.append(f"| {name} | {steps:.2f} | {one / steps:.2f} | {'; '.join(per) or '—'} |")
open(f"{out}/results.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

#!/usr/bin/env bash
# Routing benchmark inputs: a signalised grid (default 40x40 junctions, 2 lanes, 200 m) and ~100k
# random trips (randomTrips.py, seed 42, one trip every 0.036 s over 3600 s) in bench/work/routing/.
# Skips work whose outputs exist (same options) unless --force.
#
# Usage: bench/make_routing_scenario.sh [--force] [--out DIR] [--grid N] [--period S] [--end S]
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/bench/lib.sh"

force=0
out="$repo/bench/work/routing"
grid=40
period=0.036
end=3600
seed=42
# randomTrips measures a trip from its first edge's start node to its last edge's end node; a trip on
# a single 200 m edge measures 200 m and its reverse edge 0 m, so 250 m keeps from != to (checked below).
min_distance=250
while [[ $# -gt 0 ]]; do
  case "$1" in
    --force) force=1; shift ;;
    --out) out="$2"; shift 2 ;;
    --grid) grid="$2"; shift 2 ;;
    --period) period="$2"; shift 2 ;;
    --end) end="$2"; shift 2 ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "unknown option: $1" >&2; exit 2 ;;
  esac
done

mkdir -p "$out"
net="$out/net.xml"
trips="$out/trips.xml"
stamp="$out/options.txt"
options="grid=$grid length=200 lanes=2 tls seed=$seed period=$period end=$end min_distance=$min_distance"

if [[ $force -eq 0 && -s "$net" && -s "$trips" && -f "$stamp" && "$(cat "$stamp")" == "$options" ]]; then
  log "inputs exist in $out (use --force to regenerate)"
  exit 0
fi
rm -f "$stamp"

started=$SECONDS
log "netgenerate ${grid}x${grid} grid -> $net"
netgenerate --grid --grid.number "$grid" --grid.length 200 --default.lanenumber 2 \
  --default-junction-type traffic_light --no-internal-links false --seed "$seed" \
  --output-file "$net" >/dev/null

log "randomTrips.py (seed $seed, period $period s, end $end s) -> $trips"
/usr/bin/python3 "$SUMO_HOME/tools/randomTrips.py" -n "$net" -o "$trips.tmp" --seed "$seed" \
  -b 0 -e "$end" -p "$period" --min-distance "$min_distance" >/dev/null
mv "$trips.tmp" "$trips"

# Every trip must go somewhere: from != to.
read -r count same < <(awk '
  /<trip / { n++; f = $0; t = $0
             sub(/.* from="/, "", f); sub(/".*/, "", f)
             sub(/.* to="/, "", t); sub(/".*/, "", t)
             if (f == t) s++ }
  END { print n + 0, s + 0 }' "$trips")
if [[ "$same" -ne 0 ]]; then
  echo "$trips: $same of $count trips have from == to" >&2
  exit 1
fi
echo "$options" >"$stamp"
log "$count trips, none with from == to; generated in $((SECONDS - started)) s"

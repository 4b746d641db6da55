#!/usr/bin/env bash
# A district of the real Bay Area network (../shared/lpsim_bayarea_tertiary, the original LPSim CSV) as a SUMO
# scenario with one hour of random demand, for validating LPSim against SUMO on the same real .net.xml:
#
#   tools/make_bayarea_district.sh [OUT_DIR]      (default /work/bayarea_district; files are large, keep them
#                                                  outside the repository)
#
# 1. tools/lpsim_csv_to_sumo.py converts the whole CSV network to OUT/bayarea.net.xml (66k edges; its
#    .nod.xml/.edg.xml and netconvert's log beside it).
# 2. netconvert cuts the district: the edges inside BBOX (lon/lat, default downtown San Francisco, SoMa and
#    the Mission, about 2,200 edges and 600 signals), keeping the largest connected part -> OUT/district.net.xml.
# 3. randomTrips.py draws trips (one every PERIOD s for an hour, at least MIN_DISTANCE m straight-line apart,
#    seeded), duarouter routes them -> OUT/district.rou.xml; OUT/district.sumocfg names both.
# 4. SUMO runs it once (OUT/sumo_tripinfo.xml, OUT/sumo_stats.xml) and the summary says whether it flows.
#
# Then:  lpsim run -c OUT/district.sumocfg --tripinfo-output OUT/lpsim_tripinfo.xml
# Settings (environment): BBOX, PERIOD, SEED, MIN_DISTANCE, END (the configuration's end, s), CSV_DIR, and
# BAYAREA_NET (a bayarea.net.xml converted before: step 1 is skipped and the district cut from it).
set -euo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-/work/bayarea_district}"
csv_dir="$(realpath "${CSV_DIR:-$repo/../shared/lpsim_bayarea_tertiary}")"
bbox="${BBOX:--122.45,37.75,-122.38,37.81}"
period="${PERIOD:-1}"
seed="${SEED:-42}"
min_distance="${MIN_DISTANCE:-500}"
end="${END:-10800}"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"

mkdir -p "$out"

whole_net="${BAYAREA_NET:-}"
if [[ -n "$whole_net" ]]; then
  whole_net="$(realpath "$whole_net")"
fi
cd "$out"

if [[ -z "$whole_net" ]]; then
  echo "== 1. the whole network"
  python3 "$repo/tools/lpsim_csv_to_sumo.py" --nodes "$csv_dir/nodes.csv" --edges "$csv_dir/edges.csv" \
    -o bayarea.net.xml
  whole_net=bayarea.net.xml
fi

echo "== 2. the district $bbox"
# The same turnaround and signal-timing options as the conversion, for the junctions the cut changes.
netconvert -s "$whole_net" --keep-edges.in-geo-boundary "$bbox" --keep-edges.components 1 \
  --no-turnarounds.except-deadend --tls.green.time 30 --tls.yellow.time 3 \
  -o district.net.xml > district.netconvert.log 2>&1 || { cat district.netconvert.log; exit 1; }
echo "district.net.xml: $(grep -c '<edge id="[^:]' district.net.xml) edges, $(grep -c '<tlLogic' district.net.xml) signals"

echo "== 3. one hour of trips"
python3 "$SUMO_HOME/tools/randomTrips.py" -n district.net.xml -o district.trips.xml -b 0 -e 3600 -p "$period" \
  --seed "$seed" --min-distance "$min_distance" --validate > randomtrips.log 2>&1 || { cat randomtrips.log; exit 1; }
duarouter -n district.net.xml -r district.trips.xml -o district.rou.xml --seed "$seed" --no-step-log \
  > duarouter.log 2>&1 || { cat duarouter.log; exit 1; }
echo "district.rou.xml: $(grep -c '<vehicle ' district.rou.xml) vehicles"

cat > district.sumocfg <<EOF
<configuration>
    <input>
        <net-file value="district.net.xml"/>
        <route-files value="district.rou.xml"/>
    </input>
    <time>
        <begin value="0"/>
        <end value="$end"/>
    </time>
</configuration>
EOF

echo "== 4. SUMO's run"
sumo -c district.sumocfg --no-step-log --duration-log.statistics --tripinfo-output sumo_tripinfo.xml \
  --statistic-output sumo_stats.xml > sumo.log 2>&1 || { cat sumo.log; exit 1; }
grep -E "Inserted|Running|Waiting|Teleports|Duration|Statistics|Performance" sumo.log || true

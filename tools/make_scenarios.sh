#!/usr/bin/env bash
# Regenerates the bundled test scenarios under scenarios/ with SUMO's own tools, then their
# sumo_reference.txt files. Deterministic: every random tool gets a fixed seed and SUMO's
# "generated on <date>" header comments are stripped, so a rerun reproduces the committed files.
# Needs SUMO 1.15 (netgenerate, netconvert, duarouter, sumo) and /usr/bin/python3 (sees sumolib).
set -euo pipefail

export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
PY=/usr/bin/python3
TOOLS=$SUMO_HOME/tools
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=$ROOT/scenarios
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# Drops SUMO's provenance comment (date, absolute paths) from the files given.
strip_generated_header() {
  "$PY" - "$@" <<'EOF'
import re, sys
for path in sys.argv[1:]:
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"<!-- generated on .*?-->\n+", "", text, flags=re.S)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
EOF
}

write_sumocfg() {  # dir name route-or-empty
  local dir=$1 name=$2 routes=$3
  cat > "$dir/$name.sumocfg" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<configuration xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/sumoConfiguration.xsd">
    <input>
        <net-file value="$name.net.xml"/>
        <route-files value="$routes"/>
    </input>
    <time>
        <begin value="0"/>
        <end value="3600"/>
    </time>
</configuration>
EOF
}

# --- grid_tls: 5x5 grid, 200 m blocks, 2 lanes, every junction signalised; 1000 routed vehicles -------------
make_grid_tls() {
  local d=$OUT/grid_tls
  rm -rf "$d" && mkdir -p "$d"
  netgenerate --grid --grid.number 5 --grid.length 200 --default.lanenumber 2 \
    --default-junction-type traffic_light --seed 1 -o "$d/grid_tls.net.xml"
  (cd "$TMP" && "$PY" "$TOOLS/randomTrips.py" -n "$d/grid_tls.net.xml" -b 0 -e 1000 -p 1 --seed 1 \
    -o "$TMP/grid_tls.trips.xml")
  duarouter -n "$d/grid_tls.net.xml" --route-files "$TMP/grid_tls.trips.xml" --seed 1 --no-step-log \
    -o "$d/grid_tls.rou.xml"
  rm -f "$d/grid_tls.rou.alt.xml"
  strip_generated_header "$d/grid_tls.net.xml" "$d/grid_tls.rou.xml"
  write_sumocfg "$d" grid_tls grid_tls.rou.xml
}

# --- random_net: random topology, right_before_left / priority / traffic_light junctions; 300 unrouted trips ----
make_random_net() {
  local d=$OUT/random_net
  rm -rf "$d" && mkdir -p "$d"
  # netgenerate gives every junction one type: build right_before_left with a few guessed signals, then turn
  # every second remaining junction with 3+ approaches into a priority junction.
  netgenerate --rand --rand.iterations 30 --seed 7 --random-lanenumber --default.lanenumber 2 \
    --default.speed 13.89 --default-junction-type right_before_left --tls.guess --tls.guess.threshold 100 \
    -o "$TMP/random_rbl.net.xml"
  "$PY" - "$TMP/random_rbl.net.xml" "$TMP/priority.nod.xml" <<'EOF'
import sys
sys.path.append("/usr/share/sumo/tools")
import sumolib
net = sumolib.net.readNet(sys.argv[1])
ids = sorted(n.getID() for n in net.getNodes()
             if n.getType() == "right_before_left" and len(n.getIncoming()) >= 3)
with open(sys.argv[2], "w") as f:
    f.write("<nodes>\n")
    for node_id in ids[::2]:
        f.write('    <node id="%s" type="priority"/>\n' % node_id)
    f.write("</nodes>\n")
EOF
  netconvert -s "$TMP/random_rbl.net.xml" -n "$TMP/priority.nod.xml" -o "$d/random_net.net.xml"
  # randomTrips --validate leaves a routes.rou.xml in the working directory: run it in $TMP.
  (cd "$TMP" && "$PY" "$TOOLS/randomTrips.py" -n "$d/random_net.net.xml" -b 0 -e 600 -p 2 --seed 7 --validate \
    -o "$d/random_net.trips.xml")
  strip_generated_header "$d/random_net.net.xml" "$d/random_net.trips.xml"
  write_sumocfg "$d" random_net random_net.trips.xml
}

# --- flows: 3x3 grid, 2 lanes, priority junctions; every kind of <flow>, a vTypeDistribution, a routeDistribution --
make_flows() {
  local d=$OUT/flows
  rm -rf "$d" && mkdir -p "$d"
  netgenerate --grid --grid.number 3 --grid.length 150 --default.lanenumber 2 --seed 3 \
    -o "$d/flows.net.xml"
  strip_generated_header "$d/flows.net.xml"
  cat > "$d/flows.rou.xml" <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<routes xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/routes_file.xsd">
    <vTypeDistribution id="mix">
        <vType id="car" accel="2.6" decel="4.5" sigma="0.5" length="5" minGap="2.5" maxSpeed="50" probability="0.8"/>
        <vType id="van" accel="1.8" decel="4.0" sigma="0.5" length="7.5" minGap="2.5" maxSpeed="30" probability="0.2"/>
    </vTypeDistribution>
    <vType id="slow" maxSpeed="10" speedFactor="1.0" speedDev="0"/>
    <route id="west_east" edges="A1B1 B1C1"/>
    <route id="south_north" edges="B0B1 B1B2"/>
    <routeDistribution id="mixed_routes">
        <route id="mixed_a" edges="A0B0 B0C0 C0C1" probability="3"/>
        <route id="mixed_b" edges="C2B2 B2A2 A2A1" probability="1"/>
    </routeDistribution>
    <!-- period, fixed route: 60 vehicles (0, 10, ..., 590) -->
    <flow id="by_period" type="mix" route="west_east" begin="0" end="600" period="10"/>
    <!-- vehsPerHour, from/to (routed on insertion): 60 vehicles -->
    <flow id="by_rate" type="car" from="A2B2" to="C1C0" begin="0" end="600" vehsPerHour="360" departLane="best" departSpeed="max"/>
    <!-- probability per second, route distribution: random count (about 60) -->
    <flow id="by_probability" type="mix" route="mixed_routes" begin="0" end="600" probability="0.1" departLane="random"/>
    <!-- number, fixed route: 40 vehicles spread evenly over [0, 400) -->
    <flow id="by_number" type="slow" route="south_north" begin="0" end="400" number="40"/>
    <!-- number, from/to with via: 20 vehicles -->
    <flow id="by_number_trip" from="C0C1" to="A1A0" via="B1A1" begin="100" end="500" number="20" departPos="random"/>
</routes>
EOF
  write_sumocfg "$d" flows flows.rou.xml
}

# --- lpsim_csv_small: the original LPSim CSV format, a signalised cross plus one extra road (WGS84 near Berkeley) --
make_lpsim_csv_small() {
  local d=$OUT/lpsim_csv_small
  rm -rf "$d" && mkdir -p "$d"
  cat > "$d/nodes.csv" <<'EOF'
osmid,x,y,ref,highway
1001,-122.26,37.87,,traffic_signals
1002,-122.262,37.87,,
1003,-122.258,37.87,,
1004,-122.26,37.8716,,stop
1005,-122.26,37.8684,,
1006,-122.256,37.87,,
EOF
  cat > "$d/edges.csv" <<'EOF'
uniqueid,u,v,length,lanes,speed_mph
0,1002,1001,176.0,2,35
1,1001,1002,176.0,2,35
2,1001,1003,176.0,2,35
3,1003,1001,176.0,2,35
4,1003,1006,176.5,1,25
5,1006,1003,176.5,1,25
6,1004,1001,178.5,1,25
7,1001,1004,178.5,1,
8,1005,1001,178.5,0,25
9,1001,1005,178.5,1,0
EOF
  # The same edges in the header of the original's full network (u/v dense node indices, osmids beside them).
  cat > "$d/edges_full_header.csv" <<'EOF'
uniqueid,osmid_u,osmid_v,length,lanes,speed_mph,u,v
0,1002,1001,176.0,2,35,1,0
1,1001,1002,176.0,2,35,0,1
2,1001,1003,176.0,2,35,0,2
3,1003,1001,176.0,2,35,2,0
4,1003,1006,176.5,1,25,2,5
5,1006,1003,176.5,1,25,5,2
6,1004,1001,178.5,1,25,3,0
7,1001,1004,178.5,1,,0,3
8,1005,1001,178.5,0,25,4,0
9,1001,1005,178.5,1,0,0,4
EOF
  cat > "$d/od.csv" <<'EOF'
,SAMPN,PERNO,origin_osmid,destination_osmid,dep_time,origin,destination
0,1,1,1002,1006,0.0,1,5
1,2,1,1006,1002,5.0,5,1
2,3,1,1004,1005,10.5,3,4
3,4,1,1005,1002,12.0,4,1
4,5,1,1002,1004,20.0,1,3
5,6,1,1006,1005,31.2,5,4
6,7,1,1004,1006,45.0,3,5
7,8,1,1005,1004,60.0,4,3
EOF
}

# --- actuated_cross: one actuated traffic light (netconvert's default actuated program), a busy and a quiet
# approach pair, so that the gap control decides how long each green lasts --
make_actuated_cross() {
  local d=$OUT/actuated_cross
  rm -rf "$d" && mkdir -p "$d"
  cat > "$TMP/cross.nod.xml" <<'EOF'
<nodes>
    <node id="C" x="0" y="0" type="traffic_light"/>
    <node id="N" x="0" y="300"/>
    <node id="S" x="0" y="-300"/>
    <node id="E" x="300" y="0"/>
    <node id="W" x="-300" y="0"/>
</nodes>
EOF
  cat > "$TMP/cross.edg.xml" <<'EOF'
<edges>
    <edge id="NC" from="N" to="C" numLanes="1" speed="13.89"/>
    <edge id="CS" from="C" to="S" numLanes="1" speed="13.89"/>
    <edge id="SC" from="S" to="C" numLanes="1" speed="13.89"/>
    <edge id="CN" from="C" to="N" numLanes="1" speed="13.89"/>
    <edge id="EC" from="E" to="C" numLanes="1" speed="13.89"/>
    <edge id="CW" from="C" to="W" numLanes="1" speed="13.89"/>
    <edge id="WC" from="W" to="C" numLanes="1" speed="13.89"/>
    <edge id="CE" from="C" to="E" numLanes="1" speed="13.89"/>
</edges>
EOF
  netconvert -n "$TMP/cross.nod.xml" -e "$TMP/cross.edg.xml" --tls.default-type actuated --no-turnarounds \
    -o "$d/actuated_cross.net.xml" > /dev/null
  cat > "$d/actuated_cross.rou.xml" <<'EOF'
<routes>
    <flow id="ns" from="NC" to="CS" begin="0" end="1800" vehsPerHour="700"/>
    <flow id="sn" from="SC" to="CN" begin="0" end="1800" vehsPerHour="500"/>
    <flow id="ew" from="EC" to="CW" begin="0" end="1800" vehsPerHour="120"/>
</routes>
EOF
  strip_generated_header "$d/actuated_cross.net.xml"
  write_sumocfg "$d" actuated_cross actuated_cross.rou.xml
}

# --- keep_clear: a priority junction with a 6 m edge behind it on the main road, whose queue (from a
# traffic light further on) spills back over the junction; a minor side road crosses there. SUMO's drivers
# do not enter the junction while the room behind it cannot hold them, so the side road keeps flowing --
make_keep_clear() {
  local d=$OUT/keep_clear
  rm -rf "$d" && mkdir -p "$d"
  cat > "$TMP/keep.nod.xml" <<'EOF'
<nodes>
    <node id="W" x="-300" y="0"/>
    <node id="J1" x="0" y="0" type="priority"/>
    <node id="J2" x="10" y="0" type="priority"/>
    <node id="J3" x="200" y="0" type="traffic_light"/>
    <node id="E" x="500" y="0"/>
    <node id="N1" x="0" y="300"/>
    <node id="S1" x="0" y="-300"/>
    <node id="N3" x="200" y="300"/>
    <node id="S3" x="200" y="-300"/>
</nodes>
EOF
  cat > "$TMP/keep.edg.xml" <<'EOF'
<edges>
    <edge id="WJ1" from="W" to="J1" numLanes="1" speed="13.89" priority="3"/>
    <edge id="J1J2" from="J1" to="J2" numLanes="1" speed="13.89" priority="3"/>
    <edge id="J2J3" from="J2" to="J3" numLanes="1" speed="13.89" priority="3"/>
    <edge id="J3E" from="J3" to="E" numLanes="1" speed="13.89" priority="3"/>
    <edge id="N1J1" from="N1" to="J1" numLanes="1" speed="13.89" priority="1"/>
    <edge id="J1S1" from="J1" to="S1" numLanes="1" speed="13.89" priority="1"/>
    <edge id="N3J3" from="N3" to="J3" numLanes="1" speed="13.89" priority="1"/>
    <edge id="J3S3" from="J3" to="S3" numLanes="1" speed="13.89" priority="1"/>
</edges>
EOF
  netconvert -n "$TMP/keep.nod.xml" -e "$TMP/keep.edg.xml" --no-turnarounds -o "$d/keep_clear.net.xml" > /dev/null
  cat > "$d/keep_clear.rou.xml" <<'EOF'
<routes>
    <flow id="main" from="WJ1" to="J3E" begin="0" end="1800" vehsPerHour="1000"/>
    <flow id="side" from="N1J1" to="J1S1" begin="0" end="1800" vehsPerHour="300"/>
    <flow id="cross" from="N3J3" to="J3S3" begin="0" end="1800" vehsPerHour="200"/>
</routes>
EOF
  strip_generated_header "$d/keep_clear.net.xml"
  write_sumocfg "$d" keep_clear keep_clear.rou.xml
}

# --- cosim_line: one lane A-B-C-D-E, a long red at D; demand above its capacity, so the queue grows from D
# back over C and B (the co-simulation tests put the corridor before it or on it) -------------------------
make_cosim_line() {
  local d=$OUT/cosim_line
  rm -rf "$d" && mkdir -p "$d"
  cat > "$TMP/line.nod.xml" <<'EOF'
<nodes>
    <node id="A" x="0" y="0" type="priority"/>
    <node id="B" x="400" y="0" type="priority"/>
    <node id="C" x="800" y="0" type="priority"/>
    <node id="D" x="1200" y="0" type="traffic_light"/>
    <node id="E" x="1600" y="0" type="priority"/>
</nodes>
EOF
  cat > "$TMP/line.edg.xml" <<'EOF'
<edges>
    <edge id="AB" from="A" to="B" numLanes="1" speed="13.89"/>
    <edge id="BC" from="B" to="C" numLanes="1" speed="13.89"/>
    <edge id="CD" from="C" to="D" numLanes="1" speed="13.89"/>
    <edge id="DE" from="D" to="E" numLanes="1" speed="13.89"/>
</edges>
EOF
  cat > "$TMP/line.tll.xml" <<'EOF'
<tlLogics>
    <tlLogic id="D" type="static" programID="0" offset="0">
        <phase duration="10" state="G"/>
        <phase duration="3" state="y"/>
        <phase duration="47" state="r"/>
    </tlLogic>
</tlLogics>
EOF
  netconvert -n "$TMP/line.nod.xml" -e "$TMP/line.edg.xml" -i "$TMP/line.tll.xml" --no-turnarounds \
    -o "$d/cosim_line.net.xml" > /dev/null
  cat > "$d/cosim_line.rou.xml" <<'EOF'
<routes>
    <flow id="f" from="AB" to="DE" begin="0" end="600" vehsPerHour="900" departLane="best" departSpeed="max"/>
</routes>
EOF
  strip_generated_header "$d/cosim_line.net.xml"
  write_sumocfg "$d" cosim_line cosim_line.rou.xml
}

# --- emissions_*: one lane A-B-C-D (3 x 300 m, 13.89 m/s) and vehicles with sigma 0 and speedDev 0, whose
# trips LPSim drives as SUMO does; emissions.add.xml asks for emissions edgeData (period 60) and laneData
# (the whole run, internal lanes too). It is not in the .sumocfg: its outputs land beside it, so the tests run
# a copy. make_emissions_line DIR NAME [red]: the network DIR/NAME.net.xml (priority nodes, or with "red" a
# signal at C: red 70 s, green 40 s, yellow 3 s from time 0) and the add-file.
make_emissions_line() {
  local d=$1 name=$2 signal=${3:-}
  local c_type=priority tll=()
  if [ "$signal" = red ]; then
    c_type=traffic_light
    tll=(-i "$TMP/line.tll.xml")
  fi
  cat > "$TMP/line.nod.xml" <<EOF
<nodes>
    <node id="A" x="0" y="0" type="priority"/>
    <node id="B" x="300" y="0" type="priority"/>
    <node id="C" x="600" y="0" type="$c_type"/>
    <node id="D" x="900" y="0" type="priority"/>
</nodes>
EOF
  cat > "$TMP/line.edg.xml" <<'EOF'
<edges>
    <edge id="AB" from="A" to="B" numLanes="1" speed="13.89"/>
    <edge id="BC" from="B" to="C" numLanes="1" speed="13.89"/>
    <edge id="CD" from="C" to="D" numLanes="1" speed="13.89"/>
</edges>
EOF
  cat > "$TMP/line.tll.xml" <<'EOF'
<tlLogics>
    <tlLogic id="C" type="static" programID="0" offset="0">
        <phase duration="70" state="r"/>
        <phase duration="40" state="G"/>
        <phase duration="3" state="y"/>
    </tlLogic>
</tlLogics>
EOF
  netconvert -n "$TMP/line.nod.xml" -e "$TMP/line.edg.xml" "${tll[@]}" --no-turnarounds \
    -o "$d/$name.net.xml" > /dev/null
  strip_generated_header "$d/$name.net.xml"
  cat > "$d/emissions.add.xml" <<'EOF'
<additional>
    <edgeData id="edges_60" type="emissions" file="edges_60.xml" period="60"/>
    <laneData id="lanes" type="emissions" file="lanes.xml" withInternal="true"/>
</additional>
EOF
}

# --- emissions_free: three cars accelerating from standstill (one departing at full speed) and cruising ----
make_emissions_free() {
  local d=$OUT/emissions_free
  rm -rf "$d" && mkdir -p "$d"
  make_emissions_line "$d" emissions_free
  cat > "$d/emissions_free.rou.xml" <<'EOF'
<routes>
    <vType id="car" sigma="0" speedDev="0"/>
    <route id="r" edges="AB BC CD"/>
    <vehicle id="car0" type="car" route="r" depart="0"/>
    <vehicle id="car1" type="car" route="r" depart="30" departSpeed="max"/>
    <vehicle id="car2" type="car" route="r" depart="60"/>
</routes>
EOF
  write_sumocfg "$d" emissions_free emissions_free.rou.xml
}

# --- emissions_redlight: a car, an HBEFA2 car, a bus and a car stop at C's red light, queue and restart ---
make_emissions_redlight() {
  local d=$OUT/emissions_redlight
  rm -rf "$d" && mkdir -p "$d"
  make_emissions_line "$d" emissions_redlight red
  cat > "$d/emissions_redlight.rou.xml" <<'EOF'
<routes>
    <vType id="car" sigma="0" speedDev="0"/>
    <vType id="car_hbefa2" sigma="0" speedDev="0" emissionClass="HBEFA2/P_7_7"/>
    <vType id="bus" vClass="bus" sigma="0" speedDev="0"/>
    <route id="r" edges="AB BC CD"/>
    <vehicle id="car0" type="car" route="r" depart="0"/>
    <vehicle id="car1" type="car_hbefa2" route="r" depart="4"/>
    <vehicle id="bus0" type="bus" route="r" depart="8"/>
    <vehicle id="car2" type="car" route="r" depart="12"/>
</routes>
EOF
  write_sumocfg "$d" emissions_redlight emissions_redlight.rou.xml
}

# --- emissions_classes: one vehicle of each of eight emission classes, 15 s apart: HBEFA3 petrol car (the
# default), diesel car (PC_D_EU6), truck (HDV), bus, motorcycle (LDV_G_EU6) and delivery van (LDV); HBEFA2
# car (the bare name P_7_7) and truck without acceleration terms (HDV_A0_12_3) -----------------------------
make_emissions_classes() {
  local d=$OUT/emissions_classes
  rm -rf "$d" && mkdir -p "$d"
  make_emissions_line "$d" emissions_classes
  cat > "$d/emissions_classes.rou.xml" <<'EOF'
<routes>
    <vType id="car" sigma="0" speedDev="0"/>
    <vType id="car_hbefa2" sigma="0" speedDev="0" emissionClass="P_7_7"/>
    <vType id="car_diesel" sigma="0" speedDev="0" emissionClass="HBEFA3/PC_D_EU6"/>
    <vType id="truck" vClass="truck" sigma="0" speedDev="0"/>
    <vType id="truck_hbefa2" vClass="truck" sigma="0" speedDev="0" emissionClass="HBEFA2/HDV_A0_12_3"/>
    <vType id="bus" vClass="bus" sigma="0" speedDev="0"/>
    <vType id="moto" vClass="motorcycle" sigma="0" speedDev="0"/>
    <vType id="van" vClass="delivery" sigma="0" speedDev="0"/>
    <route id="r" edges="AB BC CD"/>
    <vehicle id="car" type="car" route="r" depart="0"/>
    <vehicle id="truck" type="truck" route="r" depart="15"/>
    <vehicle id="bus" type="bus" route="r" depart="30"/>
    <vehicle id="moto" type="moto" route="r" depart="45"/>
    <vehicle id="car_hbefa2" type="car_hbefa2" route="r" depart="60"/>
    <vehicle id="truck_hbefa2" type="truck_hbefa2" route="r" depart="75"/>
    <vehicle id="van" type="van" route="r" depart="90"/>
    <vehicle id="car_diesel" type="car_diesel" route="r" depart="105"/>
</routes>
EOF
  write_sumocfg "$d" emissions_classes emissions_classes.rou.xml
}

# --- motorway_ramps: a 3-lane motorway (130 km/h) with an on-ramp whose lane runs on as a 4th lane for
# 300 m and alone leads to the off-ramp after it (a weaving section: entering and exiting vehicles cross),
# then a lane drop (3 -> 2, the left lane ends). Cars and 90 km/h trucks, step 0.5 s, flows for 30 min --
make_motorway_ramps() {
  local d=$OUT/motorway_ramps
  rm -rf "$d" && mkdir -p "$d"
  cat > "$TMP/mw.nod.xml" <<'EOF'
<nodes>
    <node id="A" x="0" y="0" type="priority"/>
    <node id="R" x="1000" y="-100" type="priority"/>
    <node id="B" x="1500" y="0" type="priority"/>
    <node id="C" x="1800" y="0" type="priority"/>
    <node id="O" x="2300" y="-100" type="priority"/>
    <node id="D" x="2800" y="0" type="priority"/>
    <node id="E" x="3800" y="0" type="priority"/>
    <node id="F" x="4300" y="0" type="priority"/>
</nodes>
EOF
  cat > "$TMP/mw.edg.xml" <<'EOF'
<edges>
    <edge id="AB" from="A" to="B" numLanes="3" speed="36.11" priority="13"/>
    <edge id="RB" from="R" to="B" numLanes="1" speed="22.22" priority="9"/>
    <edge id="BC" from="B" to="C" numLanes="4" speed="36.11" priority="13"/>
    <edge id="CO" from="C" to="O" numLanes="1" speed="22.22" priority="9"/>
    <edge id="CD" from="C" to="D" numLanes="3" speed="36.11" priority="13"/>
    <edge id="DE" from="D" to="E" numLanes="2" speed="36.11" priority="13"/>
    <edge id="EF" from="E" to="F" numLanes="2" speed="36.11" priority="13"/>
</edges>
EOF
  cat > "$TMP/mw.con.xml" <<'EOF'
<connections>
    <connection from="RB" to="BC" fromLane="0" toLane="0"/>
    <connection from="AB" to="BC" fromLane="0" toLane="1"/>
    <connection from="AB" to="BC" fromLane="1" toLane="2"/>
    <connection from="AB" to="BC" fromLane="2" toLane="3"/>
    <connection from="BC" to="CO" fromLane="0" toLane="0"/>
    <connection from="BC" to="CD" fromLane="1" toLane="0"/>
    <connection from="BC" to="CD" fromLane="2" toLane="1"/>
    <connection from="BC" to="CD" fromLane="3" toLane="2"/>
    <connection from="CD" to="DE" fromLane="0" toLane="0"/>
    <connection from="CD" to="DE" fromLane="1" toLane="1"/>
    <connection from="DE" to="EF" fromLane="0" toLane="0"/>
    <connection from="DE" to="EF" fromLane="1" toLane="1"/>
</connections>
EOF
  # netconvert warns that junctions B and C's shapes lie off their positions (the ramps' angles): harmless.
  netconvert -n "$TMP/mw.nod.xml" -e "$TMP/mw.edg.xml" -x "$TMP/mw.con.xml" --no-turnarounds \
    -o "$d/motorway_ramps.net.xml" > /dev/null 2>&1
  cat > "$d/motorway_ramps.rou.xml" <<'EOF'
<routes>
    <vType id="truck" vClass="truck" length="12" minGap="2.5" accel="1.0" decel="4.0" maxSpeed="25" speedDev="0.05"/>
    <flow id="main_through" from="AB" to="EF" begin="0" end="1800" vehsPerHour="2100" departLane="best" departSpeed="max"/>
    <flow id="main_trucks" type="truck" from="AB" to="EF" begin="0" end="1800" vehsPerHour="250" departLane="best" departSpeed="max"/>
    <flow id="main_exit" from="AB" to="CO" begin="0" end="1800" vehsPerHour="500" departLane="best" departSpeed="max"/>
    <flow id="ramp_through" from="RB" to="EF" begin="0" end="1800" vehsPerHour="500" departLane="best" departSpeed="max"/>
    <flow id="ramp_exit" from="RB" to="CO" begin="0" end="1800" vehsPerHour="100" departLane="best" departSpeed="max"/>
</routes>
EOF
  strip_generated_header "$d/motorway_ramps.net.xml"
  cat > "$d/motorway_ramps.sumocfg" <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<configuration xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/sumoConfiguration.xsd">
    <input>
        <net-file value="motorway_ramps.net.xml"/>
        <route-files value="motorway_ramps.rou.xml"/>
    </input>
    <time>
        <begin value="0"/>
        <end value="2400"/>
        <step-length value="0.5"/>
    </time>
</configuration>
EOF
}

# A town's arterial with three signals, its side streets, cars, trucks held to 30 km/h on the arterial by its
# edge type's <restriction>, and two bus lines with curb stops: on the arterial's right lane (traffic passes
# on the left lane) and on a one-lane side street (traffic waits behind the bus).
make_city_mixed() {
  local d=$OUT/city_mixed
  rm -rf "$d" && mkdir -p "$d"
  cat > "$TMP/cm.nod.xml" <<'EOF'
<nodes>
    <node id="W" x="0" y="0" type="priority"/>
    <node id="J1" x="300" y="0" type="traffic_light"/>
    <node id="J2" x="600" y="0" type="traffic_light"/>
    <node id="J3" x="900" y="0" type="traffic_light"/>
    <node id="E" x="1200" y="0" type="priority"/>
    <node id="N1" x="300" y="250" type="priority"/>
    <node id="S1" x="300" y="-250" type="priority"/>
    <node id="N2" x="600" y="250" type="priority"/>
    <node id="S2" x="600" y="-250" type="priority"/>
    <node id="N3" x="900" y="250" type="priority"/>
    <node id="S3" x="900" y="-250" type="priority"/>
</nodes>
EOF
  cat > "$TMP/cm.typ.xml" <<'EOF'
<types>
    <type id="arterial" priority="7" numLanes="2" speed="13.89">
        <restriction vClass="truck" speed="8.33"/>
    </type>
    <type id="local" priority="5" numLanes="1" speed="11.11"/>
</types>
EOF
  {
    echo "<edges>"
    local nodes=(W J1 J2 J3 E) k end
    for k in 0 1 2 3; do
      local a=${nodes[$k]} b=${nodes[$((k + 1))]}
      echo "    <edge id=\"$a$b\" from=\"$a\" to=\"$b\" type=\"arterial\"/>"
      echo "    <edge id=\"$b$a\" from=\"$b\" to=\"$a\" type=\"arterial\"/>"
    done
    for k in 1 2 3; do
      for end in N S; do
        echo "    <edge id=\"$end${k}J$k\" from=\"$end$k\" to=\"J$k\" type=\"local\"/>"
        echo "    <edge id=\"J$k$end$k\" from=\"J$k\" to=\"$end$k\" type=\"local\"/>"
      done
    done
    echo "</edges>"
  } > "$TMP/cm.edg.xml"
  netconvert -t "$TMP/cm.typ.xml" -n "$TMP/cm.nod.xml" -e "$TMP/cm.edg.xml" --no-turnarounds \
    --tls.default-type static -o "$d/city_mixed.net.xml" > /dev/null 2>&1
  strip_generated_header "$d/city_mixed.net.xml"
  cat > "$d/city_mixed.add.xml" <<'EOF'
<additional>
    <busStop id="arterial_east" lane="J1J2_0" startPos="120" endPos="140"/>
    <busStop id="arterial_west" lane="J2J1_0" startPos="120" endPos="140"/>
    <busStop id="north_out" lane="J2N2_0" startPos="100" endPos="115"/>
    <busStop id="north_in" lane="N2J2_0" startPos="100" endPos="115"/>
</additional>
EOF
  # Sorted by departure: SUMO ignores a flow listed after a later one (route files are read ahead).
  cat > "$d/city_mixed.rou.xml" <<'EOF'
<routes>
    <vType id="truck" vClass="truck" length="10" minGap="2.5" accel="1.0" decel="4.0" maxSpeed="25"/>
    <vType id="bus" vClass="bus" length="12" minGap="2.5" accel="1.2" decel="4.0" maxSpeed="20"/>
    <route id="bus_out" edges="WJ1 J1J2 J2N2">
        <stop busStop="arterial_east" duration="20"/>
        <stop busStop="north_out" duration="15"/>
    </route>
    <route id="bus_in" edges="N2J2 J2J1 J1W">
        <stop busStop="north_in" duration="15"/>
        <stop busStop="arterial_west" duration="20"/>
    </route>
    <flow id="car_we" from="WJ1" to="J3E" begin="0" end="1800" vehsPerHour="500" departLane="best"/>
    <flow id="car_ew" from="EJ3" to="J1W" begin="0" end="1800" vehsPerHour="500" departLane="best"/>
    <flow id="car_n1s3" from="N1J1" to="J3S3" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="car_s1n3" from="S1J1" to="J3N3" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="car_n2e" from="N2J2" to="J3E" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="car_s2w" from="S2J2" to="J1W" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="car_n3w" from="N3J3" to="J1W" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="car_s3e" from="S3J3" to="J3E" begin="0" end="1800" vehsPerHour="120" departLane="best"/>
    <flow id="truck_we" type="truck" from="WJ1" to="J3E" begin="0" end="1800" vehsPerHour="60" departLane="best"/>
    <flow id="truck_ew" type="truck" from="EJ3" to="J1W" begin="0" end="1800" vehsPerHour="60" departLane="best"/>
    <flow id="truck_s1e" type="truck" from="S1J1" to="J3E" begin="0" end="1800" vehsPerHour="40" departLane="best"/>
    <flow id="bus_out" type="bus" route="bus_out" begin="30" end="1800" period="180" departLane="best"/>
    <flow id="bus_in" type="bus" route="bus_in" begin="90" end="1800" period="180" departLane="best"/>
</routes>
EOF
  cat > "$d/city_mixed.sumocfg" <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<configuration xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/sumoConfiguration.xsd">
    <input>
        <net-file value="city_mixed.net.xml"/>
        <route-files value="city_mixed.rou.xml"/>
        <additional-files value="city_mixed.add.xml"/>
    </input>
    <time>
        <begin value="0"/>
        <end value="2400"/>
    </time>
</configuration>
EOF
}

make_grid_tls
make_random_net
make_flows
make_lpsim_csv_small
make_actuated_cross
make_keep_clear
make_cosim_line
make_emissions_free
make_emissions_redlight
make_emissions_classes
make_motorway_ramps
make_city_mixed

for name in grid_tls random_net flows actuated_cross keep_clear cosim_line emissions_free emissions_redlight \
  emissions_classes motorway_ramps city_mixed; do
  "$PY" "$ROOT/tools/sumo_reference.py" "$OUT/$name/$name.sumocfg" > "$OUT/$name/sumo_reference.txt"
done
du -sh "$OUT"

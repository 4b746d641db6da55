#!/usr/bin/python3
"""Build osmWebWizard-style SUMO scenarios from the OSM-derived networks in the shared folder.

Usage (from the repository root; run with /usr/bin/python3, which sees sumolib):

    tools/make_wizard_scenarios.py [--out DIR] [--shared ../shared] [--only NAME,...] [--check]

  --out DIR       output folder (default: build/wizard_scenarios in the repository, git-ignored)
  --shared DIR    the shared folder holding scenarios/ (default: ../shared next to the repository)
  --only NAMES    build only these scenarios (comma separated, e.g. wizard_wildau)
  --check         afterwards run each scenario with `sumo -c osm.sumocfg --no-step-log` and print
                  SUMO's loaded/inserted/arrived figures and the run time
  --rail-stop-tag busStop|trainStop
                  element written for stops on rail lanes (default trainStop; netconvert itself
                  writes <busStop> for every stop, use busStop for byte-level netconvert style)

What it does: SUMO's tools/osmWebWizard.py downloads OSM data, imports it with netconvert (with
--ptstop-output/--ptline-output) and then generates the demand. We have no OSM data, so this script
starts from the already imported networks and does everything the wizard does after the import:

  * copies the network to <scenario>/osm.net.xml.gz;
  * public transport: since --ptstop-output/--ptline-output need OSM input, it derives the
    netconvert-style stops file (osm_stops.add.xml: <busStop> on the rightmost lane that buses may
    use, <trainStop> on rail lanes with <access> elements to sidewalks within 150 m, all with
    friendlyPos="true" as netconvert writes them) and the ptlines file (osm_ptlines.xml:
    <ptLine id name line type vClass period completeness> with <route edges/> and <busStop id name/>
    children) from the network: bus lines along fastest paths between opposite sides of the network
    (both directions, stops every ~500 m), train lines along the longest rail paths (both directions
    where a separate reverse track exists; never against each other on a single bidi track, which
    would deadlock without a timetable; stops every ~2 km); then calls ptlines2flows.py with exactly the
    wizard's options (-p 600 --random-begin --seed 42 --ignore-errors --vtype-prefix pt_
    --min-stops 0 --extend-to-fringe ...) -> osm_pt.rou.xml;
  * calls randomTrips.py per mode with the wizard's options (vehicleParameters + parseTripOpts:
    --fringe-factor, --insertion-density, -e <duration>, --validate, --remove-loops, departLane/
    departSpeed attributes, per-mode distances, pedestrians as person trips with modes="public"
    routed over the stops and pt routes);
  * writes osm.view.xml and the configuration osm.sumocfg with `sumo ... --save-configuration`
    using the wizard's options, plus build.bat / run.bat as the wizard does.

Everything is deterministic (fixed seeds). Nothing is written outside --out.
Running a scenario: `SUMO_HOME=/usr/share/sumo sumo -c <out>/<scenario>/osm.sumocfg --no-step-log`
(the files reference SUMO's XML schemas, as the wizard's do; without SUMO_HOME, SUMO 1.15 cannot
resolve them offline and stops with "invalid document structure").
"""

import argparse
import gzip
import heapq
import math
import os
import re
import shutil
import subprocess
import sys
import time

SUMO_HOME = os.environ.get("SUMO_HOME", "/usr/share/sumo")
os.environ["SUMO_HOME"] = SUMO_HOME
TOOLS = os.path.join(SUMO_HOME, "tools")
sys.path.append(TOOLS)
import sumolib  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHON = sys.executable or "/usr/bin/python3"
PREFIX = "osm"

# ---------------------------------------------------------------------------------------------
# the wizard's randomTrips parameters (tools/osmWebWizard.py, SUMO 1.15)
CP = ["--trip-attributes", 'departLane="best"',
      "--fringe-start-attributes", 'departSpeed="max"',
      "--validate", "--remove-loops"]
PP = ["--vehicle-class", "pedestrian", "--prefix", "ped"]


def getParams(vClass, prefix=None):
    if prefix is None:
        prefix = vClass
    return ["--vehicle-class", vClass, "--vclass", vClass, "--prefix", prefix]


VEHICLE_PARAMETERS = {
    "passenger": CP + getParams("passenger", "veh") + ["--min-distance", "300", "--min-distance.fringe", "10",
                                                       "--allow-fringe.min-length", "1000", "--lanes"],
    "truck": CP + getParams("truck") + ["--min-distance", "600", "--min-distance.fringe", "10"],
    "bus": CP + getParams("bus") + ["--min-distance", "600", "--min-distance.fringe", "10"],
    "motorcycle": CP + getParams("motorcycle") + ["--max-distance", "1200"],
    "bicycle": CP + getParams("bicycle", "bike") + ["--max-distance", "8000"],
    "pedestrian": PP + ["--pedestrians", "--max-distance", "2000"],
    "persontrips": PP + ["--persontrips", "--trip-attributes", 'modes="public"'],
}

# web wizard defaults (webWizard/script.js): fringeFactor, count (per hour and km of lane)
#   passenger 5/12, truck 5/8, bus 5/4, motorcycle 2/4, bicycle 2/6, pedestrian 1/10
SCENARIOS = [
    {
        "name": "wizard_wildau",
        "net": "scenarios/wildau/net.net.xml.gz",
        "duration": 3600,
        "vehicles": {  # the web wizard's defaults
            "passenger": {"fringeFactor": 5, "count": 12},
            "truck": {"fringeFactor": 5, "count": 8},
            "bus": {"fringeFactor": 5, "count": 4},
            "motorcycle": {"fringeFactor": 2, "count": 4},
            "bicycle": {"fringeFactor": 2, "count": 6},
            "pedestrian": {"fringeFactor": 1, "count": 10},
        },
        "bus_lines": 3,
        "train_lines": 2,
    },
    {
        "name": "wizard_badhersfeld",
        "net": "scenarios/dlr_badhersfeld_bus/osm_edited.net.xml.gz",
        "duration": 3600,
        "vehicles": {  # the wizard's fringe factors, counts reduced (large net: 15 x 11 km)
            "passenger": {"fringeFactor": 5, "count": 3},
            "truck": {"fringeFactor": 5, "count": 0.6},
            "bus": {"fringeFactor": 5, "count": 0.4},
            "motorcycle": {"fringeFactor": 2, "count": 0.5},
            "bicycle": {"fringeFactor": 2, "count": 1},
            "pedestrian": {"fringeFactor": 1, "count": 1},
        },
        "bus_lines": 3,
        "train_lines": 2,
    },
]

# public transport generation parameters (netconvert defaults for stop lengths:
# --osm.stop-output.length 25, --osm.stop-output.length.train 200; railway access: 150 m, 5, x1.5)
PT = {
    "bus": {"vclass": "bus", "type": "bus", "spacing": 500.0, "first": 200.0, "stop_len": 25.0,
            "min_edge": 25.0, "min_line": 1500.0, "period": 600, "max_speed": 22.3},
    "train": {"vclass": "rail", "type": "train", "spacing": 2000.0, "first": 600.0, "stop_len": 200.0,
              "min_edge": 120.0, "min_line": 2000.0, "period": 1200, "max_speed": None},
}
ACCESS_DIST = 150.0
ACCESS_MAX = 5
ACCESS_FACTOR = 1.5


def log(msg):
    print(msg, flush=True)


def fmt(x):
    return "%.2f" % x


def xml_escape(s):
    return (str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))


# ---------------------------------------------------------------------------------------------
# network helpers
def normal_edges(net):
    return [e for e in net.getEdges() if e.getFunction() == ""]


def edge_center(e):
    shape = e.getShape()
    return sumolib.geomhelper.positionAtShapeOffset(shape, sumolib.geomhelper.polyLength(shape) / 2)


def first_allowed_lane(edge, vclass):
    """netconvert: the first lane (from the right) that permits the stop's vehicle class"""
    for lane in edge.getLanes():
        if lane.allows(vclass):
            return lane
    return None


def is_turnaround(e, o):
    return o.getFromNode() == e.getToNode() and o.getToNode() == e.getFromNode()


def dijkstra(src, vclass, usable):
    """fastest paths (travel time at the speed limit) from src over usable edges"""
    dist = {src: src.getLength() / src.getSpeed()}
    prev = {src: None}
    heap = [(dist[src], src.getID(), src)]
    while heap:
        d, _, e = heapq.heappop(heap)
        if d > dist[e]:
            continue
        for o in sorted(e.getAllowedOutgoing(vclass), key=lambda x: x.getID()):
            if not usable(o) or o.getFunction() != "" or is_turnaround(e, o):
                continue
            nd = d + o.getLength() / o.getSpeed()
            if nd < dist.get(o, 1e400):
                dist[o] = nd
                prev[o] = e
                heapq.heappush(heap, (nd, o.getID(), o))
    return prev


def backtrack(prev, dst):
    if dst not in prev:
        return None
    path = []
    e = dst
    while e is not None:
        path.append(e)
        e = prev[e]
    return path[::-1]


def path_length(path):
    return sum(e.getLength() for e in path)


def overlap(path, other):
    """share of the length of path that is also in other"""
    common = set(path) & set(other)
    return sum(e.getLength() for e in common) / max(1.0, path_length(path))


def bidi_conflict(path, other):
    """path uses the opposite direction of a single track (bidi edge) used by other"""
    other = set(other)
    return any(e.getBidi() is not None and e.getBidi() in other for e in path)


def strongly_connected_core(edges, vclass, usable):
    """the edges that can reach and be reached from the usable edge nearest to the centre"""
    edges = [e for e in edges if usable(e)]
    if not edges:
        return set()
    eset = set(edges)
    succ = {e: [o for o in e.getAllowedOutgoing(vclass) if o in eset and not is_turnaround(e, o)] for e in edges}
    pred = {e: [] for e in edges}
    for e in edges:
        for o in succ[e]:
            pred[o].append(e)
    xs = [edge_center(e) for e in edges]
    cx = sum(x for x, _ in xs) / len(xs)
    cy = sum(y for _, y in xs) / len(xs)

    def reach(seed, nbrs):
        seen = {seed}
        todo = [seed]
        while todo:
            e = todo.pop()
            for o in nbrs[e]:
                if o not in seen:
                    seen.add(o)
                    todo.append(o)
        return seen
    best = set()
    # try seeds in order of distance to the centre until a large component is found
    for _, _, seed in sorted((dist2(x, (cx, cy)), e.getID(), e) for x, e in zip(xs, edges))[:10]:
        comp = reach(seed, succ) & reach(seed, pred)
        if len(comp) > len(best):
            best = comp
        if len(best) > len(edges) / 3:
            break
    return best


def dist2(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


# ---------------------------------------------------------------------------------------------
# public transport lines and stops
class PTBuilder:
    def __init__(self, net, rail_stop_tag):
        self.net = net
        self.rail_stop_tag = rail_stop_tag
        self.stops = {}       # id -> dict
        self.stop_on_edge = {}  # (kind, edge id) -> stop id
        self.lines = []       # dicts
        self.counter = {"bus": 0, "train": 0}
        self.ped_lanes = None

    # -- stops --
    def get_stop(self, kind, edge, center, line_ref):
        p = PT[kind]
        # re-use a stop of another line (or direction) that is near on the same edge
        for sid in self.stop_on_edge.get((kind, edge.getID()), []):
            s = self.stops[sid]
            if abs((s["start"] + s["end"]) / 2 - center) < p["spacing"] / 2:
                if line_ref not in s["lines"]:
                    s["lines"].append(line_ref)
                return sid
        lane = first_allowed_lane(edge, p["vclass"])
        length = lane.getLength()
        half = p["stop_len"] / 2
        if length >= p["stop_len"]:
            center = min(max(center, half), length - half)
        else:
            center = length / 2
        start = max(0.0, center - half)
        end = min(center + half, length)
        self.counter[kind] += 1
        n = self.counter[kind]
        sid = ("bs_%s" if kind == "bus" else "ts_%s") % n
        name = ("Bus stop %s" if kind == "bus" else "Station %s") % n
        stop = {"id": sid, "name": name, "lane": lane.getID(), "start": start, "end": end,
                "lines": [line_ref], "kind": kind, "access": []}
        if kind == "train":
            stop["access"] = self.find_access(lane, center)
        self.stops[sid] = stop
        self.stop_on_edge.setdefault((kind, edge.getID()), []).append(sid)
        return sid

    def find_access(self, lane, pos):
        """like netconvert's railway access search: sidewalks within 150 m, at most 5, length
        = air-line distance * 1.5"""
        if self.ped_lanes is None:
            self.ped_lanes = []
            for e in normal_edges(self.net):
                if e.allows("rail"):
                    continue
                for ln in e.getLanes():
                    if ln.allows("pedestrian"):
                        x0, y0, x1, y1 = ln.getBoundingBox(False)
                        self.ped_lanes.append((x0, y0, x1, y1, ln))
        x, y = sumolib.geomhelper.positionAtShapeOffset(lane.getShape(), pos)
        cands = {}
        for x0, y0, x1, y1, ln in self.ped_lanes:
            if x < x0 - ACCESS_DIST or x > x1 + ACCESS_DIST or y < y0 - ACCESS_DIST or y > y1 + ACCESS_DIST:
                continue
            lpos, d = ln.getClosestLanePosAndDist((x, y))
            if d <= ACCESS_DIST:
                eid = ln.getEdge().getID()
                if eid not in cands or d < cands[eid][0]:
                    cands[eid] = (d, ln.getID(), lpos)
        best = sorted(cands.values())[:ACCESS_MAX]
        return [(lid, lpos, d * ACCESS_FACTOR) for d, lid, lpos in best]

    def place_stops(self, kind, path, line_ref):
        """a stop about every `spacing` metres along the path (first one after `first` metres),
        on edges long enough for the stop (netconvert's default stop lengths)"""
        p = PT[kind]
        cum = []
        c = 0.0
        for e in path:
            cum.append(c)
            c += e.getLength()
        total = c
        result = []
        d = p["first"]
        last = None  # path offset of the previous stop
        while d <= total - p["first"] / 2:
            i = max(k for k in range(len(path)) if cum[k] <= d)
            j = i
            while j < len(path) and (path[j].getLength() < p["min_edge"]
                                     or first_allowed_lane(path[j], p["vclass"]) is None):
                j += 1
            if j < len(path) and cum[j] < d + p["spacing"] / 2:
                center = d - cum[j] if j == i else p["stop_len"] / 2 + 5
                if last is None or cum[j] + center - last >= p["spacing"] / 2:
                    sid = self.get_stop(kind, path[j], center, line_ref)
                    if sid not in result:
                        result.append(sid)
                        last = cum[j] + center
                d = max(d, cum[j] + center) + p["spacing"]
            else:
                d += p["spacing"]
        return result

    def add_line(self, kind, ref, direction, path):
        stops = self.place_stops(kind, path, ref)
        p = PT[kind]
        first = self.stops[stops[0]]["name"] if stops else path[0].getID()
        last = self.stops[stops[-1]]["name"] if stops else path[-1].getID()
        label = ("Bus %s" if kind == "bus" else "Train %s") % ref
        self.lines.append({
            "id": "%s_%s_%s" % (p["type"], ref, direction),
            "name": "%s: %s => %s" % (label, first, last),
            "line": ref, "type": p["type"], "vClass": p["vclass"], "period": p["period"],
            "edges": [e.getID() for e in path], "stops": stops, "length": path_length(path)})

    # -- bus lines: fastest paths between opposite sides of the network --
    def bus_lines(self, n_lines):
        p = PT["bus"]
        vclass = p["vclass"]
        allowed = [e for e in normal_edges(self.net) if e.allows(vclass) and first_allowed_lane(e, vclass)]
        if not allowed:
            return 0

        def moderate(e):
            return p["max_speed"] is None or e.getSpeed() <= p["max_speed"]
        # line ends only in the strongly connected part of the (moderate speed) bus network around
        # the centre, so that every pair of candidate ends is connected in both directions
        core = strongly_connected_core(allowed, vclass, moderate)
        ends = [e for e in allowed if e in core and e.getLength() >= 30 and e.getSpeed() >= 8.0]
        if len(ends) < 20:
            ends = [e for e in allowed if e in core]
        if len(ends) < 2:
            return 0
        centers = {e: edge_center(e) for e in ends}
        made = 0
        used_pairs = []
        angles = [math.pi * k / n_lines for k in range(n_lines)]
        angles += [math.pi * (k + 0.5) / n_lines for k in range(n_lines)]
        for ang in angles:
            if made >= n_lines:
                break
            u = (math.cos(ang), math.sin(ang))
            ranked = sorted(ends, key=lambda e: (centers[e][0] * u[0] + centers[e][1] * u[1], e.getID()))
            srcs, dsts = ranked[:6], ranked[::-1][:6]
            fwd = self.best_path(srcs, dsts, vclass, moderate, p["min_line"])
            if fwd is None:
                continue
            if any(overlap(fwd, q) > 0.5 for q in used_pairs):
                continue
            ref = str(made + 1)
            self.add_line("bus", ref, "a", fwd)
            used_pairs.append(fwd)
            # reverse direction: start near the end of the forward path and vice versa
            endp, startp = fwd[-1].getToNode().getCoord(), fwd[0].getFromNode().getCoord()
            rsrcs = sorted(ends, key=lambda e: (dist2(centers[e], endp), e.getID()))[:6]
            rdsts = sorted(ends, key=lambda e: (dist2(centers[e], startp), e.getID()))[:6]
            rev_first = [e for e in fwd[-1].getToNode().getOutgoing()
                         if e.getToNode() == fwd[-1].getFromNode() and e in centers]
            rev_last = [e for e in fwd[0].getFromNode().getIncoming()
                        if e.getFromNode() == fwd[0].getToNode() and e in centers]
            bwd = self.best_path(rev_first + rsrcs, rev_last + rdsts, vclass, moderate, p["min_line"])
            if bwd is not None:
                self.add_line("bus", ref, "b", bwd)
            made += 1
        return made

    def best_path(self, srcs, dsts, vclass, usable, min_len):
        for s in srcs:
            prev = dijkstra(s, vclass, lambda e: usable(e) or e == s)
            for d in dsts:
                if d == s:
                    continue
                path = backtrack(prev, d)
                if path and path_length(path) >= min_len:
                    return path
        return None

    # -- train lines: longest rail paths from track starts to track ends --
    def train_lines(self, n_lines):
        p = PT["train"]
        vclass = p["vclass"]
        rail = [e for e in normal_edges(self.net) if e.allows(vclass) and not e.allows("passenger")]
        if not rail:
            return 0
        railset = set(rail)

        def usable(e):
            return e in railset
        # track starts/ends: no rail predecessor/successor except the own reverse direction (bidi track)
        starts = [e for e in rail if not any(i in railset and i.getAllowedOutgoing(vclass).get(e)
                                             and not is_turnaround(i, e) for i in e.getIncoming())]
        ends = [e for e in rail if not any(o in railset and not is_turnaround(e, o)
                                           for o in e.getAllowedOutgoing(vclass))]
        cands = []
        for s in sorted(starts, key=lambda e: e.getID()):
            prev = dijkstra(s, vclass, usable)
            for d in sorted(ends, key=lambda e: e.getID()):
                path = backtrack(prev, d)
                if path and path_length(path) >= p["min_line"]:
                    cands.append(path)
        cands.sort(key=lambda q: (-path_length(q), q[0].getID()))
        chosen = []
        made = 0
        for q in cands:
            if made >= n_lines:
                break
            # (lines may share a trunk in the same direction, but never run against each other on
            # a single (bidi) track: that deadlocks / collides without a timetable)
            if any(overlap(q, c) > 0.75 or bidi_conflict(q, c) for c in chosen) or q in chosen:
                continue
            qs, qe = q[0].getFromNode().getCoord(), q[-1].getToNode().getCoord()
            # the other direction: a path starting near q's end and ending near q's start
            rev = None
            for r in cands:
                if (r is q or r in chosen or overlap(r, q) > 0.5
                        or any(bidi_conflict(r, c) for c in chosen + [q])):
                    continue
                rs, re_ = r[0].getFromNode().getCoord(), r[-1].getToNode().getCoord()
                if dist2(rs, qe) < 800 and dist2(re_, qs) < 800:
                    rev = r
                    break
            ref = "R%s" % (made + 1)
            self.add_line("train", ref, "a", q)
            chosen.append(q)
            if rev is not None:
                self.add_line("train", ref, "b", rev)
                chosen.append(rev)
            made += 1
        return made

    # -- output in netconvert's formats --
    def write_stops(self, fname):
        with open(fname, "w") as f:
            f.write('<?xml version="1.0" encoding="UTF-8"?>\n\n')
            f.write("<!-- generated by tools/make_wizard_scenarios.py in the format of netconvert's "
                    "ptstop-output option -->\n\n")
            f.write('<additional xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
                    'xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/additional_file.xsd">\n')
            for sid in sorted(self.stops, key=lambda s: (s[:3], int(s[3:]))):
                s = self.stops[sid]
                tag = "busStop" if s["kind"] == "bus" else self.rail_stop_tag
                attrs = 'id="%s" name="%s" lane="%s" startPos="%s" endPos="%s" friendlyPos="true" lines="%s"' % (
                    sid, xml_escape(s["name"]), s["lane"], fmt(s["start"]), fmt(s["end"]),
                    xml_escape(" ".join(s["lines"])))
                if s["access"]:
                    f.write('    <%s %s>\n' % (tag, attrs))
                    for lid, pos, length in sorted(s["access"]):
                        f.write('        <access lane="%s" pos="%s" length="%s" friendlyPos="true"/>\n' % (
                            lid, fmt(pos), fmt(length)))
                    f.write('    </%s>\n' % tag)
                else:
                    f.write('    <%s %s/>\n' % (tag, attrs))
            f.write("</additional>\n")

    def write_lines(self, fname):
        with open(fname, "w") as f:
            f.write('<?xml version="1.0" encoding="UTF-8"?>\n\n')
            f.write("<!-- generated by tools/make_wizard_scenarios.py in the format of netconvert's "
                    "ptline-output option -->\n\n")
            f.write('<ptLines xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
                    'xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/ptlines_file.xsd">\n')
            for ln in self.lines:
                f.write('    <ptLine id="%s" name="%s" line="%s" type="%s" vClass="%s" period="%s" '
                        'completeness="1">\n' % (ln["id"], xml_escape(ln["name"]), xml_escape(ln["line"]),
                                                 ln["type"], ln["vClass"], ln["period"]))
                f.write('        <route edges="%s"/>\n' % " ".join(ln["edges"]))
                for sid in ln["stops"]:
                    f.write('        <busStop id="%s" name="%s"/>\n' % (sid, xml_escape(self.stops[sid]["name"])))
                f.write("    </ptLine>\n")
            f.write("</ptLines>\n")


# ---------------------------------------------------------------------------------------------
def quoted_str(s):
    if isinstance(s, float):
        return "%.6f" % s
    elif not isinstance(s, str):
        return str(s)
    elif '"' in s or ' ' in s:
        return '"' + s.replace('"', '\\"') + '"'
    return s


def run(cmd, cwd, logf):
    logf.write("\n$ " + " ".join(quoted_str(c) for c in cmd) + "\n")
    logf.flush()
    r = subprocess.run(cmd, cwd=cwd, stdout=logf, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        raise RuntimeError("command failed (rc %s): %s (see %s)" % (r.returncode, " ".join(cmd), logf.name))


def count_elements(fname, tags):
    opener = gzip.open if fname.endswith(".gz") else open
    with opener(fname, "rt") as f:
        text = f.read()
    return {t: len(re.findall(r"<%s[\s>]" % t, text)) for t in tags}


def build_scenario(sc, shared, outdir, rail_stop_tag):
    t0 = time.time()
    d = os.path.join(outdir, sc["name"])
    if os.path.isdir(d):
        shutil.rmtree(d)
    os.makedirs(d)
    logf = open(os.path.join(d, "build.log"), "w")
    src = os.path.join(shared, sc["net"])
    net_file = PREFIX + ".net.xml.gz"
    if src.endswith(".gz"):
        shutil.copyfile(src, os.path.join(d, net_file))
    else:
        with open(src, "rb") as fi, gzip.open(os.path.join(d, net_file), "wb") as fo:
            shutil.copyfileobj(fi, fo)
    net = sumolib.net.readNet(os.path.join(d, net_file))

    # --- public transport (what netconvert --ptstop-output/--ptline-output + ptlines2flows give)
    files = {"stops": PREFIX + "_stops.add.xml", "ptlines": PREFIX + "_ptlines.xml",
             "ptroutes": PREFIX + "_pt.rou.xml"}
    ptb = PTBuilder(net, rail_stop_tag)
    nbus = ptb.bus_lines(sc.get("bus_lines", 0))
    ntrain = ptb.train_lines(sc.get("train_lines", 0))
    public_transport = len(ptb.lines) > 0
    routenames, additional = [], []
    summary = {"bus lines": nbus, "train lines": ntrain, "ptLine elements": len(ptb.lines),
               "busStops": sum(1 for s in ptb.stops.values() if s["kind"] == "bus"),
               "trainStops(rail lanes)": sum(1 for s in ptb.stops.values() if s["kind"] == "train")}
    pt_options = None
    if public_transport:
        ptb.write_stops(os.path.join(d, files["stops"]))
        ptb.write_lines(os.path.join(d, files["ptlines"]))
        additional.append(files["stops"])
        routenames.append(files["ptroutes"])
        stops_for_p2f = files["stops"]
        if rail_stop_tag != "busStop" and summary["trainStops(rail lanes)"]:
            # ptlines2flows.py of SUMO 1.15 only reads <busStop> elements (netconvert writes all pt
            # stops as <busStop>); give it a copy with the rail stops as <busStop>.
            stops_for_p2f = PREFIX + "_stops.ptlines2flows.add.xml"
            with open(os.path.join(d, files["stops"])) as fi, open(os.path.join(d, stops_for_p2f), "w") as fo:
                fo.write(re.sub(r"<(/?)%s\b" % rail_stop_tag, r"<\1busStop", fi.read()))
        pt_options = ["-n", net_file, "-e", sc["duration"], "-p", "600", "--random-begin", "--seed", "42",
                      "--ptstops", stops_for_p2f, "--ptlines", files["ptlines"], "-o", files["ptroutes"],
                      "--ignore-errors", "--vtype-prefix", "pt_", "--stopinfos-file", "stopinfos.xml",
                      "--routes-file", "vehroutes.xml", "--trips-file", "trips.trips.xml",
                      "--min-stops", "0", "--extend-to-fringe", "--verbose"]
        run([PYTHON, os.path.join(TOOLS, "ptlines2flows.py")] + [str(o) for o in pt_options], d, logf)
        if stops_for_p2f != files["stops"]:
            os.remove(os.path.join(d, stops_for_p2f))
            pt_options[pt_options.index(stops_for_p2f)] = files["stops"]
        summary["pt flows"] = count_elements(os.path.join(d, files["ptroutes"]), ["flow"])["flow"]

    # --- randomTrips per mode, exactly as Builder.build/parseTripOpts
    random_trips_calls = []
    trips = {}
    for vehicle in sorted(sc["vehicles"]):
        opt = sc["vehicles"][vehicle]
        route = "%s.%s.rou.xml" % (PREFIX, vehicle)
        tripf = "%s.%s.trips.xml" % (PREFIX, vehicle)
        options = ["-n", net_file, "--fringe-factor", opt["fringeFactor"], "--insertion-density", opt["count"],
                   "-o", tripf, "-r", route, "-e", sc["duration"]]
        if vehicle == "pedestrian" and public_transport:
            options += VEHICLE_PARAMETERS["persontrips"]
            options += ["--additional-files", ",".join([files["stops"], files["ptroutes"]])]
            options += ["--persontrip.walk-opposite-factor", "0.8"]
        else:
            options += VEHICLE_PARAMETERS[vehicle]
        options = [str(o) for o in options]
        run([PYTHON, os.path.join(TOOLS, "randomTrips.py")] + options, d, logf)
        random_trips_calls.append(options)
        if vehicle == "pedestrian":
            routenames.append(route)
            trips[vehicle] = count_elements(os.path.join(d, route), ["person"])["person"]
        else:
            routenames.append(tripf)
            os.remove(os.path.join(d, route))
            alt = os.path.join(d, "%s.%s.rou.alt.xml" % (PREFIX, vehicle))
            if os.path.exists(alt):
                os.remove(alt)
            trips[vehicle] = count_elements(os.path.join(d, tripf), ["trip"])["trip"]
    for junk in ("NUL", PREFIX + ".pedestrian.rou.alt.xml"):
        if os.path.exists(os.path.join(d, junk)):
            os.remove(os.path.join(d, junk))
    summary["trips"] = trips

    # --- build.bat as the wizard writes it
    with open(os.path.join(d, "build.bat"), "w") as f:
        f.write("#!/bin/bash\n")
        f.write("# osm_stops.add.xml / osm_ptlines.xml: generated by tools/make_wizard_scenarios.py "
                "(the wizard gets them from netconvert's OSM import)\n")
        if rail_stop_tag != "busStop":
            f.write("# note: ptlines2flows.py 1.15 reads only <busStop>; the generator gave it a copy of the stops "
                    "file with the <%s> elements renamed to <busStop>\n" % rail_stop_tag)
        if pt_options is not None:
            f.write('python "%s" %s\n' % (os.path.join("$SUMO_HOME", "tools", "ptlines2flows.py"),
                                          " ".join(map(quoted_str, pt_options))))
        for opts in sorted(random_trips_calls):
            f.write('python "%s" %s\n' % (os.path.join("$SUMO_HOME", "tools", "randomTrips.py"),
                                          " ".join(map(quoted_str, opts))))
    os.chmod(os.path.join(d, "build.bat"), 0o755)

    # --- makeConfigFile
    with open(os.path.join(d, PREFIX + ".view.xml"), "w") as f:
        f.write("""
<viewsettings>
    <scheme name="real world"/>
    <delay value="20"/>
</viewsettings>
""")
    opts = [sumolib.checkBinary("sumo"), "-n", net_file, "--gui-settings-file", PREFIX + ".view.xml",
            "--duration-log.statistics",
            "--device.rerouting.adaptation-interval", "10",
            "--device.rerouting.adaptation-steps", "18",
            "-v", "--no-step-log", "--save-configuration", PREFIX + ".sumocfg", "--ignore-route-errors"]
    if routenames:
        opts += ["-r", ",".join(routenames)]
    if additional:
        opts += ["-a", ",".join(additional)]
    run(opts, d, logf)
    with open(os.path.join(d, "run.bat"), "w") as f:
        f.write("sumo-gui -c " + PREFIX + ".sumocfg")
    os.chmod(os.path.join(d, "run.bat"), 0o755)
    logf.close()
    summary["build s"] = round(time.time() - t0, 1)
    return d, summary


def check_scenario(d):
    """run the scenario as `sumo -c osm.sumocfg --no-step-log` and extract SUMO's statistics"""
    t0 = time.time()
    r = subprocess.run([sumolib.checkBinary("sumo"), "-c", PREFIX + ".sumocfg", "--no-step-log"], cwd=d,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    wall = time.time() - t0
    out = r.stdout
    with open(os.path.join(d, "check_run.log"), "w") as f:
        f.write(out)
    res = {"rc": r.returncode, "wall s": round(wall, 1),
           "errors": len(re.findall(r"^Error:", out, re.M)), "warnings": len(re.findall(r"^Warning:", out, re.M))}
    m = re.search(r"Simulation ended at time: ([\d.]+)", out)
    if m:
        res["end time"] = float(m.group(1))
    for who in ("Vehicles", "Persons"):
        m = re.search(r"^%s:\s*\n\s*Inserted: (\d+)(?: \(Loaded: (\d+)\))?\n\s*Running: (\d+)" % who, out, re.M)
        if m:
            k = who[:3].lower()
            res[k + " inserted"] = int(m.group(1))
            res[k + " loaded"] = int(m.group(2) or m.group(1))
            res[k + " running@end"] = int(m.group(3))
    m = re.search(r"^\s*Waiting: (\d+)", out, re.M)
    if m:
        res["veh waiting@end"] = int(m.group(1))
    m = re.search(r"^\s*Jammed: (\d+)", out, re.M)
    if m:
        res["per jammed"] = int(m.group(1))
    m = re.search(r"^Statistics \(avg of (\d+)\):\n\s*RouteLength", out, re.M)
    bikes = re.search(r"^Bike Statistics \(avg of (\d+)\)", out, re.M)
    res["veh arrived"] = (int(m.group(1)) if m else 0) + (int(bikes.group(1)) if bikes else 0)
    m = re.search(r"Teleports: (\d+)", out)
    res["teleports"] = int(m.group(1)) if m else 0
    m = re.search(r"Pedestrian Statistics \(avg of (\d+) walks\)", out)
    if m:
        res["walks"] = int(m.group(1))
    m = re.search(r"Ride Statistics \(avg of (\d+) rides\)", out)
    if m:
        res["rides"] = int(m.group(1))
    m = re.search(r"^ Duration: ([\d.,]+)s", out, re.M)
    if m:
        res["sumo duration s"] = float(m.group(1).replace(",", ""))
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(REPO, "build", "wizard_scenarios"))
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(REPO), "shared"))
    ap.add_argument("--only", help="comma separated scenario names")
    ap.add_argument("--check", action="store_true", help="run each scenario in sumo afterwards")
    ap.add_argument("--rail-stop-tag", default="trainStop", choices=["busStop", "trainStop"])
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    shared = os.path.abspath(a.shared)
    if out == shared or out.startswith(shared + os.sep):
        sys.exit("refusing to write into the shared folder %s" % shared)
    os.makedirs(out, exist_ok=True)
    only = set(a.only.split(",")) if a.only else None
    for sc in SCENARIOS:
        if only and sc["name"] not in only:
            continue
        log("building %s from %s" % (sc["name"], sc["net"]))
        d, summary = build_scenario(sc, shared, out, a.rail_stop_tag)
        log("  %s: %s" % (d, summary))
        if a.check:
            log("  sumo: %s" % check_scenario(d))


if __name__ == "__main__":
    main()

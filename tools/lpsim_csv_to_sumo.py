#!/usr/bin/python3
"""Writes an original-LPSim CSV network (nodes.csv, edges.csv) as SUMO plain XML (.nod.xml, .edg.xml) and
runs netconvert on it, so that SUMO and `lpsim run -n` load the same .net.xml.

    tools/lpsim_csv_to_sumo.py --nodes nodes.csv --edges edges.csv -o out.net.xml [-- NETCONVERT OPTIONS]

Writes out.nod.xml, out.edg.xml (beside the output unless --plain-prefix says where), out.net.xml and
out.netconvert.log (netconvert's own messages); prints netconvert's time and its warnings grouped by kind.
Options after `--` go to netconvert unchanged (e.g. `-- --no-internal-links`). Needs netconvert (PATH or
$SUMO_HOME/bin); SUMO_HOME defaults to /usr/share/sumo where that exists.

The CSV is read by the rules of LPSim's own reader (converters/lpsim_csv_reader.cpp), so the numbers match:
- nodes: `osmid` is the node id; x/y are WGS84 lon/lat when LPSim would read them so (every x within
  [-180,180], every y within [-90,90], and the edge lengths agree better with the degree reading), and are
  then projected by netconvert --proj.utm; otherwise they are metres, used unprojected.
- edges: id `uniqueid`; endpoints osmid_u/osmid_v when the header has them, else u/v (osmids); numLanes =
  `lanes` rounded, 0/empty/missing -> 1; speed = speed_mph * 0.44704 m/s, 0/empty/missing -> 13.89 m/s;
  `length` is written as the edge's length attribute, so SUMO's lanes keep the CSV length, not the distance
  between the projected nodes. The shape is the straight line between the nodes, as in LPSim.
- traffic lights: a node is type="traffic_light" exactly where LPSim makes it one (highway=traffic_signals
  and approaches on two axes: some incoming edge at 45 degrees or more to the axis of the incoming edge with
  the largest speed*lanes). Every other node with incoming and outgoing edges is type="priority" (LPSim's
  reading has no right-before-left); netconvert decides the rest (dead ends).
- edge priority = round(speed m/s * lanes), LPSim's major-road score, so netconvert picks the same kind of
  road as the major one.

What differs from LPSim's own reading of the CSV (netconvert builds the junctions, LPSim's reader derives
them by fixed rules):
- junctions get internal lanes (LPSim's CSV reading has none), so a trip drives a few metres more per
  junction; pass `-- --no-internal-links` to leave them out.
- connections and turn lanes are netconvert's: lanes are assigned to turns (not every incoming lane to every
  outgoing edge) and U-turns are built only at dead ends (--no-turnarounds.except-deadend; LPSim keeps a
  U-turn where a node offers the edge no other exit).
- right of way at priority junctions is netconvert's (major road = the two highest-priority edges, left
  turns yield), not LPSim's heading-group rule; signal programs are netconvert's static programs (one phase
  per compatible group of streams, 30 s green and 3 s yellow as LPSim's; left-turn phases where netconvert
  adds them), not LPSim's two-group 66 s cycle.
- self-loops (an edge from a node to itself) are dropped by netconvert with a warning; LPSim keeps them.
- projection: UTM (netconvert) rather than LPSim's equirectangular projection; lengths are the CSV's in both.
"""

import argparse
import collections
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import time
from xml.sax.saxutils import quoteattr

MPH_TO_METRES_PER_SECOND = 0.44704
DEFAULT_SPEED = 13.89  # m/s, SUMO's default edge speed (LPSim's default for a missing speed)
MAX_LANES = 32
EARTH_RADIUS = 6371008.8
SAME_AXIS_TOLERANCE = math.radians(45)
# Closest to LPSim's signal plans (30 s green, 3 s yellow per group) that netconvert's static programs allow.
NETCONVERT_DEFAULTS = ["--no-turnarounds.except-deadend", "--tls.green.time", "30", "--tls.yellow.time", "3"]


class InputError(Exception):
    """A bad input value: the message names file:line, the column and the value."""


def fail(path, line, message):
    raise InputError("%s:%d: %s" % (path, line, message))


def read_table(path):
    """Yields (line number, {column: trimmed field}) for each data record; the first record is the header."""
    try:
        handle = open(path, newline="", encoding="utf-8")
    except OSError as error:
        raise InputError("%s: cannot open: %s" % (path, error.strerror)) from None
    with handle:
        reader = csv.reader(handle)
        header = None
        for fields in reader:
            if not fields or fields == [""]:
                continue  # blank line
            if header is None:
                header = [name.strip() for name in fields]
                continue
            if len(fields) != len(header):
                fail(path, reader.line_num, "%d fields where the header has %d" % (len(fields), len(header)))
            yield reader.line_num, header, dict(zip(header, (f.strip() for f in fields)))


def number(path, line, row, column, optional=False):
    text = row.get(column, "")
    if text == "" and optional:
        return None
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not math.isfinite(value):
        fail(path, line, "column %s: %r is not a number" % (column, text))
    return value


def require(path, header, column):
    if column not in header:
        raise InputError("%s:1: no column %r in the header" % (path, column))


class Network:
    """The CSV network: nodes (ids, raw x/y, signal flags) and edges, by LPSim's reading rules."""

    def __init__(self):
        self.node_ids, self.node_x, self.node_y, self.node_signal = [], [], [], []
        self.node_index = {}
        self.edges = []  # (id, u index, v index, length, lanes, speed m/s)


def read_nodes(path, net):
    for line, header, row in read_table(path):
        for column in ("osmid", "x", "y"):
            require(path, header, column)
        node_id = row["osmid"]
        if node_id == "":
            fail(path, line, "empty node id")
        if node_id in net.node_index:
            fail(path, line, "duplicate node id %r" % node_id)
        net.node_index[node_id] = len(net.node_ids)
        net.node_ids.append(node_id)
        net.node_x.append(number(path, line, row, "x"))
        net.node_y.append(number(path, line, row, "y"))
        net.node_signal.append(row.get("highway", "") == "traffic_signals")


def round_half_away(value):
    return int(math.floor(value + 0.5))  # std::lround for the non-negative values it is used on


def read_edges(path, net):
    seen = set()
    for line, header, row in read_table(path):
        for column in ("uniqueid", "length"):
            require(path, header, column)
        # The full-network header carries dense indices in u/v and osmids in osmid_u/osmid_v.
        u_column, v_column = ("osmid_u", "osmid_v") if "osmid_u" in header else ("u", "v")
        require(path, header, u_column)
        require(path, header, v_column)
        edge_id = row["uniqueid"]
        if edge_id == "":
            fail(path, line, "empty edge id")
        if edge_id in seen:
            fail(path, line, "duplicate edge id %r" % edge_id)
        seen.add(edge_id)
        ends = []
        for column in (u_column, v_column):
            if row[column] not in net.node_index:
                fail(path, line, "column %s: unknown node %r (not in the nodes file)" % (column, row[column]))
            ends.append(net.node_index[row[column]])
        length = number(path, line, row, "length")
        if length < 0:
            fail(path, line, "negative length %r" % row["length"])
        lanes = number(path, line, row, "lanes", optional=True) or 0
        if lanes < 0:
            fail(path, line, "negative lane count %r" % row["lanes"])
        if lanes > MAX_LANES:
            fail(path, line, "more than %d lanes: %r" % (MAX_LANES, row["lanes"]))
        mph = number(path, line, row, "speed_mph", optional=True) or 0
        if mph < 0:
            fail(path, line, "negative speed %r" % row["speed_mph"])
        speed = mph * MPH_TO_METRES_PER_SECOND if mph > 0 else DEFAULT_SPEED
        net.edges.append((edge_id, ends[0], ends[1], length, max(1, round_half_away(lanes)), speed))


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def projection(net):
    """(degrees?, function (x, y) -> metres): LPSim's choice and its equirectangular projection, used here only
    for the headings that decide where a traffic light goes."""
    if not net.node_ids:
        return False, lambda x, y: (x, y)
    if any(abs(x) > 180 for x in net.node_x) or any(abs(y) > 90 for y in net.node_y):
        return False, lambda x, y: (x, y)
    lon0, lat0 = min(net.node_x), min(net.node_y)
    cos_lat = math.cos(math.radians(sum(net.node_y) / len(net.node_y)))
    scale = EARTH_RADIUS * math.pi / 180

    def project(x, y):
        return scale * cos_lat * (x - lon0), scale * (y - lat0)

    as_degrees, as_metres = [], []
    for _, u, v, length, _, _ in net.edges:
        dx, dy = net.node_x[v] - net.node_x[u], net.node_y[v] - net.node_y[u]
        metres = math.hypot(dx, dy)
        if metres <= 0 or length <= 0:
            continue
        as_degrees.append(abs(math.log(length / (scale * math.hypot(dx * cos_lat, dy)))))
        as_metres.append(abs(math.log(length / metres)))
    degrees = not as_degrees or median(as_degrees) <= median(as_metres)
    return degrees, (project if degrees else (lambda x, y: (x, y)))


def axis_difference(a, b):
    d = abs(math.remainder(a - b, 2 * math.pi))
    return min(d, math.pi - d)


def node_types(net, project):
    """{node index: SUMO junction type} by LPSim's rule; nodes left out are netconvert's to type."""
    pos = [project(x, y) for x, y in zip(net.node_x, net.node_y)]
    incoming = collections.defaultdict(list)
    has_out = set()
    for e, (_, u, v, _, _, _) in enumerate(net.edges):
        incoming[v].append(e)
        has_out.add(u)

    def heading(e):
        _, u, v, _, _, _ = net.edges[e]
        (ax, ay), (bx, by) = pos[u], pos[v]
        return math.atan2(by - ay, bx - ax) if (ax, ay) != (bx, by) else None

    def score(e):
        return net.edges[e][5] * net.edges[e][4]

    types = {}
    for node, edges in incoming.items():
        if node not in has_out:
            continue
        types[node] = "priority"
        if not net.node_signal[node]:
            continue
        reference = heading(max(edges, key=score))  # max() keeps the first of equals, as LPSim
        if reference is None:
            continue
        for e in edges:
            h = heading(e)
            if h is not None and axis_difference(h, reference) >= SAME_AXIS_TOLERANCE:
                types[node] = "traffic_light"
                break
    return types


def write_plain(net, types, prefix):
    with open(prefix + ".nod.xml", "w", encoding="utf-8") as out:
        out.write("<nodes>\n")
        for i, node_id in enumerate(net.node_ids):
            kind = ' type="%s"' % types[i] if i in types else ""
            out.write('    <node id=%s x="%r" y="%r"%s/>\n'
                      % (quoteattr(node_id), net.node_x[i], net.node_y[i], kind))
        out.write("</nodes>\n")
    with open(prefix + ".edg.xml", "w", encoding="utf-8") as out:
        out.write("<edges>\n")
        for edge_id, u, v, length, lanes, speed in net.edges:
            # netconvert ignores a length of 0 and takes the geometry's; LPSim's lane keeps 0 m (one cell).
            length_attr = ' length="%r"' % length if length > 0 else ""
            out.write(
                '    <edge id=%s from=%s to=%s priority="%d" numLanes="%d" speed="%r"%s/>\n'
                % (quoteattr(edge_id), quoteattr(net.node_ids[u]), quoteattr(net.node_ids[v]),
                   round_half_away(speed * lanes), lanes, speed, length_attr))
        out.write("</edges>\n")


def find_netconvert(explicit):
    if explicit:
        return explicit
    found = shutil.which("netconvert")
    if found:
        return found
    home = os.environ.get("SUMO_HOME", "")
    candidate = os.path.join(home, "bin", "netconvert")
    if home and os.access(candidate, os.X_OK):
        return candidate
    raise InputError("netconvert not found (put it on PATH or set SUMO_HOME)")


def warning_summary(log_text):
    """[(count, example)] for netconvert's warnings, most frequent first. netconvert prints the first few of a
    kind, then "N total messages of type: T" with '%' where the ids and numbers were; the other warnings are
    grouped by their text with quoted ids and numbers blanked."""
    lines = [line[len("Warning: "):] for line in log_text.splitlines() if line.startswith("Warning: ")]
    kinds = collections.OrderedDict()  # kind -> [count, example, counted by netconvert?]
    templates = []
    for text in lines:
        total = re.match(r"(\d+) total messages of type: (.*)$", text)
        if total:
            pattern = re.compile(".*?".join(re.escape(part) for part in total.group(2).split("%")) + "$")
            templates.append((pattern, total.group(2)))
            kinds[total.group(2)] = [int(total.group(1)), None, True]
    for text in lines:
        if re.match(r"\d+ total messages of type: ", text):
            continue
        kind = next((t for pattern, t in templates if pattern.match(text)), None)
        if kind is None:
            kind = re.sub(r"\d+(\.\d+)?", "N", re.sub(r"'[^']*'", "'…'", text))
        entry = kinds.setdefault(kind, [0, None, False])
        if not entry[2]:
            entry[0] += 1
        if entry[1] is None:
            entry[1] = text
    return sorted(((count, example or kind) for kind, (count, example, _) in kinds.items()),
                  key=lambda item: -item[0])


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", required=True, help="nodes.csv (osmid,x,y,...,highway)")
    parser.add_argument("--edges", required=True, help="edges.csv (uniqueid,u,v,length,lanes,speed_mph)")
    parser.add_argument("-o", "--output", required=True, help="the .net.xml to write")
    parser.add_argument("--plain-prefix", help="where the .nod.xml/.edg.xml go (default: the output's name)")
    parser.add_argument("--netconvert", help="netconvert binary (default: PATH, then $SUMO_HOME/bin)")
    parser.add_argument("netconvert_options", nargs="*", help="after --: more netconvert options")
    args = parser.parse_args(argv)

    net = Network()
    read_nodes(args.nodes, net)
    read_edges(args.edges, net)
    degrees, project = projection(net)
    types = node_types(net, project)
    prefix = args.plain_prefix or re.sub(r"(\.net)?\.xml(\.gz)?$", "", args.output)
    write_plain(net, types, prefix)
    self_loops = sum(1 for _, u, v, _, _, _ in net.edges if u == v)
    print("wrote %s.nod.xml (%d nodes, %d traffic lights) and %s.edg.xml (%d edges, %d lanes, %d self-loops)"
          % (prefix, len(net.node_ids), sum(t == "traffic_light" for t in types.values()), prefix,
             len(net.edges), sum(e[4] for e in net.edges), self_loops))

    if "SUMO_HOME" not in os.environ and os.path.isdir("/usr/share/sumo"):
        os.environ["SUMO_HOME"] = "/usr/share/sumo"  # netconvert validates against its XSDs there
    command = [find_netconvert(args.netconvert), "-n", prefix + ".nod.xml", "-e", prefix + ".edg.xml",
               "-o", args.output] + (["--proj.utm"] if degrees else []) + NETCONVERT_DEFAULTS
    command += args.netconvert_options
    print("running: " + " ".join(command))
    start = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    elapsed = time.monotonic() - start
    log_path = prefix + ".netconvert.log"
    with open(log_path, "w", encoding="utf-8") as log:
        log.write(result.stdout)
    summary = warning_summary(result.stdout)
    print("netconvert: exit %d after %.1f s, %d warnings (all in %s)"
          % (result.returncode, elapsed, sum(count for count, _ in summary), log_path))
    for count, example in summary:
        print("  %6d x %s" % (count, example))
    if result.returncode != 0:
        print("lpsim_csv_to_sumo: error: netconvert failed (exit %d):\n%s"
              % (result.returncode, result.stdout[-2000:]), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except InputError as error:
        print("lpsim_csv_to_sumo: error: %s" % error, file=sys.stderr)
        sys.exit(2)

#!/usr/bin/python3
"""The largest hand-over rate a boundary lane sustains in `lpsim cosim`, against the same lane's throughput in
LPSim alone and SUMO alone. A straight one-lane road A-B-C-D (400 m edges, 13.89 m/s, priority junctions,
no signal) with the corridor on B-C; one flow A-B -> C-D offered at rising rates. Per 300 s interval after
the first: vehicles handed into SUMO (SUMO counts them as departures on B-C), taken back (LPSim counts them
entering C-D), and, alone, vehicles entering C-D. Prints a markdown table.

  bench/cosim_handover_rate.py [--lpsim build/lpsim] [--out DIR] [--rates 1200,1800,2400,3000,3600]
"""
import argparse
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

NODES = """<nodes>
    <node id="A" x="0" y="0" type="priority"/>
    <node id="B" x="400" y="0" type="priority"/>
    <node id="C" x="800" y="0" type="priority"/>
    <node id="D" x="1200" y="0" type="priority"/>
</nodes>
"""
EDGES = """<edges>
    <edge id="AB" from="A" to="B" numLanes="1" speed="13.89"/>
    <edge id="BC" from="B" to="C" numLanes="1" speed="13.89"/>
    <edge id="CD" from="C" to="D" numLanes="1" speed="13.89"/>
</edges>
"""
PERIOD = 300
DURATION = 1800


def write(path, text):
    with open(path, "w") as handle:
        handle.write(text)
    return path


def counts(edgedata, edge, attribute):
    """attribute per interval of `edge`, by interval begin (intervals after the first only)."""
    out = {}
    for interval in ET.parse(edgedata).getroot().iter("interval"):
        begin = float(interval.get("begin"))
        if begin < PERIOD or begin + PERIOD > DURATION:
            continue
        value = 0.0
        for e in interval.iter("edge"):
            if e.get("id") == edge:
                value = float(e.get(attribute, 0))
        out[begin] = value
    return out


def per_hour(values):
    return max(values.values()) * 3600.0 / PERIOD if values else 0.0


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--lpsim", default="build/lpsim")
    p.add_argument("--out", default="build/cosim_handover_rate")
    p.add_argument("--rates", default="1200,1800,2400,3000,3600")
    args = p.parse_args(argv)
    lpsim = os.path.abspath(args.lpsim)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    env = dict(os.environ, SUMO_HOME=os.environ.get("SUMO_HOME", "/usr/share/sumo"))
    net = os.path.join(out, "line.net.xml")
    subprocess.run(["netconvert", "-n", write(os.path.join(out, "line.nod.xml"), NODES), "-e",
                    write(os.path.join(out, "line.edg.xml"), EDGES), "--no-turnarounds", "-o", net],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    corridor = write(os.path.join(out, "corridor.txt"), "edge:BC\n")
    rows = ["| offered veh/h | SUMO alone: CD entered, most per h | LPSim alone | co-sim: into SUMO | "
            "co-sim: out of SUMO | co-sim longest wait at the boundary s |",
            "|---|---|---|---|---|---|"]
    for rate in [int(r) for r in args.rates.split(",")]:
        d = os.path.join(out, "r%d" % rate)
        os.makedirs(d, exist_ok=True)
        routes = write(os.path.join(d, "flow.rou.xml"),
                       '<routes>\n    <flow id="f" from="AB" to="CD" begin="0" end="%d" vehsPerHour="%d" '
                       'departLane="best" departSpeed="max"/>\n</routes>\n' % (DURATION, rate))
        results = {}
        for kind in ("sumo", "lpsim", "cosim"):
            k = os.path.join(d, kind)
            os.makedirs(k, exist_ok=True)
            # Relative to the additional file: each run writes its own periods.xml (and SUMO's side of the
            # co-simulation's, sumo.periods.xml, merged into it).
            add = write(os.path.join(k, "periods.add.xml"),
                        '<additional>\n    <edgeData id="p" file="periods.xml" period="%d"/>\n</additional>\n'
                        % PERIOD)
            common = ["-n", net, "-r", routes, "-a", add, "--end", str(DURATION), "--no-step-log"]
            if kind == "sumo":
                cmd = ["sumo"] + common
            else:
                cmd = [lpsim, "run" if kind == "lpsim" else "cosim"] + common + ["--no-warnings"]
                if kind == "cosim":
                    cmd += ["--corridor", corridor]
            done = subprocess.run(cmd, cwd=k, env=env, capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit("%s at %d veh/h failed: %s" % (kind, rate, done.stderr[-500:]))
            results[kind] = (os.path.join(k, "periods.xml"), done.stdout)
        wait = re.search(r"Longest wait at the boundary: ([0-9.]+)", results["cosim"][1])
        rows.append("| %d | %.0f | %.0f | %.0f | %.0f | %s |" % (
            rate, per_hour(counts(results["sumo"][0], "CD", "entered")),
            per_hour(counts(results["lpsim"][0], "CD", "entered")),
            per_hour(counts(results["cosim"][0], "BC", "departed")),
            per_hour(counts(results["cosim"][0], "CD", "entered")), wait.group(1) if wait else "-"))
    print("\n".join(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

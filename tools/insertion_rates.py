#!/usr/bin/env python3
"""Insertion rates on a generated motorway near capacity, SUMO against LPSim.

Builds a 3-lane, 33.33 m/s motorway (2.5 km main line, a 1-lane on-ramp joining after 1.5 km) with
netconvert from plain XML, and flows of IDM cars at a demand near capacity on the main line and the ramp.
For each depart setting (departLane / departPos / departSpeed as real scenarios use them) it runs SUMO and
LPSim on the same files and prints the vehicles inserted per hour on each lane of the two entry edges,
LPSim against SUMO, and the vehicles still waiting to be inserted at the end of the demand.

usage: insertion_rates.py --lpsim build/lpsim [--hours 1] [--main-vph 6300] [--ramp-vph 600]
                          [--settings best/base/max,free/free/desired] [--out DIR] [--keep]
"""
import argparse
import collections
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

# departLane/departPos/departSpeed combinations of real scenarios (SUMO's own defaults: first/base/0).
DEFAULT_SETTINGS = [
    "best/base/max",
    "free/base/desired",
    "random/free/avg",
    "first/base/0",
    "best/last/max",
    "best/free/desired",
]

NODES = """<nodes>
  <node id="n0" x="0" y="0"/>
  <node id="n1" x="1500" y="0" type="priority"/>
  <node id="n2" x="2500" y="0"/>
  <node id="r0" x="1200" y="-150"/>
</nodes>
"""
EDGES = """<edges>
  <edge id="main_in" from="n0" to="n1" numLanes="3" speed="33.33" priority="10"/>
  <edge id="ramp" from="r0" to="n1" numLanes="1" speed="22.22" priority="5"/>
  <edge id="main_out" from="n1" to="n2" numLanes="3" speed="33.33" priority="10"/>
</edges>
"""


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def build_network(work):
    write(os.path.join(work, "motorway.nod.xml"), NODES)
    write(os.path.join(work, "motorway.edg.xml"), EDGES)
    subprocess.run(["netconvert", "--node-files", "motorway.nod.xml", "--edge-files", "motorway.edg.xml",
                    "--no-turnarounds", "true", "-o", "motorway.net.xml"],
                   cwd=work, check=True, stdout=subprocess.DEVNULL)


def write_scenario(work, name, setting, args):
    lane, pos, speed = setting.split("/")
    end = int(args.hours * 3600)
    attrs = 'departLane="%s" departPos="%s" departSpeed="%s"' % (lane, pos, speed)
    routes = """<routes>
  <vType id="car" carFollowModel="IDM" length="5" minGap="2.5" accel="2.6" decel="4.5" maxSpeed="40"/>
  <flow id="main" type="car" from="main_in" to="main_out" begin="0" end="%d" vehsPerHour="%g" %s/>
  <flow id="ramp" type="car" from="ramp" to="main_out" begin="0" end="%d" vehsPerHour="%g" %s/>
</routes>
""" % (end, args.main_vph, attrs, end, args.ramp_vph, attrs)
    write(os.path.join(work, name + ".rou.xml"), routes)
    cfg = """<configuration>
  <input><net-file value="motorway.net.xml"/><route-files value="%s.rou.xml"/></input>
  <time><begin value="0"/><end value="%d"/></time>
</configuration>
""" % (name, end + 600)
    path = os.path.join(work, name + ".sumocfg")
    write(path, cfg)
    return path, end


def summary_at(path, time):
    """(inserted, waiting) of the summary row at `time` (the last row before it when there is none)."""
    best = (0, 0)
    for _, el in ET.iterparse(path):
        if el.tag == "step":
            if float(el.get("time")) > time + 1e-6:
                break
            best = (int(el.get("inserted")), int(el.get("waiting")))
    return best


def per_lane(tripinfo, until):
    counts = collections.Counter()
    for _, el in ET.iterparse(tripinfo):
        if el.tag == "tripinfo" and float(el.get("depart")) <= until:
            counts[el.get("departLane")] += 1
        el.clear()
    return counts


def run(cmd, cwd):
    res = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if res.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (res.returncode, " ".join(cmd), res.stderr[-2000:]))


def simulate(work, name, cfg, lpsim, reuse_sumo):
    out = {}
    for who in ("sumo", "lpsim"):
        trip = os.path.join(work, "%s.%s.tripinfo.xml" % (name, who))
        summ = os.path.join(work, "%s.%s.summary.xml" % (name, who))
        out[who] = (trip, summ)
        if who == "sumo" and reuse_sumo and os.path.exists(summ):
            continue
        if who == "sumo":
            cmd = ["sumo", "-c", cfg, "--tripinfo-output", trip, "--summary-output", summ, "--no-step-log",
                   "--no-warnings", "--seed", "42"]
        else:
            cmd = [lpsim, "run", "-c", cfg, "--tripinfo-output", trip, "--summary-output", summ,
                   "--no-step-log", "--no-warnings", "--seed", "42", "--threads", "1"]
        run(cmd, work)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lpsim", required=True)
    ap.add_argument("--hours", type=float, default=1.0)
    ap.add_argument("--main-vph", type=float, default=6300.0, help="main line demand, veh/h (all lanes)")
    ap.add_argument("--ramp-vph", type=float, default=600.0)
    ap.add_argument("--settings", default=",".join(DEFAULT_SETTINGS),
                    help="comma-separated departLane/departPos/departSpeed")
    ap.add_argument("--out", default=None, help="work folder (default: a temporary one, removed)")
    ap.add_argument("--keep", action="store_true")
    ap.add_argument("--reuse-sumo", action="store_true", help="with --out: keep SUMO's outputs of an earlier run")
    args = ap.parse_args(argv)
    lpsim = os.path.abspath(args.lpsim)
    work = args.out or tempfile.mkdtemp(prefix="lpsim_insert_")
    os.makedirs(work, exist_ok=True)
    build_network(work)
    lanes = ["main_in_0", "main_in_1", "main_in_2", "ramp_0"]
    print("| setting (lane/pos/speed) | lane | SUMO veh/h | LPSim veh/h | diff % |")
    print("|---|---|---:|---:|---:|")
    waits = []
    worst = 0.0
    for i, setting in enumerate(args.settings.split(",")):
        name = "s%d" % i
        cfg, end = write_scenario(work, name, setting, args)
        files = simulate(work, name, cfg, lpsim, args.reuse_sumo)
        counts = {w: per_lane(files[w][0], end) for w in files}
        for lane in lanes + ["all"]:
            s = sum(counts["sumo"].values()) if lane == "all" else counts["sumo"][lane]
            l = sum(counts["lpsim"].values()) if lane == "all" else counts["lpsim"][lane]
            diff = 100.0 * (l - s) / s if s else (0.0 if l == 0 else float("inf"))
            if lane != "all" and s >= 50:
                worst = max(worst, abs(diff))
            print("| %s | %s | %.0f | %.0f | %+.1f |" % (setting, lane, s / args.hours, l / args.hours, diff))
        waits.append((setting, summary_at(files["sumo"][1], end), summary_at(files["lpsim"][1], end)))
    print()
    print("| setting | SUMO inserted | LPSim inserted | SUMO waiting at %ds | LPSim waiting |" % end)
    print("|---|---:|---:|---:|---:|")
    for setting, s, l in waits:
        print("| %s | %d | %d | %d | %d |" % (setting, s[0], l[0], s[1], l[1]))
    print("\nlargest per-lane difference (lanes with >= 50 insertions): %.1f %%" % worst)
    if not args.out and not args.keep:
        shutil.rmtree(work)
    elif args.keep:
        print("files in", work)


if __name__ == "__main__":
    main()

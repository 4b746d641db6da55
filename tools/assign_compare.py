#!/usr/bin/python3
"""`lpsim assign` against SUMO's duaIterate.py on the same demand: the relative gap of each duaIterate
iteration (computed by `lpsim assign --weight-files` on that iteration's routes and edgeData dump, the formula
`lpsim assign` prints), its CPU time, the CPU time `lpsim assign` takes to reach duaIterate's last gap, and the
per-edge flows of the two final assignments (vehicles entering or departing on each edge: duaIterate's last
dump against `lpsim run` of lpsim's final routes; Pearson r). Standard library only.

  tools/assign_compare.py --dua-dir DIR --net NET --demand TRIPS [--begin B] [--end E] [--lpsim build/lpsim]
                          [--out DIR] [--threads 1] [--max-iterations 50] [--extra "lpsim options"]

DIR is where duaIterate.py ran with one demand file (its NNN/ folders with the routes its sumo ran and
dump_<aggregation>.xml, and time.log from `/usr/bin/time -v` around it for its CPU time); TRIPS the trips or
flows file `lpsim assign` starts from (the one duaIterate was given with -t, or an equivalent).
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validation import metrics  # noqa: E402


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--dua-dir", required=True)
    p.add_argument("--net", required=True)
    p.add_argument("--demand", required=True)
    p.add_argument("--begin", default="0")
    p.add_argument("--end", default=None)
    p.add_argument("--lpsim", default=os.path.join(os.path.dirname(__file__), "..", "build", "lpsim"))
    p.add_argument("--out", default="assign_compare")
    p.add_argument("--threads", default="1")
    p.add_argument("--max-iterations", default="50")
    p.add_argument("--extra", default="", help="further lpsim options (e.g. --ignore-route-errors)")
    return p.parse_args()


def span(args):
    s = ["-b", args.begin]
    if args.end is not None:
        s += ["-e", args.end]
    return s


def edge_flows(dump):
    """Vehicles entering or departing on each edge, summed over a meandata file's intervals."""
    flows = {}
    for _, el in ET.iterparse(dump):
        if el.tag == "edge":
            flows[el.get("id")] = flows.get(el.get("id"), 0) + float(el.get("entered", 0)) + \
                float(el.get("departed", 0))
        el.clear()
    return flows


def cpu_of_time_log(path):
    text = open(path).read()
    user = float(re.search(r"User time \(seconds\): ([0-9.]+)", text).group(1))
    system = float(re.search(r"System time \(seconds\): ([0-9.]+)", text).group(1))
    return user + system


def timed(cmd, cwd):
    """Runs cmd under GNU time; returns (stdout, CPU seconds)."""
    r = subprocess.run(["/usr/bin/time", "-f", "CPU %U %S"] + cmd, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stderr[-2000:]))
    user, system = re.findall(r"CPU ([0-9.]+) ([0-9.]+)", r.stderr)[-1]
    return r.stdout, float(user) + float(system)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    lpsim = os.path.abspath(args.lpsim)
    extra = args.extra.split()
    iterations = sorted(d for d in os.listdir(args.dua_dir) if re.fullmatch(r"[0-9]{3}", d))
    dua_gaps = []
    for it in iterations:
        folder = os.path.join(args.dua_dir, it)
        routes = glob.glob(os.path.join(folder, "*_%s.rou.xml" % it))  # what its sumo simulated
        dumps = glob.glob(os.path.join(folder, "dump_*.xml"))
        if len(routes) != 1 or not dumps:
            continue
        routes = routes[0]
        out, _ = timed([lpsim, "assign", "-n", args.net, "-r", routes, "--weight-files", dumps[0],
                        "--threads", args.threads] + span(args) + extra, args.out)
        gap = float(re.search(r"relative gap ([-0-9.e]+)", out).group(1))
        dua_gaps.append((int(it), gap, dumps[0]))
        print("duaIterate %s: relative gap %.6f" % (it, gap), flush=True)
    dua_cpu = cpu_of_time_log(os.path.join(args.dua_dir, "time.log"))
    target = dua_gaps[-1][1]

    out, lpsim_cpu = timed([lpsim, "assign", "-n", args.net, "-r", os.path.abspath(args.demand), "-o",
                            "assigned.rou.xml", "--gap", repr(target), "--iterations", args.max_iterations,
                            "--threads", args.threads] + span(args) + extra, args.out)
    print(out)
    lines = [l.split() for l in out.splitlines() if re.match(r"\s*[0-9]+\s", l)]
    with open(os.path.join(args.out, "dump.add.xml"), "w") as f:
        f.write('<additional><edgeData id="flows" file="flows.xml"/></additional>\n')
    timed([lpsim, "run", "-n", args.net, "-r", "assigned.rou.xml", "-a", "dump.add.xml", "--no-step-log",
           "--threads", args.threads] + span(args) + extra, args.out)
    dua_flows = edge_flows(dua_gaps[-1][2])
    lpsim_flows = edge_flows(os.path.join(args.out, "flows.xml"))
    edges = sorted(set(dua_flows) | set(lpsim_flows))
    r = metrics.pearson([dua_flows.get(e, 0) for e in edges], [lpsim_flows.get(e, 0) for e in edges])
    best_dua = min(g for _, g, _ in dua_gaps)
    print("| | iterations | last relative gap | lowest | CPU s |")
    print("|---|---:|---:|---:|---:|")
    print("| duaIterate.py | %d | %.4f | %.4f | %.1f |" % (len(dua_gaps), target, best_dua, dua_cpu))
    print("| lpsim assign to that gap | %d | %s | | %.2f |" % (len(lines), lines[-1][1] if lines else "-", lpsim_cpu))
    print("CPU ratio %.0fx; per-edge flows of the final assignments r = %.3f over %d edges" %
          (dua_cpu / lpsim_cpu, r, len(edges)))


if __name__ == "__main__":
    main()

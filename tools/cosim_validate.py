#!/usr/bin/python3
"""Co-simulation against SUMO alone and LPSim alone on the same SUMO scenarios: arrivals, mean trip duration,
the corridor edges' mean speeds (Pearson r against SUMO alone), CPU time, and the hand-overs' cost in process
(libsumo) and over TraCI. Standard library and SUMO's sumolib only: run with /usr/bin/python3.

  tools/cosim_validate.py SCENARIO.sumocfg... [--lpsim build/lpsim] [--out DIR] [--corridor-share 0.2]
                          [--end T] [--markdown FILE] [--no-traci]

The corridor is chosen from the network alone: the normal edges whose midpoints lie nearest the middle of
the network's bounding box, --corridor-share of them (a compact district, as a modeller would select in
sumo-gui), closed over their junctions as `lpsim cosim` closes it (every road into a junction they lead
to). It is written as DIR/<name>/corridor.txt (a sumo-gui selection file) and the share of SUMO alone's
vehicle-seconds on it is reported. Every run happens in its own mirror of the scenario folder
(tools/validation/runner.py). Prints a markdown table and writes DIR/results.json.
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.append(os.path.join(os.environ.get("SUMO_HOME", "/usr/share/sumo"), "tools"))

from validation import metrics, parsers, runner  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("configs", nargs="+", metavar="SCENARIO_CFG")
    p.add_argument("--lpsim", default="build/lpsim")
    p.add_argument("--sumo", default="sumo")
    p.add_argument("--out", default="build/cosim_validation")
    p.add_argument("--end", type=float, default=None, help="end of every run (default: the cfg's)")
    p.add_argument("--corridor-share", type=float, default=0.2, help="share of the normal edges (default 0.2)")
    p.add_argument("--markdown", default=None)
    p.add_argument("--no-traci", action="store_true", help="skip the run over TraCI")
    p.add_argument("--timeout", type=float, default=3600)
    return p.parse_args(argv)


def choose_corridor(net_file, share):
    """The normal edges (with a lane cars may use) nearest the bounding box's middle, `share` of them."""
    import sumolib  # SUMO's tools

    net = sumolib.net.readNet(net_file, withInternal=False)
    (x0, y0), (x1, y1) = net.getBBoxXY()
    cx, cy = (x0 + x1) / 2.0, (y0 + y1) / 2.0
    edges = [e for e in net.getEdges() if e.getFunction() == "" and e.allows("passenger")]

    def distance(edge):
        shape = edge.getShape()
        mx, my = shape[len(shape) // 2]
        return (mx - cx) ** 2 + (my - cy) ** 2

    edges.sort(key=lambda e: (distance(e), e.getID()))
    count = max(1, int(round(share * len(edges))))
    chosen = edges[:count]
    # Closed over its junctions, as lpsim cosim takes it: every road into a junction a chosen road leads to.
    junctions = {e.getToNode().getID() for e in chosen}
    closed = {e.getID() for e in chosen} | {e.getID() for e in edges if e.getToNode().getID() in junctions}
    return sorted(closed), len(edges)


def cfg_net_file(cfg):
    config = parsers.read_sumocfg(cfg)
    net = config["options"].get("net-file") or config["options"].get("net")
    return net if os.path.isabs(net) else os.path.join(os.path.dirname(os.path.abspath(cfg)), net)


def cosim_report(stdout_file):
    """The numbers of lpsim cosim's end-of-run report."""
    text = open(stdout_file, errors="replace").read()

    def number(label):
        m = re.search(re.escape(label) + r"\s*([0-9.eE+-]+)", text)
        return float(m.group(1)) if m else None

    return {
        "into_sumo": number("Handed into SUMO:"),
        "out_of_sumo": number("Taken back from SUMO:"),
        "arrived_in_sumo": number("Arrived in SUMO:"),
        "longest_wait_s": number("Longest wait at the boundary:"),
        "in_handover_at_end": number("In hand-over at the end:"),
        "sumo_step_s": number("Wall time: SUMO's steps"),
        "handover_s": number("s, hand-overs"),
        "steps": number("Steps:") if False else None,
    }


def steps_of(stdout_file):
    m = re.search(r"Simulation ended at time: ([0-9.]+)", open(stdout_file, errors="replace").read())
    return float(m.group(1)) if m else None


def run_one(name, kind, command, run_dir, env, timeout):
    files = runner.output_files(run_dir, with_statistics=(kind == "sumo"))
    result = runner.RunResult(name, command(files), run_dir, files)
    runner.run_timed(result, env=env, timeout=timeout)
    return result


def main(argv):
    args = parse_args(argv)
    lpsim = os.path.abspath(args.lpsim)
    env = runner.sumo_env(None)
    entries = []
    for cfg in args.configs:
        cfg = os.path.abspath(cfg)
        name = os.path.basename(os.path.dirname(cfg))
        base = os.path.join(os.path.abspath(args.out), name)
        config = parsers.read_sumocfg(cfg)
        end = args.end if args.end is not None else config.get("end")
        step = config.get("step_length") or 1.0
        corridor, normal_edges = choose_corridor(cfg_net_file(cfg), args.corridor_share)
        os.makedirs(base, exist_ok=True)
        corridor_file = os.path.join(base, "corridor.txt")
        with open(corridor_file, "w") as handle:
            handle.writelines("edge:%s\n" % e for e in corridor)
        entry = {"scenario": name, "cfg": cfg, "corridor_edges": len(corridor), "normal_edges": normal_edges,
                 "runs": {}}
        runs = {}
        for kind in ("sumo", "lpsim", "cosim", "cosim_traci"):
            if kind == "cosim_traci" and args.no_traci:
                continue
            run_dir = os.path.join(base, kind)
            runner.mirror_folder(os.path.dirname(cfg), run_dir)
            run_cfg = os.path.join(run_dir, os.path.basename(cfg))
            time_options = ["--seed", "23423", "--step-length", runner._number(step)]
            if end is not None:
                time_options += ["--end", runner._number(end)]
            if kind == "sumo":
                def command(files, run_cfg=run_cfg, run_dir=run_dir):
                    runner.write_edgedata_additional(files["edgedata_add"], files["edgedata"])
                    additional = runner.cfg_additional_files(config, run_cfg)
                    return runner.sumo_command(args.sumo, run_cfg, files, "Krauss", end, step, 23423, additional)
            else:
                def command(files, run_cfg=run_cfg, kind=kind):
                    c = [lpsim, "run" if kind == "lpsim" else "cosim", "-c", run_cfg, "--tripinfo-output",
                         files["tripinfo"], "--edgedata-output", files["edgedata"], "--no-step-log",
                         "--no-warnings", "--threads", "1"] + time_options
                    if kind != "lpsim":
                        c += ["--corridor", corridor_file]
                    if kind == "cosim_traci":
                        c += ["--sumo-binary", args.sumo]
                    return c
            result = run_one(name, kind, command, run_dir, env, args.timeout)
            entry["runs"][kind] = result.to_json()
            if result.error:
                print("%s %s: %s" % (name, kind, result.error), file=sys.stderr)
                continue
            runs[kind] = {"trips": parsers.parse_tripinfo(result.files["tripinfo"]),
                          "edges": parsers.parse_edgedata(result.files["edgedata"]),
                          "cpu_s": result.cpu_s, "wall_s": result.wall_s, "stdout": result.files["stdout"]}
        sumo = runs.get("sumo")
        if sumo is None:
            entries.append(entry)
            continue
        total = sum(s.sampled_seconds for s in sumo["edges"].values())
        on_corridor = sum(sumo["edges"][e].sampled_seconds for e in corridor if e in sumo["edges"])
        entry["corridor_vehicle_seconds_share"] = on_corridor / total if total > 0 else None
        entry["sumo"] = {"arrived": len(sumo["trips"].durations), "mean_duration": metrics.mean(sumo["trips"].durations),
                         "cpu_s": sumo["cpu_s"]}
        for kind in ("lpsim", "cosim", "cosim_traci"):
            run = runs.get(kind)
            if run is None:
                continue
            arrived = len(run["trips"].durations)
            mean_duration = metrics.mean(run["trips"].durations)
            corridor_set = set(corridor)
            r = metrics.edge_speed_correlation({e: s for e, s in sumo["edges"].items() if e in corridor_set},
                                               {e: s for e, s in run["edges"].items() if e in corridor_set})
            out = {"arrived": arrived, "mean_duration": mean_duration,
                   "arrived_vs_sumo": metrics.relative_difference(arrived, entry["sumo"]["arrived"]),
                   "duration_vs_sumo": metrics.relative_difference(mean_duration, entry["sumo"]["mean_duration"]),
                   "corridor_speed_r": r["r"], "corridor_edges_compared": r["edges"],
                   "cpu_s": run["cpu_s"], "cpu_vs_sumo": run["cpu_s"] / sumo["cpu_s"] if sumo["cpu_s"] else None}
            if kind != "lpsim":
                rep = cosim_report(run["stdout"])
                steps = (steps_of(run["stdout"]) or 0) / step
                handed = (rep["into_sumo"] or 0) + (rep["out_of_sumo"] or 0)
                rep["handover_us_per_vehicle"] = 1e6 * rep["handover_s"] / handed if handed and rep["handover_s"] is not None else None
                rep["handover_us_per_step"] = 1e6 * rep["handover_s"] / steps if steps and rep["handover_s"] is not None else None
                out["report"] = rep
            entry[kind] = out
        entries.append(entry)
    os.makedirs(os.path.abspath(args.out), exist_ok=True)
    with open(os.path.join(os.path.abspath(args.out), "results.json"), "w") as handle:
        json.dump(entries, handle, indent=1, default=str)
    table = markdown(entries)
    print(table)
    if args.markdown:
        with open(args.markdown, "w") as handle:
            handle.write(table)
    return 0


def fmt(x, digits=1, pct=False):
    if x is None:
        return "-"
    return ("%+.1f %%" % (100 * x)) if pct else ("%.*f" % (digits, x))


def markdown(entries):
    rows = ["| scenario | corridor edges (share of veh-s in SUMO) | arrived SUMO / LPSim / co-sim | mean duration s "
            "SUMO / LPSim / co-sim (co-sim vs SUMO) | corridor speed r LPSim / co-sim | CPU s SUMO / LPSim / "
            "co-sim (co-sim / SUMO) | hand-overs in / out / arrived in SUMO | hand-over µs per vehicle "
            "libsumo / TraCI | per step libsumo / TraCI |",
            "|---|---|---|---|---|---|---|---|---|"]
    for e in entries:
        s, l, c, t = e.get("sumo"), e.get("lpsim"), e.get("cosim"), e.get("cosim_traci")
        if s is None or c is None:
            rows.append("| %s | failed: see results.json |||||||" % e["scenario"])
            continue
        rep = c["report"]
        rows.append("| %s | %d of %d (%s) | %d / %s / %d | %s / %s / %s (%s) | %s / %s | %s / %s / %s (%.2f×) | "
                    "%s / %s / %s | %s / %s | %s / %s |" % (
                        e["scenario"], e["corridor_edges"], e["normal_edges"],
                        fmt(e["corridor_vehicle_seconds_share"], pct=False, digits=2),
                        s["arrived"], l["arrived"] if l else "-", c["arrived"],
                        fmt(s["mean_duration"]), fmt(l["mean_duration"]) if l else "-", fmt(c["mean_duration"]),
                        fmt(c["duration_vs_sumo"], pct=True),
                        fmt(l["corridor_speed_r"], 2) if l else "-", fmt(c["corridor_speed_r"], 2),
                        fmt(s["cpu_s"], 2), fmt(l["cpu_s"], 2) if l else "-", fmt(c["cpu_s"], 2), c["cpu_vs_sumo"],
                        fmt(rep["into_sumo"], 0), fmt(rep["out_of_sumo"], 0), fmt(rep["arrived_in_sumo"], 0),
                        fmt(rep["handover_us_per_vehicle"], 0),
                        fmt(t["report"]["handover_us_per_vehicle"], 0) if t else "-",
                        fmt(rep["handover_us_per_step"], 0),
                        fmt(t["report"]["handover_us_per_step"], 0) if t else "-"))
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

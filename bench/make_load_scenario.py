#!/usr/bin/python3
"""Generate the load benchmark scenario: a large signalised grid plus >= 1M vehicles with inline routes.

The output (net.xml, routes.rou.xml, load.sumocfg) is deterministic for a given set of options,
so SUMO and LPSim load byte-identical inputs on every machine.

Routes are random walks over the edge-to-edge connections of the generated net (no turnarounds,
no edge visited twice), so every route is connected and SUMO accepts it as is.
"""

import argparse
import os
import random
import re
import subprocess
import sys
import time

# netconvert/netgenerate write one element per line; scanning lines with a regex is ~20x faster
# than a full XML parse of a 400 MB net, and we only need the <connection> elements.
ATTRIBUTE = re.compile(r'([\w:]+)="([^"]*)"')


def log(message):
    print("[make_load_scenario] " + message, file=sys.stderr, flush=True)


def parse_args():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default=os.path.join(here, "work", "load"),
                        help="output folder (default bench/work/load)")
    parser.add_argument("--grid", type=int, default=160,
                        help="junctions per grid side (160 -> 101,760 edges)")
    parser.add_argument("--grid-length", type=float, default=200.0, help="edge length in metres")
    parser.add_argument("--lanes", type=int, default=2, help="lanes per edge")
    parser.add_argument("--vehicles", type=int, default=1000000, help="number of vehicles")
    parser.add_argument("--duration", type=float, default=3600.0,
                        help="departures are spread over [0, duration) seconds")
    parser.add_argument("--min-edges", type=int, default=10, help="shortest route, in edges")
    parser.add_argument("--max-edges", type=int, default=40, help="longest route, in edges")
    parser.add_argument("--seed", type=int, default=42, help="random seed (routes and departures)")
    parser.add_argument("--force", action="store_true", help="regenerate even if outputs exist")
    args = parser.parse_args()
    if args.grid < 2:
        parser.error("--grid must be >= 2")
    if not 1 <= args.min_edges <= args.max_edges:
        parser.error("need 1 <= --min-edges <= --max-edges")
    if args.vehicles < 1 or args.duration <= 0:
        parser.error("--vehicles and --duration must be positive")
    return args


def build_net(args, net_path):
    command = [
        "netgenerate", "--grid",
        "--grid.number", str(args.grid),
        "--grid.length", str(args.grid_length),
        "--default.lanenumber", str(args.lanes),
        "--default-junction-type", "traffic_light",
        "--no-internal-links", "false",
        "--seed", str(args.seed),
        "--output-file", net_path,
    ]
    log("running: " + " ".join(command))
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)


def read_successors(net_path):
    """Return (edge ids, successor index lists) over normal edges, turnarounds excluded."""
    index_of = {}
    edge_ids = []
    successors = []

    def index(edge_id):
        found = index_of.get(edge_id)
        if found is None:
            found = len(edge_ids)
            index_of[edge_id] = found
            edge_ids.append(edge_id)
            successors.append([])
        return found

    with open(net_path, encoding="utf-8") as net:
        for line in net:
            if "<connection " not in line:
                continue
            attributes = dict(ATTRIBUTE.findall(line))
            source = attributes["from"]
            if source.startswith(":") or attributes.get("dir") == "t":
                continue  # internal lanes and U-turns are not route steps
            source_index = index(source)
            target_index = index(attributes["to"])
            # One connection per lane pair: keep each edge successor once.
            if target_index not in successors[source_index]:
                successors[source_index].append(target_index)
    return edge_ids, successors


def random_walk(rng, successors, start_edges, min_edges, max_edges):
    """A connected route of min..max edges that never repeats an edge."""
    while True:
        wanted = rng.randint(min_edges, max_edges)
        current = rng.choice(start_edges)
        route = [current]
        visited = {current}
        while len(route) < wanted:
            options = [e for e in successors[current] if e not in visited]
            if not options:
                break
            current = rng.choice(options)
            route.append(current)
            visited.add(current)
        if len(route) >= min_edges:
            return route


def write_routes(args, routes_path, edge_ids, successors):
    rng = random.Random(args.seed)
    start_edges = [e for e in range(len(edge_ids)) if successors[e]]
    if not start_edges:
        raise SystemExit("net has no edge with a successor: cannot build routes")
    # Centiseconds keep departures exact in text and sortable as integers.
    limit = int(round(args.duration * 100))
    departs = sorted(rng.randrange(limit) for _ in range(args.vehicles))
    tmp_path = routes_path + ".tmp"
    with open(tmp_path, "w", encoding="utf-8") as out:
        out.write("<routes>\n")
        chunk = []
        for number, depart in enumerate(departs):
            route = random_walk(rng, successors, start_edges, args.min_edges, args.max_edges)
            chunk.append('    <vehicle id="v%d" depart="%d.%02d"><route edges="%s"/></vehicle>\n'
                         % (number, depart // 100, depart % 100,
                            " ".join(edge_ids[e] for e in route)))
            if len(chunk) == 10000:
                out.write("".join(chunk))
                chunk.clear()
                if (number + 1) % 100000 == 0:
                    log("  %d vehicles written" % (number + 1))
        out.write("".join(chunk))
        out.write("</routes>\n")
    os.replace(tmp_path, routes_path)


def write_config(args, config_path):
    with open(config_path, "w", encoding="utf-8") as out:
        out.write('<configuration>\n'
                  '    <input>\n'
                  '        <net-file value="net.xml"/>\n'
                  '        <route-files value="routes.rou.xml"/>\n'
                  '    </input>\n'
                  '    <time>\n'
                  '        <begin value="0"/>\n'
                  '        <end value="%g"/>\n'
                  '    </time>\n'
                  '</configuration>\n' % args.duration)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    net_path = os.path.join(args.out, "net.xml")
    routes_path = os.path.join(args.out, "routes.rou.xml")
    config_path = os.path.join(args.out, "load.sumocfg")
    # The options are recorded so that a later run with different ones regenerates.
    stamp_path = os.path.join(args.out, "options.txt")
    stamp = repr(sorted((k, v) for k, v in vars(args).items() if k not in ("force", "out")))
    previous = open(stamp_path, encoding="utf-8").read() if os.path.exists(stamp_path) else None
    complete = all(os.path.exists(p) for p in (net_path, routes_path, config_path))
    if complete and previous == stamp and not args.force:
        log("inputs exist in %s (use --force to regenerate)" % args.out)
        return
    if os.path.exists(stamp_path):
        os.remove(stamp_path)

    started = time.monotonic()
    build_net(args, net_path)
    log("netgenerate: %.1f s" % (time.monotonic() - started))

    step = time.monotonic()
    edge_ids, successors = read_successors(net_path)
    log("read %d edges with %d successor links: %.1f s"
        % (len(edge_ids), sum(len(s) for s in successors), time.monotonic() - step))

    step = time.monotonic()
    write_routes(args, routes_path, edge_ids, successors)
    log("wrote %d vehicles: %.1f s" % (args.vehicles, time.monotonic() - step))

    write_config(args, config_path)
    with open(stamp_path, "w", encoding="utf-8") as out:
        out.write(stamp)
    log("done in %.1f s: %s" % (time.monotonic() - started, args.out))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Regional-scale LPSim scenario: the real Bay Area tertiary network tiled into a larger region, plus an
OD demand of 1M-10M trips over 12 hours, in the original LPSim CSV format (nodes.csv, edges.csv, od.csv).

Network: `--tiles` shifted copies of ../shared/lpsim_bayarea_tertiary laid out on a grid (8 tiles: 4 x 2,
248,968 nodes, ~529k edges). Neighbouring tiles are stitched by `--bridges` two-way freeway links (3 lanes,
65 mph) between the copies' facing borders. Bridge ends and zones lie in the base network's largest strongly
connected component, so every zone can reach every other one.

Demand: zones are TAZ-like centroids, one per occupied cell of a `--zone-grid` square grid over each tile (the
SCC node nearest the cell centre), weighted by the number of nodes in the cell. Trips leave a zone drawn by
weight; the destination is one of the origin's 8 nearest zones in the same tile (local, 75 %), any zone of the
same tile (15 %), a zone of a neighbouring tile (7 %) or any zone (3 %). Departures over `--hours`: 35 % in
a morning peak (mean 2 h, sd 0.75 h), 40 % in an evening peak (mean 10.5 h, sd 1 h), 25 % uniform. Zones
bound the number of distinct origins (one shortest-path tree each when LPSim routes the trips).

OD origin/destination are dense node indices (nodes.csv row order), as LPSim's CSV reader expects. Output is
deterministic for given options (no hashing of strings, one seeded random.Random), so the same seed gives the
same bytes on every machine.
"""

import argparse
import bisect
import csv
import math
import os
import random
import sys
import time

EARTH_RADIUS = 6371008.8
BRIDGE_LANES = 3
BRIDGE_SPEED_MPH = 65
TILE_GAP_DEG = 0.02  # gap between neighbouring copies (about 2 km)
NEAREST_ZONES = 8


def log(message):
    print("[make_regional_scenario] " + message, file=sys.stderr, flush=True)


def parse_args():
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    # ../shared beside the repository; a git worktree one level deeper finds it one more level up.
    candidates = [os.path.join(repo, up, "shared", "lpsim_bayarea_tertiary") for up in ("..", os.path.join("..", ".."))]
    default_base = next((c for c in candidates if os.path.isdir(c)), candidates[0])
    p.add_argument("--bayarea", default=default_base,
                   help="folder with the base nodes.csv and edges.csv (default ../shared/lpsim_bayarea_tertiary)")
    p.add_argument("--out", help="output folder (default bench/work/regional/<trips>)")
    p.add_argument("--trips", type=int, default=1000000, help="number of trips (default 1,000,000)")
    p.add_argument("--seed", type=int, default=42)
    p.add_argument("--hours", type=float, default=12.0, help="departures over [0, hours * 3600) s")
    p.add_argument("--tiles", type=int, default=8, help="copies of the base network (default 8: 4 x 2)")
    p.add_argument("--bridges", type=int, default=24, help="two-way links between two neighbouring tiles")
    p.add_argument("--zone-grid", type=int, default=16, help="zones: occupied cells of an N x N grid per tile")
    p.add_argument("--scale", type=float, default=1.0,
                   help="keep only the base nodes in this central fraction of the base's width and height "
                        "(small test scenarios; 1 = the whole network)")
    a = p.parse_args()
    if a.trips < 1 or a.tiles < 1 or a.bridges < 1 or a.zone_grid < 1 or a.hours <= 0:
        p.error("--trips, --tiles, --bridges, --zone-grid and --hours must be positive")
    if not 0 < a.scale <= 1:
        p.error("--scale must be in (0, 1]")
    if a.out is None:
        a.out = os.path.join(repo, "bench", "work", "regional", str(a.trips))
    return a


def read_base(folder, scale):
    """Base nodes (osmid -> dense index, x, y, highway) and edges (u, v, length, lanes, speed_mph)."""
    with open(os.path.join(folder, "nodes.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    xs = [float(r["x"]) for r in rows]
    ys = [float(r["y"]) for r in rows]
    keep = [True] * len(rows)
    if scale < 1:
        cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
        hw, hh = (max(xs) - min(xs)) * scale / 2, (max(ys) - min(ys)) * scale / 2
        keep = [abs(x - cx) <= hw and abs(y - cy) <= hh for x, y in zip(xs, ys)]
    index, nodes = {}, []
    for r, x, y, k in zip(rows, xs, ys, keep):
        if k:
            index[r["osmid"].strip()] = len(nodes)
            nodes.append((x, y, (r.get("highway") or "").strip()))
    edges = []
    with open(os.path.join(folder, "edges.csv"), newline="") as f:
        reader = csv.DictReader(f)
        u_col, v_col = ("osmid_u", "osmid_v") if "osmid_u" in reader.fieldnames else ("u", "v")
        for r in reader:
            u, v = index.get(r[u_col].strip()), index.get(r[v_col].strip())
            if u is None or v is None:
                continue
            edges.append((u, v, r["length"].strip(), r["lanes"].strip(), r["speed_mph"].strip()))
    return nodes, edges


def largest_scc(n, edges):
    """Membership flags of the largest strongly connected component (iterative Kosaraju)."""
    succ = [[] for _ in range(n)]
    pred = [[] for _ in range(n)]
    for u, v, *_ in edges:
        succ[u].append(v)
        pred[v].append(u)
    seen = [False] * n
    order = []
    for s in range(n):
        if seen[s]:
            continue
        seen[s] = True
        stack = [(s, 0)]
        while stack:
            node, i = stack[-1]
            if i < len(succ[node]):
                stack[-1] = (node, i + 1)
                w = succ[node][i]
                if not seen[w]:
                    seen[w] = True
                    stack.append((w, 0))
            else:
                stack.pop()
                order.append(node)
    comp = [-1] * n
    sizes = []
    for s in reversed(order):
        if comp[s] >= 0:
            continue
        c = len(sizes)
        comp[s] = c
        stack, size = [s], 0
        while stack:
            node = stack.pop()
            size += 1
            for w in pred[node]:
                if comp[w] < 0:
                    comp[w] = c
                    stack.append(w)
        sizes.append(size)
    best = max(range(len(sizes)), key=lambda c: (sizes[c], -c))
    return [c == best for c in comp]


def metres(x0, y0, x1, y1):
    """Equirectangular distance between two lon/lat points (as LPSim's reader projects them)."""
    lat = math.radians((y0 + y1) / 2)
    return EARTH_RADIUS * math.hypot(math.radians(x1 - x0) * math.cos(lat), math.radians(y1 - y0))


def tile_layout(tiles):
    rows = max(1, int(math.sqrt(tiles)))
    cols = -(-tiles // rows)
    return [(k % cols, k // cols) for k in range(tiles)], cols


def border_nodes(nodes, in_scc, side, bands):
    """Per band along the border, the SCC node furthest towards `side` (east/west/north/south)."""
    horizontal = side in ("east", "west")
    along = [n[1] if horizontal else n[0] for n in nodes]
    lo, hi = min(along), max(along)
    best = [None] * bands
    sign = 1 if side in ("east", "north") else -1
    for i, (x, y, _) in enumerate(nodes):
        if not in_scc[i]:
            continue
        b = min(bands - 1, int((along[i] - lo) / (hi - lo + 1e-12) * bands))
        key = sign * (x if horizontal else y)
        if best[b] is None or key > best[b][0]:
            best[b] = (key, i)
    return [b[1] if b else None for b in best]


def make_zones(nodes, in_scc, grid):
    """(node, weight) per occupied cell: the SCC node nearest the cell centre, weight = nodes in the cell."""
    xs, ys = [n[0] for n in nodes], [n[1] for n in nodes]
    x0, y0 = min(xs), min(ys)
    w, h = (max(xs) - x0) / grid + 1e-12, (max(ys) - y0) / grid + 1e-12
    cells = {}
    for i, (x, y, _) in enumerate(nodes):
        c = (min(grid - 1, int((x - x0) / w)), min(grid - 1, int((y - y0) / h)))
        entry = cells.setdefault(c, [0, None, 0.0])
        entry[0] += 1
        if in_scc[i]:
            cx, cy = x0 + (c[0] + 0.5) * w, y0 + (c[1] + 0.5) * h
            d = (x - cx) ** 2 + (y - cy) ** 2
            if entry[1] is None or d < entry[2]:
                entry[1], entry[2] = i, d
    return [(cells[c][1], cells[c][0]) for c in sorted(cells) if cells[c][1] is not None]


def departure(rng, seconds):
    hours = seconds / 3600.0
    while True:
        u = rng.random()
        if u < 0.35:
            t = rng.gauss(2.0, 0.75) / 12.0 * hours
        elif u < 0.75:
            t = rng.gauss(10.5, 1.0) / 12.0 * hours
        else:
            t = rng.random() * hours
        if 0 <= t < hours:
            return t * 3600.0


def main():
    a = parse_args()
    t0 = time.time()
    nodes, edges = read_base(a.bayarea, a.scale)
    n = len(nodes)
    if n == 0:
        sys.exit("make_regional_scenario: no base nodes in " + a.bayarea)
    in_scc = largest_scc(n, edges)
    log(f"base: {n} nodes, {len(edges)} edges, largest SCC {sum(in_scc)} nodes")

    cells, cols = tile_layout(a.tiles)
    xs, ys = [p[0] for p in nodes], [p[1] for p in nodes]
    step_x = max(xs) - min(xs) + TILE_GAP_DEG
    step_y = max(ys) - min(ys) + TILE_GAP_DEG
    pos = {c: k for k, c in enumerate(cells)}
    os.makedirs(a.out, exist_ok=True)

    # Nodes: tile k's copy of base node i has dense index k * n + i (also its id).
    with open(os.path.join(a.out, "nodes.csv"), "w") as f:
        f.write("osmid,x,y,ref,highway\n")
        for k, (cx, cy) in enumerate(cells):
            dx, dy = cx * step_x, cy * step_y
            base = k * n
            f.write("".join(f"{base + i},{x + dx:.7f},{y + dy:.7f},,{hw}\n" for i, (x, y, hw) in enumerate(nodes)))

    def xy(node):
        k, i = divmod(node, n)
        return nodes[i][0] + cells[k][0] * step_x, nodes[i][1] + cells[k][1] * step_y

    bridges = []  # (u, v) global node indices, both directions added below
    east, west = border_nodes(nodes, in_scc, "east", a.bridges), border_nodes(nodes, in_scc, "west", a.bridges)
    north, south = border_nodes(nodes, in_scc, "north", a.bridges), border_nodes(nodes, in_scc, "south", a.bridges)
    for k, (cx, cy) in enumerate(cells):
        for (nx, ny), here, there in (((cx + 1, cy), east, west), ((cx, cy + 1), north, south)):
            j = pos.get((nx, ny))
            if j is None:
                continue
            for p, q in zip(here, there):
                if p is not None and q is not None:
                    bridges.append((k * n + p, j * n + q))

    num_edges = 0
    with open(os.path.join(a.out, "edges.csv"), "w") as f:
        f.write("uniqueid,u,v,length,lanes,speed_mph\n")
        for k in range(a.tiles):
            base, first = k * n, num_edges
            f.write("".join(f"{first + e},{base + u},{base + v},{length},{lanes},{mph}\n"
                            for e, (u, v, length, lanes, mph) in enumerate(edges)))
            num_edges += len(edges)
        for u, v in bridges:
            length = max(1.0, metres(*xy(u), *xy(v)))
            for s, t in ((u, v), (v, u)):
                f.write(f"{num_edges},{s},{t},{length:.1f},{BRIDGE_LANES},{BRIDGE_SPEED_MPH}\n")
                num_edges += 1
    log(f"network: {a.tiles * n} nodes, {num_edges} edges ({2 * len(bridges)} bridge edges), "
        f"{time.time() - t0:.1f} s")

    # Zones per tile (same cells in every copy), with each zone's nearest zones of its own tile.
    base_zones = make_zones(nodes, in_scc, a.zone_grid)
    zone_nodes = [z for z, _ in base_zones]
    cum = []
    total = 0
    for _, w in base_zones:
        total += w
        cum.append(total)
    nz = len(base_zones)
    near = []
    for z in zone_nodes:
        zx, zy = nodes[z][0], nodes[z][1]
        ranked = sorted(range(nz), key=lambda j: ((nodes[zone_nodes[j]][0] - zx) ** 2 +
                                                  (nodes[zone_nodes[j]][1] - zy) ** 2, j))
        near.append([j for j in ranked[1:NEAREST_ZONES + 1]])
    neighbours = []
    for cx, cy in cells:
        around = [pos[c] for c in ((cx - 1, cy), (cx + 1, cy), (cx, cy - 1), (cx, cy + 1)) if c in pos]
        neighbours.append(around)
    log(f"zones: {nz} per tile, {nz * a.tiles} in all")

    rng = random.Random(a.seed)
    seconds = a.hours * 3600.0

    def pick_zone():
        return bisect.bisect_right(cum, rng.random() * total)

    kinds = [0, 0, 0, 0]
    with open(os.path.join(a.out, "od.csv"), "w") as f:
        f.write("dep_time,origin,destination\n")
        chunk = []
        for trip in range(a.trips):
            k = rng.randrange(a.tiles)
            oz = pick_zone()
            u = rng.random()
            dk, dz = k, oz
            if u < 0.75 and near[oz]:
                dz, kind = near[oz][rng.randrange(len(near[oz]))], 0
            elif u < 0.90:
                kind = 1
            elif u < 0.97 and neighbours[k]:
                dk, kind = neighbours[k][rng.randrange(len(neighbours[k]))], 2
            else:
                dk, kind = rng.randrange(a.tiles), 3
            while dk == k and dz == oz:
                if nz == 1 and a.tiles == 1:
                    break
                dz = pick_zone()
                if nz == 1:
                    dk = rng.randrange(a.tiles)
            kinds[kind] += 1
            chunk.append(f"{departure(rng, seconds):.1f},{k * n + zone_nodes[oz]},{dk * n + zone_nodes[dz]}\n")
            if len(chunk) >= 100000:
                f.write("".join(chunk))
                chunk.clear()
        f.write("".join(chunk))
    log(f"demand: {a.trips} trips (nearest-zone {kinds[0]}, same tile {kinds[1]}, neighbouring tile {kinds[2]}, "
        f"anywhere {kinds[3]}) over {a.hours:g} h, {time.time() - t0:.1f} s in all")
    with open(os.path.join(a.out, "scenario.txt"), "w") as f:
        f.write(f"tiles={a.tiles} nodes={a.tiles * n} edges={num_edges} bridge_edges={2 * len(bridges)} "
                f"zones={nz * a.tiles} trips={a.trips} hours={a.hours:g} seed={a.seed} scale={a.scale:g}\n")


if __name__ == "__main__":
    main()

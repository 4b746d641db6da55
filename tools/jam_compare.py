#!/usr/bin/python3
"""Where LPSim jams and SUMO does not: reads LPSim's jam report (`lpsim run --jam-report FILE`) and SUMO's FCD of
the same scenario (`sumo --fcd-output`, plain or .gz) and prints, for the lanes where LPSim's long stops
cluster, LPSim's stopped vehicle-seconds and teleports there beside SUMO's, ranked; then the causes: stopped
seconds and episodes per reason, teleports per cause, the root causes at the ends of the blocker chains, and
the deadlock cycles.

Both sides count the same thing: episodes of a vehicle standing (speed < 0.1 m/s) at least the report's stop
time, each counted on the lane where it stood last, for its whole length. SUMO's teleports come from its log
(`--sumo-log`, the stderr of the SUMO run: "Teleporting vehicle ...; lane='...'") when given.

Usage: tools/jam_compare.py jam.xml sumo_fcd.xml [--sumo-log sumo.log] [--top 20] [--by edge]
"""

import argparse
import collections
import gzip
import re
import signal
import sys
import xml.etree.ElementTree as ET

STANDING = 0.1  # m/s: SUMO's halting threshold, the report's too


def open_xml(path):
    return gzip.open(path, "rb") if path.endswith(".gz") else open(path, "rb")


def place(lane, by):
    """The lane, or its edge (SUMO lane ids are <edge>_<index>)."""
    return lane.rsplit("_", 1)[0] if by == "edge" else lane


def read_report(path):
    root = ET.parse(open_xml(path)).getroot()
    jams = []
    for j in root.iter("jam"):
        blockers = [b.attrib for b in j.findall("blocker")]
        dl = j.find("deadlock")
        jams.append({**j.attrib, "blockers": blockers, "deadlock": dl.attrib if dl is not None else None})
    return float(root.get("stopTime", "60")), jams


def sumo_episodes(path, stop_time):
    """(lane of the last standing step, seconds standing) for each of SUMO's standing episodes >= stop_time."""
    open_ep = {}  # vehicle -> [begin, lane]
    last_time = None
    episodes = []

    def close(vid, t):
        begin, lane = open_ep.pop(vid)
        if t - begin + 1e-9 >= stop_time:
            episodes.append((lane, t - begin))

    seen = set()
    for event, el in ET.iterparse(open_xml(path), events=("start", "end")):
        if event == "start" and el.tag == "timestep":
            t = float(el.get("time"))
            seen = set()
        elif event == "end" and el.tag == "vehicle":
            vid = el.get("id")
            seen.add(vid)
            if float(el.get("speed")) < STANDING:
                if vid in open_ep:
                    open_ep[vid][1] = el.get("lane")
                else:
                    open_ep[vid] = [t, el.get("lane")]
            elif vid in open_ep:
                close(vid, t)
            el.clear()
        elif event == "end" and el.tag == "timestep":
            for vid in [v for v in open_ep if v not in seen]:  # left the road (arrived, teleported)
                close(vid, t)
            last_time = t
            el.clear()
    for vid in list(open_ep):
        close(vid, last_time)
    return episodes


def sumo_teleports(path):
    counts = collections.Counter()
    pattern = re.compile(r"Teleporting vehicle '.*?'; waited too long(?: \(([^)]*)\))?, lane='([^']*)'")
    with open(path, errors="replace") as f:
        for line in f:
            m = pattern.search(line)
            if m:
                counts[m.group(2)] += 1
    return counts


def root_cause(jam):
    """What holds the chain at its end: the reason of its last vehicle (the vehicle itself when nothing blocks
    it), "moving, ..." when that vehicle moves (a slow queue, not a blocked one), or "deadlock cycle"."""
    if jam["deadlock"] is not None:
        return "deadlock cycle"
    root = jam["blockers"][-1] if jam["blockers"] else jam
    return ("moving, " if float(root["speed"]) >= STANDING else "") + root["reason"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("jam_report")
    ap.add_argument("sumo_fcd")
    ap.add_argument("--sumo-log", help="SUMO's stderr, for its teleports per lane")
    ap.add_argument("--top", type=int, default=20, help="places to list (default 20)")
    ap.add_argument("--by", choices=["lane", "edge"], default="lane", help="group by lane (default) or edge")
    a = ap.parse_args()

    stop_time, jams = read_report(a.jam_report)
    lp_seconds, lp_episodes, lp_teleports = collections.Counter(), collections.Counter(), collections.Counter()
    causes = collections.defaultdict(collections.Counter)  # place -> root cause -> standing seconds
    for j in jams:
        p = place(j["lane"], a.by)
        causes[p][root_cause(j)] += float(j["duration"])
        if j["ended"] == "teleported":
            lp_teleports[p] += 1
        if float(j["duration"]) + 1e-9 >= stop_time:
            lp_seconds[p] += float(j["duration"])
            lp_episodes[p] += 1
    su_seconds, su_episodes = collections.Counter(), collections.Counter()
    for lane, seconds in sumo_episodes(a.sumo_fcd, stop_time):
        su_seconds[place(lane, a.by)] += seconds
        su_episodes[place(lane, a.by)] += 1
    su_teleports = collections.Counter()
    if a.sumo_log:
        for lane, n in sumo_teleports(a.sumo_log).items():
            su_teleports[place(lane, a.by)] += n

    print(f"Standing episodes >= {stop_time:g} s, by {a.by}: LPSim {sum(lp_episodes.values())} "
          f"({sum(lp_seconds.values()):.0f} veh-s, {sum(lp_teleports.values())} teleports), "
          f"SUMO {sum(su_episodes.values())} ({sum(su_seconds.values()):.0f} veh-s"
          + (f", {sum(su_teleports.values())} teleports)" if a.sumo_log else ")"))
    places = sorted(set(lp_seconds) | set(lp_teleports), key=lambda p: (-lp_seconds[p], -lp_teleports[p], p))
    print(f"\n{'rank':>4}  {a.by:<32} {'LPSim veh-s':>11} {'episodes':>8} {'teleports':>9} "
          f"{'SUMO veh-s':>10} {'episodes':>8}" + (f" {'teleports':>9}" if a.sumo_log else "")
          + "  LPSim's main root cause there (share of its veh-s)")
    for rank, p in enumerate(places[: a.top], 1):
        main_cause, secs = causes[p].most_common(1)[0] if causes[p] else ("-", 0)
        share = secs / sum(causes[p].values()) if secs else 0
        print(f"{rank:>4}  {p:<32} {lp_seconds[p]:>11.0f} {lp_episodes[p]:>8} {lp_teleports[p]:>9} "
              f"{su_seconds[p]:>10.0f} {su_episodes[p]:>8}" + (f" {su_teleports[p]:>9}" if a.sumo_log else "")
              + f"  {main_cause} ({share:.0%})")

    # Causes. A record's reason is what bounded it in the last step it stood; its reasons attribute the
    # seconds per reason over the episode; a chain's root is its last blocker (or the vehicle itself).
    reason_seconds, reason_count, roots = collections.Counter(), collections.Counter(), collections.Counter()
    teleport_causes = collections.Counter()
    for j in jams:
        reason_count[j["reason"]] += 1
        for part in j.get("reasons", "").split():
            name, _, secs = part.rpartition(":")
            reason_seconds[name] += float(secs)
        if j["ended"] == "teleported":
            teleport_causes[j.get("teleport", "jam")] += 1
        roots[root_cause(j)] += 1
    print("\nReasons (episodes by last reason; standing seconds by reason over all episodes):")
    for name in sorted(set(reason_count) | set(reason_seconds), key=lambda n: -reason_seconds[n]):
        print(f"  {name:<12} {reason_count[name]:>7} episodes {reason_seconds[name]:>10.0f} s")
    print("Root causes (reason of the last vehicle of each chain, the vehicle itself when none blocks it):")
    for name, n in roots.most_common():
        print(f"  {name:<15} {n:>7}")
    print("Teleports by cause: " + (", ".join(f"{c} {n}" for c, n in teleport_causes.most_common()) or "none"))

    cycles = {}
    for j in jams:
        if j["deadlock"] is not None:
            ids = j["deadlock"]["vehicles"].split()
            key = tuple(sorted(ids))
            if key not in cycles:
                cycles[key] = (j["deadlock"]["lanes"], float(j["end"]))
    print(f"Deadlock cycles: {len(cycles)}")
    for ids, (lanes, end) in sorted(cycles.items(), key=lambda kv: kv[1][1])[: a.top]:
        print(f"  {len(ids)} vehicles on lanes {' '.join(sorted(set(lanes.split())))} (first seen ending {end:.0f} s)")
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    sys.exit(main())

#!/usr/bin/python3
"""Writes reference counts for a SUMO scenario as `key=value` lines (stdout).

Network counts come from sumolib (cross-checked against a plain XML count); demand counts from the route files;
run counts from SUMO itself (`sumo -c <cfg> --statistic-output ... --duration-log.statistics`).
Usage: /usr/bin/python3 tools/sumo_reference.py scenarios/<name>/<name>.sumocfg > .../sumo_reference.txt
"""
import math
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

SUMO_HOME = os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
sys.path.append(os.path.join(SUMO_HOME, "tools"))
import sumolib  # noqa: E402


def config_files(cfg_path):
    """net file and route/additional files named by a .sumocfg, as paths."""
    base = os.path.dirname(os.path.abspath(cfg_path))
    root = ET.parse(cfg_path).getroot()
    files = {"net-file": [], "route-files": [], "additional-files": []}
    for section in root:
        for opt in section:
            if opt.tag in files:
                files[opt.tag] += [os.path.join(base, f.strip()) for f in opt.get("value", "").split(",") if f.strip()]
    return files


def network_counts(net_file):
    net = sumolib.net.readNet(net_file, withInternal=True, withPrograms=True)
    normal = [e for e in net.getEdges(withInternal=True) if e.getFunction() == ""]
    internal = [e for e in net.getEdges(withInternal=True) if e.getFunction() == "internal"]
    lanes = [lane for e in normal for lane in e.getLanes()]
    passenger_lanes = [lane for lane in lanes if lane.allows("passenger")]
    passenger_ids = {lane.getID() for lane in passenger_lanes}
    connections = 0
    for lane in passenger_lanes:
        for con in lane.getOutgoing():
            if con.getToLane().getID() in passenger_ids:
                connections += 1
    counts = {
        "normal_edges": len(normal),
        "internal_edges": len(internal),
        "junctions": sum(1 for n in net.getNodes() if n.getType() != "internal"),
        "passenger_lanes": len(passenger_lanes),
        "non_passenger_lanes": len(lanes) - len(passenger_lanes),
        "tl_programs": sum(len(tls.getPrograms()) for tls in net.getTrafficLights()),
        "passenger_connections": connections,
    }
    for node_type in sorted({n.getType() for n in net.getNodes()} - {"internal"}):
        counts["junctions_" + node_type] = sum(1 for n in net.getNodes() if n.getType() == node_type)
    # Independent count straight from the XML: a <connection> between two lanes sumolib says allow cars.
    xml_connections = 0
    xml_programs = 0
    for _, elem in ET.iterparse(net_file):
        if elem.tag == "connection":
            src = "%s_%s" % (elem.get("from"), elem.get("fromLane"))
            dst = "%s_%s" % (elem.get("to"), elem.get("toLane"))
            if src in passenger_ids and dst in passenger_ids:
                xml_connections += 1
        elif elem.tag == "tlLogic":
            xml_programs += 1
    if xml_connections != connections or xml_programs != counts["tl_programs"]:
        sys.exit("sumolib and XML disagree: connections %d vs %d, programs %d vs %d"
                 % (connections, xml_connections, counts["tl_programs"], xml_programs))
    return counts


def flow_vehicles(flow):
    """Vehicles a <flow> generates, when that follows from its attributes alone (None for probability)."""
    begin = float(flow.get("begin", "0"))
    end = float(flow.get("end", "86400")) if flow.get("end") else None
    if flow.get("number") is not None:
        return int(flow.get("number"))
    period = None
    if flow.get("period") is not None:
        period = float(flow.get("period"))
    elif flow.get("vehsPerHour") is not None:
        period = 3600.0 / float(flow.get("vehsPerHour"))
    if period is None or end is None:
        return None
    return int(math.ceil((end - begin) / period - 1e-9))


def demand_counts(route_files):
    counts = {"xml_vehicles": 0, "xml_trips": 0, "xml_flows": 0, "xml_persons": 0}
    derivable, not_derivable = 0, 0
    for path in route_files:
        for _, elem in ET.iterparse(path):
            if elem.tag == "vehicle":
                counts["xml_vehicles"] += 1
            elif elem.tag == "trip":
                counts["xml_trips"] += 1
            elif elem.tag in ("person", "personFlow", "container", "containerFlow"):
                counts["xml_persons"] += 1
            elif elem.tag == "flow":
                counts["xml_flows"] += 1
                n = flow_vehicles(elem)
                if n is None:
                    not_derivable += 1
                else:
                    derivable += n
    counts["flow_vehicles_derivable"] = derivable
    counts["flows_not_derivable"] = not_derivable
    return counts


def run_counts(cfg_path):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.xml")
        tripinfo = os.path.join(tmp, "tripinfo.xml")
        proc = subprocess.run(
            ["sumo", "-c", cfg_path, "--statistic-output", stats, "--duration-log.statistics",
             "--tripinfo-output", tripinfo, "--no-step-log"],
            check=True, capture_output=True, text=True)
        root = ET.parse(stats).getroot()
        vehicles = root.find("vehicles")
        trips = root.find("vehicleTripStatistics")
        teleports = root.find("teleports")
        counts = {
            "sumo_vehicles_loaded": int(vehicles.get("loaded")),
            "sumo_vehicles_inserted": int(vehicles.get("inserted")),
            "sumo_vehicles_arrived": int(trips.get("count")),
            "sumo_vehicles_running_at_end": int(vehicles.get("running")),
            "sumo_vehicles_waiting_at_end": int(vehicles.get("waiting")),
            "sumo_teleports": int(teleports.get("total")) if teleports is not None else 0,
            "sumo_mean_duration_s": float(trips.get("duration")),
            "sumo_mean_route_length_m": float(trips.get("routeLength")),
        }
        # Arrivals per flow (vehicle ids "<flow id>.<n>"), for flows whose count is random.
        per_flow = {}
        for _, elem in ET.iterparse(tripinfo):
            if elem.tag == "tripinfo" and "." in elem.get("id"):
                flow_id = elem.get("id").rsplit(".", 1)[0]
                per_flow[flow_id] = per_flow.get(flow_id, 0) + 1
        for flow_id in sorted(per_flow):
            counts["sumo_arrived_flow_" + flow_id] = per_flow[flow_id]
        warnings = sum(1 for line in proc.stderr.splitlines() if line.startswith("Warning"))
        counts["sumo_warnings"] = warnings
    return counts


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    cfg = sys.argv[1]
    files = config_files(cfg)
    version = subprocess.run(["sumo", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    print("# reference counts for %s, %s" % (os.path.basename(cfg), version.strip()))
    print("# made by tools/sumo_reference.py (see scenarios/README.md for the keys)")
    counts = {}
    counts.update(network_counts(files["net-file"][0]))
    counts.update(demand_counts(files["route-files"] + files["additional-files"]))
    counts.update(run_counts(cfg))
    for key, value in counts.items():
        print("%s=%s" % (key, value))


if __name__ == "__main__":
    main()

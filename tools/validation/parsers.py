"""Readers for the SUMO-format files both simulators write (tripinfo, edgeData, summary, statistics) and for
the few .sumocfg values the runner needs. Streaming (iterparse) so hour-long city runs stay small in memory."""
import gzip
import os
import re
import xml.etree.ElementTree as ET

# Vehicle classes LPSim leaves out by design (no road lane carries them: trains, ships, walkers); their trips
# in SUMO's outputs are not compared (counted apart).
OFF_ROAD_VCLASSES = frozenset({"rail", "rail_urban", "rail_electric", "rail_fast", "subway", "cable_car", "ship",
                               "aircraft", "pedestrian", "wheelchair"})


class TripInfo:
    """Arrived trips of one run. Unfinished trips (arrival < 0, from --tripinfo-output.write-unfinished) are
    counted apart because they did not arrive."""

    def __init__(self):
        self.durations = []
        self.route_lengths = []
        self.time_losses = []
        self.ids = set()
        self.unfinished = 0
        self.off_road = 0  # arrived trips of off-road vTypes, left out of the figures above

    @property
    def arrived(self):
        return len(self.durations)


class EdgeSample:
    """One edge summed over all intervals of an edgeData file. speed_time = speed x sampledSeconds, so the
    mean speed over several intervals is weighted by time on the edge, as SUMO does within one interval."""

    __slots__ = ("sampled_seconds", "speed_time", "entered", "departed", "arrived", "left")

    def __init__(self):
        self.sampled_seconds = 0.0
        self.speed_time = 0.0
        self.entered = 0.0
        self.departed = 0.0
        self.arrived = 0.0
        self.left = 0.0

    @property
    def speed(self):
        """Mean speed in m/s, None when no vehicle was on the edge."""
        if self.sampled_seconds <= 0:
            return None
        return self.speed_time / self.sampled_seconds


def _local(tag):
    """Tag without a namespace prefix: '{ns}edge' -> 'edge'."""
    return tag.rsplit("}", 1)[-1]


def _float(attrs, name, default=None):
    text = attrs.get(name)
    if text is None or text == "":
        return default
    return float(text)


def parse_tripinfo(path, off_road_vtypes=frozenset()):
    """Reads <tripinfo> elements (person <personinfo> are ignored). arrived = count of finished trips; those of
    a vType in off_road_vtypes are only counted (TripInfo.off_road)."""
    trips = TripInfo()
    context = ET.iterparse(path, events=("start", "end"))
    root = None
    for event, elem in context:
        if event == "start":
            if root is None:
                root = elem
            continue
        if _local(elem.tag) != "tripinfo":
            continue
        attrs = elem.attrib
        arrival = _float(attrs, "arrival", 0.0)
        if arrival < 0:
            trips.unfinished += 1
        elif attrs.get("vType") in off_road_vtypes:
            trips.off_road += 1
        else:
            duration = _float(attrs, "duration")
            if duration is None:
                raise ValueError("%s: tripinfo '%s' has no duration" % (path, attrs.get("id", "?")))
            trips.durations.append(duration)
            trips.route_lengths.append(_float(attrs, "routeLength", 0.0))
            trips.time_losses.append(_float(attrs, "timeLoss", 0.0))
            trips.ids.add(attrs.get("id", ""))
        elem.clear()
        root.clear()  # drop finished children so memory stays flat
    return trips


def _add_sample(sample, attrs):
    seconds = _float(attrs, "sampledSeconds", 0.0)
    speed = _float(attrs, "speed")
    sample.sampled_seconds += seconds
    if speed is not None:
        sample.speed_time += speed * seconds
    sample.entered += _float(attrs, "entered", 0.0)
    sample.departed += _float(attrs, "departed", 0.0)
    sample.arrived += _float(attrs, "arrived", 0.0)
    sample.left += _float(attrs, "left", 0.0)


def parse_edgedata(path):
    """Reads a meandata file into {edge id: EdgeSample}, summing all intervals. Internal edges (':' ids) are
    skipped. A laneData file (<lane> inside <edge>) is summed over the edge's lanes."""
    edges = {}
    context = ET.iterparse(path, events=("start", "end"))
    root = None
    edge_id = None
    edge_has_lanes = False
    for event, elem in context:
        tag = _local(elem.tag)
        if event == "start":
            if root is None:
                root = elem
            if tag == "edge":
                edge_id = elem.get("id")
                edge_has_lanes = False
            continue
        if tag == "lane" and edge_id is not None:
            edge_has_lanes = True
            if not edge_id.startswith(":"):
                _add_sample(edges.setdefault(edge_id, EdgeSample()), elem.attrib)
        elif tag == "edge":
            if not edge_has_lanes and edge_id is not None and not edge_id.startswith(":"):
                _add_sample(edges.setdefault(edge_id, EdgeSample()), elem.attrib)
            edge_id = None
            elem.clear()
        elif tag == "interval":
            elem.clear()
            root.clear()
    return edges


def parse_statistic_output(path):
    """SUMO's --statistic-output: {'loaded', 'inserted', 'running', 'waiting', 'teleports', 'collisions',
    'mean_duration'} where present."""
    stats = {}
    for _, elem in ET.iterparse(path):
        tag = _local(elem.tag)
        attrs = elem.attrib
        if tag == "vehicles":
            for key in ("loaded", "inserted", "running", "waiting"):
                if key in attrs:
                    stats[key] = int(float(attrs[key]))
        elif tag == "teleports" and "total" in attrs:
            stats["teleports"] = int(float(attrs["total"]))
        elif tag == "safety" and "collisions" in attrs:
            stats["collisions"] = int(float(attrs["collisions"]))
        elif tag == "vehicleTripStatistics" and "duration" in attrs:
            stats["mean_duration"] = float(attrs["duration"])
    return stats


_INSERTED = re.compile(r"^\s*Inserted:\s*(\d+)(?:\s*\(Loaded:\s*(\d+)\))?", re.M)
_RUNNING = re.compile(r"^\s*Running:\s*(\d+)", re.M)
_WAITING = re.compile(r"^\s*Waiting:\s*(\d+)", re.M)
_TELEPORTS = re.compile(r"^\s*Teleports:\s*(\d+)", re.M)


def parse_statistics_text(text):
    """The block SUMO prints with --duration-log.statistics ('Inserted: 1910 (Loaded: 2171)', 'Running: 78',
    'Teleports: 3 (Jam: 2)'). SUMO omits 'Teleports:' when there were none, so it counts as 0 once the
    vehicle block was found. 'loaded' equals 'inserted' when SUMO leaves out the bracket."""
    stats = {}
    match = _INSERTED.search(text)
    if not match:
        return stats
    stats["inserted"] = int(match.group(1))
    stats["loaded"] = int(match.group(2)) if match.group(2) else stats["inserted"]
    for key, pattern in (("running", _RUNNING), ("waiting", _WAITING)):
        found = pattern.search(text)
        if found:
            stats[key] = int(found.group(1))
    found = _TELEPORTS.search(text)
    stats["teleports"] = int(found.group(1)) if found else 0
    return stats


def parse_summary_last(path):
    """Last <step> of a summary-output file: its counts are cumulative (loaded, inserted, teleports ...)."""
    last = None
    for _, elem in ET.iterparse(path):
        if _local(elem.tag) == "step":
            last = dict(elem.attrib)
        elem.clear()
    if last is None:
        return {}
    stats = {}
    for key in ("loaded", "inserted", "running", "waiting", "arrived", "teleports", "collisions"):
        if key in last:
            stats[key] = int(float(last[key]))
    return stats


def _sumo_time(text):
    """SUMO time: seconds, h:m:s or d:h:m:s (a leading '-' negates the whole)."""
    text = text.strip()
    sign = -1.0 if text.startswith("-") else 1.0
    parts = [float(p) for p in text.lstrip("-").split(":")]
    if len(parts) == 1:
        return sign * parts[0]
    if len(parts) == 3:
        hours, minutes, seconds = parts
        return sign * ((hours * 60 + minutes) * 60 + seconds)
    if len(parts) == 4:
        days, hours, minutes, seconds = parts
        return sign * (((days * 24 + hours) * 60 + minutes) * 60 + seconds)
    raise ValueError("not a SUMO time: '%s'" % text)


def read_sumocfg(path):
    """The .sumocfg values the runner uses: {'begin', 'end', 'step_length' (floats or None), 'outputs'
    {option: value} from the <output> and <report> sections, 'options' {name: value} of everything}."""
    tree = ET.parse(path)
    options = {}
    outputs = {}
    for section in tree.getroot():
        section_name = _local(section.tag)
        for option in section:
            if not isinstance(option.tag, str):
                continue  # comments
            name = _local(option.tag)
            value = option.get("value")
            if value is None:
                continue
            options[name] = value
            if section_name in ("output", "report") or name.endswith("-output") or name == "log":
                outputs[name] = value
    config = {"options": options, "outputs": outputs, "begin": None, "end": None, "step_length": None}
    for key, name in (("begin", "begin"), ("end", "end"), ("step_length", "step-length")):
        if name in options:
            config[key] = _sumo_time(options[name])
    if config["end"] is not None and config["end"] < 0:
        config["end"] = None  # SUMO's -1: run until the network is empty
    return config


def off_road_vtypes(cfg_path, config):
    """Ids of the vTypes defined in the cfg's route and additional files whose vClass is one of
    OFF_ROAD_VCLASSES (missing or unreadable files are passed over: the runs report those)."""
    folder = os.path.dirname(os.path.abspath(cfg_path))
    ids = set()
    for key in ("route-files", "additional-files"):
        for name in re.split(r"[,\s]+", config["options"].get(key, "")):
            path = os.path.join(folder, name)
            if not name or not os.path.isfile(path):
                continue
            opener = gzip.open if path.endswith(".gz") else open
            try:
                with opener(path, "rb") as handle:
                    for _event, elem in ET.iterparse(handle):
                        if _local(elem.tag) == "vType" and elem.get("vClass") in OFF_ROAD_VCLASSES:
                            ids.add(elem.get("id"))
            except (ET.ParseError, OSError):
                continue
    return ids


def file_exists(path):
    return bool(path) and os.path.isfile(path) and os.path.getsize(path) > 0

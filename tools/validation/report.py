"""Markdown table (one row per scenario and car-following model), the line totalling the targets, and the JSON
document with every number."""
import json

from . import metrics

TARGET_HEADERS = {
    "inserted": "inserted ±%g%%" % (100 * metrics.INSERTED_TOLERANCE),
    "arrived": "arrived ±%g%%" % (100 * metrics.ARRIVED_TOLERANCE),
    "duration": "dur ±%g%%" % (100 * metrics.DURATION_TOLERANCE),
    "speed_r": "speed r≥%g" % metrics.SPEED_R_MIN,
    "teleports": "teleports ≤max(%d×S,%d)" % (metrics.TELEPORTS_FACTOR, metrics.TELEPORTS_FLOOR),
}
COLUMNS = (["scenario", "model", "loaded S/L", "inserted S/L", "arrived S/L", "mean dur S/L (s)", "dur Δ",
            "speed r (edges)", "teleports S/L", "wall s S/L"]
           + [TARGET_HEADERS[t] for t in metrics.TARGETS] + ["note"])


def _num(value, digits=1):
    if value is None:
        return "–"
    if isinstance(value, int):
        return str(value)
    return "%.*f" % (digits, value)


def _pct(value):
    return "–" if value is None else "%+.1f %%" % (100.0 * value)


def _pair(a, b, digits=1):
    return "%s / %s" % (_num(a, digits), _num(b, digits))


def _cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def _target_cells(comparison):
    """PASS/MISS per target; the inserted and arrived cells carry the relative difference too."""
    if not comparison:
        return ["–"] * len(metrics.TARGETS)
    cells = []
    for target in metrics.TARGETS:
        text = comparison["targets"].get(target) or "–"
        if target in ("inserted", "arrived"):
            text += " " + _pct(comparison[target]["relative_difference"])
        cells.append(text)
    return cells


def notes_of(entry):
    """The row's note: 'refused: <LPSim's error line>' for a scenario LPSim refuses (exit status 2), else the
    errors of either side."""
    if entry.get("refused"):
        return "refused: %s" % entry["refused"]
    return "; ".join(n for n in (entry.get("reference_error"), entry.get("candidate_error")) if n)


def scenario_row(entry):
    """One markdown row from a (scenario, model) entry of the JSON document (see validate.run_scenario). Without
    a comparison (a side refused or failed) the row shows what each side gave and no verdicts."""
    sumo, cand = (entry.get("reference") or {}), (entry.get("candidate") or {})
    s, c = sumo.get("summary", {}), cand.get("summary", {})
    comparison = entry.get("comparison")
    duration_delta = comparison["duration"]["relative_difference_of_mean"] if comparison else None
    speed = "–"
    if comparison:
        speed = "%s (%d)" % (_num(comparison["edge_speed"]["r"], 3), comparison["edge_speed"]["edges"])
    cells = [
        entry["scenario"], entry.get("model", "–"),
        _pair(s.get("loaded"), c.get("loaded")),
        # Road traffic: SUMO's inserted less its arrived trains and ships, as the inserted target compares.
        _pair(comparison["inserted"]["reference"] if comparison else s.get("inserted"), c.get("inserted")),
        _pair(s.get("arrived"), c.get("arrived")),
        _pair((s.get("duration") or {}).get("mean"), (c.get("duration") or {}).get("mean")),
        _pct(duration_delta), speed,
        _pair(s.get("teleports"), c.get("teleports")),
        _pair(sumo.get("run", {}).get("wall_s"), cand.get("run", {}).get("wall_s"), 0),
    ] + _target_cells(comparison) + [notes_of(entry)]
    return "| " + " | ".join(_cell(c) for c in cells) + " |"


def summary_line(entries):
    """How many (scenario, model) pairs meet all targets, and how many miss each one."""
    totals = metrics.tally([(entry.get("comparison") or {}).get("targets") for entry in entries])
    share = 100.0 * totals["all_met"] / totals["pairs"] if totals["pairs"] else 0.0
    misses = ", ".join("%s %d" % (TARGET_HEADERS[t], totals["missed"][t]) for t in metrics.TARGETS)
    return ("**All five targets met: %d of %d (scenario, model) pairs (%.0f %%).** Pairs missing each target: %s "
            "(a refused or failed pair misses every target).\n" % (totals["all_met"], totals["pairs"], share, misses))


def markdown_table(entries, reference_label="SUMO", candidate_label="LPSim"):
    cached = sum(1 for entry in entries if ((entry.get("reference") or {}).get("run") or {}).get("cached"))
    legend = ("S = %s, L = %s; Δ = (L − S) / S; arrived = trips in tripinfo with an arrival, mean dur over them; "
              "loaded/inserted/teleports = each simulator's own totals, but SUMO's arrived trains and ships (vTypes "
              "of a class LPSim leaves out by design) are left out of its inserted and arrived counts and durations; "
              "speed r: Pearson r of per-edge mean speed over edges both sampled. SUMO runs taken from the cache: "
              "%d of %d."
              % (reference_label, candidate_label, cached, len(entries)))
    lines = [legend, "", "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += [scenario_row(entry) for entry in entries]
    return "\n".join(lines) + "\n\n" + summary_line(entries)


def write_json(path, document):
    with open(path, "w") as handle:
        json.dump(document, handle, indent=2, sort_keys=True)
        handle.write("\n")

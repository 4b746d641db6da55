"""Markdown table (one row per scenario) and the JSON document with every number."""
import json

COLUMNS = [
    "scenario", "inserted S/L", "arrived S/L", "arrived Δ", "mean dur S/L (s)", "dur Δ",
    "p10/p50/p90 S (s)", "p10/p50/p90 L (s)", "speed r (edges)", "entered r", "teleports S/L",
    "CPU s S/L", "CPU L/S", "wall s S/L", "arrived ±2%", "dur ±15%", "speed r≥0.8", "note",
]


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


def _triple(summary):
    if not summary or summary.get("mean") is None:
        return "–"
    return "%s / %s / %s" % (_num(summary["p10"], 0), _num(summary["median"], 0), _num(summary["p90"], 0))


def _cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def scenario_row(entry):
    """One markdown row from a scenario entry of the JSON document (see validate.run_scenario)."""
    name = entry["scenario"]
    sumo, cand, comparison = entry.get("reference"), entry.get("candidate"), entry.get("comparison")
    notes = [n for n in (entry.get("reference_error"), entry.get("candidate_error")) if n]
    sumo_summary = (sumo or {}).get("summary", {})
    cand_summary = (cand or {}).get("summary", {})
    s_run, c_run = (sumo or {}).get("run", {}), (cand or {}).get("run", {})
    if comparison:
        targets = comparison["targets"]
        speed = comparison["edge_speed"]
        cells = [
            name,
            _pair(comparison["inserted"]["reference"], comparison["inserted"]["candidate"]),
            _pair(comparison["arrived"]["reference"], comparison["arrived"]["candidate"]),
            _pct(comparison["arrived"]["relative_difference"]),
            _pair(comparison["duration"]["reference"]["mean"], comparison["duration"]["candidate"]["mean"]),
            _pct(comparison["duration"]["relative_difference_of_mean"]),
            _triple(comparison["duration"]["reference"]), _triple(comparison["duration"]["candidate"]),
            "%s (%d)" % (_num(speed["r"], 3), speed["edges"]),
            _num(comparison["edge_entered"]["r"], 3),
            _pair(comparison["teleports"]["reference"], comparison["teleports"]["candidate"]),
            _pair(comparison["cpu_s"]["reference"], comparison["cpu_s"]["candidate"], 2),
            _num(comparison["cpu_s"]["ratio"], 2),
            _pair(s_run.get("wall_s"), c_run.get("wall_s")),
            targets["arrived"] or "–", targets["duration"] or "–", targets["speed_r"] or "–",
        ]
    else:
        # Only one side (or neither) produced outputs: show what SUMO gave, leave the comparison empty.
        cells = [
            name,
            _pair(sumo_summary.get("inserted"), cand_summary.get("inserted")),
            _pair(sumo_summary.get("arrived"), cand_summary.get("arrived")),
            "–",
            _pair((sumo_summary.get("duration") or {}).get("mean"), (cand_summary.get("duration") or {}).get("mean")),
            "–", _triple(sumo_summary.get("duration")), _triple(cand_summary.get("duration")), "–", "–",
            _pair(sumo_summary.get("teleports"), cand_summary.get("teleports")),
            _pair(s_run.get("cpu_s"), c_run.get("cpu_s"), 2), "–",
            _pair(s_run.get("wall_s"), c_run.get("wall_s")),
            "–", "–", "–",
        ]
    cells.append("; ".join(notes))
    return "| " + " | ".join(_cell(c) for c in cells) + " |"


def markdown_table(entries, reference_label="SUMO", candidate_label="LPSim"):
    legend = ("S = %s, L = %s; Δ = (L − S) / S; speed r: Pearson r of per-edge mean speed over edges both "
              "sampled; entered r: Pearson r of per-edge entered counts." % (reference_label, candidate_label))
    lines = [legend, "", "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += [scenario_row(entry) for entry in entries]
    return "\n".join(lines) + "\n"


def write_json(path, document):
    with open(path, "w") as handle:
        json.dump(document, handle, indent=2, sort_keys=True)
        handle.write("\n")

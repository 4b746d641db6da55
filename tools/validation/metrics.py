"""Comparison metrics between a reference run (SUMO) and a candidate run (LPSim), standard library only."""
import math

# Targets of the issue "Match SUMO on the traffic not yet seen", per (scenario, car-following model): LPSim's
# inserted count within 1 % of SUMO's, arrivals within 3 %, mean duration of the arrived trips within 10 %,
# per-edge mean speed correlated with r >= 0.85, teleports at most max(2 x SUMO's, 5).
INSERTED_TOLERANCE = 0.01
ARRIVED_TOLERANCE = 0.03
DURATION_TOLERANCE = 0.10
SPEED_R_MIN = 0.85
TELEPORTS_FACTOR = 2
TELEPORTS_FLOOR = 5
TARGETS = ("inserted", "arrived", "duration", "speed_r", "teleports")


def mean(values):
    return sum(values) / len(values) if values else None


def percentile(values, fraction):
    """Linear interpolation between closest ranks (numpy's default), fraction in [0, 1]. None if empty."""
    if not values:
        return None
    ordered = sorted(values)
    position = fraction * (len(ordered) - 1)
    low = int(math.floor(position))
    high = min(low + 1, len(ordered) - 1)
    weight = position - low
    return ordered[low] + (ordered[high] - ordered[low]) * weight


def relative_difference(candidate, reference):
    """(candidate - reference) / reference; None when either is missing or the reference is 0."""
    if candidate is None or reference is None or reference == 0:
        return None
    return (candidate - reference) / reference


def pearson(xs, ys, weights=None):
    """Pearson correlation of paired values, optionally weighted. None for fewer than 2 pairs or when either
    side is constant (r is undefined there)."""
    if len(xs) != len(ys):
        raise ValueError("pearson: %d x values but %d y values" % (len(xs), len(ys)))
    if weights is None:
        weights = [1.0] * len(xs)
    if len(weights) != len(xs):
        raise ValueError("pearson: %d weights for %d pairs" % (len(weights), len(xs)))
    total = sum(weights)
    if len(xs) < 2 or total <= 0:
        return None
    mx = sum(w * x for w, x in zip(weights, xs)) / total
    my = sum(w * y for w, y in zip(weights, ys)) / total
    sxy = sum(w * (x - mx) * (y - my) for w, x, y in zip(weights, xs, ys))
    sxx = sum(w * (x - mx) ** 2 for w, x in zip(weights, xs))
    syy = sum(w * (y - my) ** 2 for w, y in zip(weights, ys))
    if sxx <= 0 or syy <= 0:
        return None
    r = sxy / math.sqrt(sxx * syy)
    return max(-1.0, min(1.0, r))  # rounding can push |r| a hair past 1


def duration_summary(durations):
    """mean/median/p10/p90 of trip durations (None each when there are no trips)."""
    return {
        "count": len(durations),
        "mean": mean(durations),
        "median": percentile(durations, 0.5),
        "p10": percentile(durations, 0.1),
        "p90": percentile(durations, 0.9),
    }


def edge_speed_correlation(reference_edges, candidate_edges, weighted=False):
    """Pearson r of per-edge mean speed over edges that both runs sampled (sampledSeconds > 0 in both).
    Weighted: each edge counts by the mean of both runs' sampledSeconds, so busy edges dominate."""
    common = sorted(e for e in reference_edges
                    if e in candidate_edges
                    and reference_edges[e].speed is not None and candidate_edges[e].speed is not None)
    xs = [reference_edges[e].speed for e in common]
    ys = [candidate_edges[e].speed for e in common]
    weights = None
    if weighted:
        weights = [(reference_edges[e].sampled_seconds + candidate_edges[e].sampled_seconds) / 2.0 for e in common]
    return {"r": pearson(xs, ys, weights), "edges": len(common), "weighted": weighted}


def edge_entered_correlation(reference_edges, candidate_edges):
    """Pearson r of per-edge entered counts over the edges either file lists; an edge one file leaves out
    counts as 0 entered there (an edge no vehicle used may be omitted)."""
    names = sorted(set(reference_edges) | set(candidate_edges))
    xs = [reference_edges[e].entered if e in reference_edges else 0.0 for e in names]
    ys = [candidate_edges[e].entered if e in candidate_edges else 0.0 for e in names]
    return {"r": pearson(xs, ys), "edges": len(names)}


def verdict(ok):
    """PASS/MISS, or None when the metric could not be computed."""
    if ok is None:
        return None
    return "PASS" if ok else "MISS"


def within(candidate, reference, tolerance):
    """|candidate - reference| <= tolerance x reference; a reference of 0 is met only by 0. None when either
    figure is missing."""
    if candidate is None or reference is None:
        return None
    if reference == 0:
        return candidate == 0
    return abs(candidate - reference) <= tolerance * abs(reference)


def teleports_ok(candidate, reference):
    """At most max(TELEPORTS_FACTOR x SUMO's, TELEPORTS_FLOOR) teleports; None when either count is missing."""
    if candidate is None or reference is None:
        return None
    return candidate <= max(TELEPORTS_FACTOR * reference, TELEPORTS_FLOOR)


def evaluate_targets(inserted, arrived, mean_duration, speed_r, teleports):
    """PASS/MISS (None: not computable) per target of TARGETS. inserted, arrived, mean_duration and teleports
    are (SUMO, LPSim) pairs; speed_r is the edge-speed Pearson r."""
    return {
        "inserted": verdict(within(inserted[1], inserted[0], INSERTED_TOLERANCE)),
        "arrived": verdict(within(arrived[1], arrived[0], ARRIVED_TOLERANCE)),
        "duration": verdict(within(mean_duration[1], mean_duration[0], DURATION_TOLERANCE)),
        "speed_r": verdict(None if speed_r is None else speed_r >= SPEED_R_MIN),
        "teleports": verdict(teleports_ok(teleports[1], teleports[0])),
    }


def tally(target_verdicts):
    """Totals over (scenario, model) pairs. target_verdicts: one dict per pair (evaluate_targets' result, or
    None for a pair without a comparison: refused, failed). A target counts as met only when PASS.
    Returns {'pairs', 'all_met', 'missed': {target: pairs missing it}}."""
    missed = dict.fromkeys(TARGETS, 0)
    all_met = 0
    for verdicts in target_verdicts:
        misses = [t for t in TARGETS if (verdicts or {}).get(t) != "PASS"]
        for target in misses:
            missed[target] += 1
        all_met += not misses
    return {"pairs": len(target_verdicts), "all_met": all_met, "missed": missed}


def compare_runs(reference, candidate, weighted_speed=False):
    """reference/candidate: dicts with 'trips' (TripInfo), 'edges' ({id: EdgeSample}), 'stats' (loaded,
    inserted, teleports ... as parsed) and 'cpu_s'. Both sides use the same definitions: inserted, loaded and
    teleports are the simulator's own totals (SUMO's statistic-output, LPSim's printed statistics), arrived is
    the number of tripinfo elements with an arrival time, the durations are those trips'. Returns every number
    plus PASS/MISS per target."""
    ref_trips, cand_trips = reference["trips"], candidate["trips"]
    ref_stats, cand_stats = reference["stats"], candidate["stats"]
    ref_dur = duration_summary(ref_trips.durations)
    cand_dur = duration_summary(cand_trips.durations)
    # Road traffic only: SUMO's arrived trains and ships (off-road vTypes, which LPSim leaves out by design) are
    # taken from its inserted count too.
    ref_inserted = ref_stats.get("inserted")
    if ref_inserted is not None:
        ref_inserted -= ref_trips.off_road
    inserted = (ref_inserted, cand_stats.get("inserted"))
    teleports = (ref_stats.get("teleports"), cand_stats.get("teleports"))
    speed = edge_speed_correlation(reference["edges"], candidate["edges"], weighted_speed)
    entered = edge_entered_correlation(reference["edges"], candidate["edges"])
    cpu_ratio = None
    if reference.get("cpu_s") and candidate.get("cpu_s") is not None:
        cpu_ratio = candidate["cpu_s"] / reference["cpu_s"]
    return {
        "loaded": {"reference": ref_stats.get("loaded"), "candidate": cand_stats.get("loaded")},
        "inserted": {"reference": inserted[0], "candidate": inserted[1],
                     "relative_difference": relative_difference(inserted[1], inserted[0])},
        "arrived": {"reference": ref_trips.arrived, "candidate": cand_trips.arrived,
                    "relative_difference": relative_difference(cand_trips.arrived, ref_trips.arrived),
                    "arrived_by_both": len(ref_trips.ids & cand_trips.ids),
                    "reference_off_road": ref_trips.off_road},
        "duration": {"reference": ref_dur, "candidate": cand_dur,
                     "relative_difference_of_mean": relative_difference(cand_dur["mean"], ref_dur["mean"])},
        "edge_speed": speed,
        "edge_entered": entered,
        "teleports": {"reference": teleports[0], "candidate": teleports[1]},
        "cpu_s": {"reference": reference.get("cpu_s"), "candidate": candidate.get("cpu_s"), "ratio": cpu_ratio},
        "targets": evaluate_targets(inserted, (ref_trips.arrived, cand_trips.arrived),
                                    (ref_dur["mean"], cand_dur["mean"]), speed["r"], teleports),
    }

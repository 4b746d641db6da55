"""Comparison metrics between a reference run (SUMO) and a candidate run (LPSim), standard library only."""
import math

# Targets from the validation issue: the candidate's arrived count within 2 % of SUMO's, mean trip duration
# within 15 %, per-edge mean speed correlated with r >= 0.8.
ARRIVED_TOLERANCE = 0.02
DURATION_TOLERANCE = 0.15
SPEED_R_MIN = 0.8


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


def compare_runs(reference, candidate, weighted_speed=False):
    """reference/candidate: dicts with 'trips' (TripInfo), 'edges' ({id: EdgeSample}), 'stats' (inserted,
    teleports ... as parsed) and 'cpu_s'. Returns every number plus PASS/MISS per target."""
    ref_trips, cand_trips = reference["trips"], candidate["trips"]
    ref_dur = duration_summary(ref_trips.durations)
    cand_dur = duration_summary(cand_trips.durations)
    arrived_rel = relative_difference(cand_trips.arrived, ref_trips.arrived)
    duration_rel = relative_difference(cand_dur["mean"], ref_dur["mean"])
    speed = edge_speed_correlation(reference["edges"], candidate["edges"], weighted_speed)
    entered = edge_entered_correlation(reference["edges"], candidate["edges"])
    cpu_ratio = None
    if reference.get("cpu_s") and candidate.get("cpu_s") is not None:
        cpu_ratio = candidate["cpu_s"] / reference["cpu_s"]
    common_ids = ref_trips.ids & cand_trips.ids
    return {
        "inserted": {"reference": reference["stats"].get("inserted"), "candidate": candidate["stats"].get("inserted")},
        "arrived": {"reference": ref_trips.arrived, "candidate": cand_trips.arrived, "relative_difference": arrived_rel,
                    "arrived_by_both": len(common_ids)},
        "duration": {"reference": ref_dur, "candidate": cand_dur, "relative_difference_of_mean": duration_rel},
        "edge_speed": speed,
        "edge_entered": entered,
        "teleports": {"reference": reference["stats"].get("teleports"), "candidate": candidate["stats"].get("teleports")},
        "cpu_s": {"reference": reference.get("cpu_s"), "candidate": candidate.get("cpu_s"), "ratio": cpu_ratio},
        "targets": {
            "arrived": verdict(None if arrived_rel is None else abs(arrived_rel) <= ARRIVED_TOLERANCE),
            "duration": verdict(None if duration_rel is None else abs(duration_rel) <= DURATION_TOLERANCE),
            "speed_r": verdict(None if speed["r"] is None else speed["r"] >= SPEED_R_MIN),
        },
    }

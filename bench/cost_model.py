#!/usr/bin/env python3
"""A bulk-synchronous cost model of the partitioned engine, fitted to bench/scaling_bench.sh's runs, and its
projection to K GPUs on the 9M-trip day (the LPSim paper's kind of projection: a model, not a measurement).

Per step every part computes its vehicles' passes, then makes R rounds of exchanges with its neighbours:
    T(K) = U / (K * rate) * imbalance + S * R * (latency + staging) + S * bytes(K) / bandwidth
where U vehicle-updates over S steps, `rate` one device's vehicle-updates per second, `imbalance` the slowest
part's compute over the mean part's, `latency` a round's cost on the interconnect, `staging` the device-host
copies a GPU rank adds to each round (Debian's OpenMPI is not CUDA-aware), `bytes(K)` a part's bytes per step.

Fitted here (from the logs of the scaling benchmark, one thread per part): compute per vehicle-update, the
compute imbalance of the parts, the cost of a round in-process and over MPI (the exchange time of the part
that waits least, per round: the exchange cost on the critical path), and bytes per part and step, which are
scaled with the cut lanes per part at K (the partition benchmark's METIS cut lanes) and with the demand.

Usage: bench/cost_model.py [--logs bench/work/scaling] [--fitted-steps 3600] [--gpu-rate 5.06e8] [--updates 4.99e10] [--steps 86400]
       [--demand-scale 9] [--latency 5e-6] [--staging 2e-5] [--bandwidth 1e10]
"""
import argparse
import glob
import re
import statistics

# METIS cut lanes of the regional network per K (docs/PERFORMANCE.md, "Partition quality", f3dcb71).
CUT_LANES = {2: 196, 4: 536, 8: 960, 16: 2299, 32: 4135, 64: 8147}
PART = re.compile(r"Part (\d+): vehicle updates (\d+), migrations out (\d+), exchanged ([0-9.]+) MB in (\d+) "
                  r"rounds, step ([0-9.]+)s of which exchanges ([0-9.]+)s")


def fit(paths, fitted_steps):
    compute_per_update, imbalance, round_cost, bytes_per_step, rounds_per_step = [], [], [], [], []
    for path in paths:
        parts = [dict(updates=int(m[2]), mb=float(m[4]), rounds=int(m[5]), step=float(m[6]), exchange=float(m[7]))
                 for m in PART.finditer(open(path).read())]
        if not parts:
            continue
        compute = [p["step"] - p["exchange"] for p in parts]
        compute_per_update.append(sum(compute) / sum(p["updates"] for p in parts))
        imbalance.append(max(compute) / statistics.mean(compute))
        least = min(parts, key=lambda p: p["exchange"])
        round_cost.append(least["exchange"] / least["rounds"])
        steps = fitted_steps
        rounds_per_step.append(parts[0]["rounds"] / steps)
        bytes_per_step.append(statistics.mean(p["mb"] for p in parts) * 1e6 / steps)
    med = statistics.median
    return dict(compute_per_update=med(compute_per_update), imbalance=med(imbalance), round_cost=med(round_cost),
                bytes_per_step=med(bytes_per_step), rounds_per_step=med(rounds_per_step))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--logs", default="bench/work/scaling")
    ap.add_argument("--fitted-steps", type=int, default=3600, help="steps of the benchmark's runs")
    ap.add_argument("--gpu-rate", type=float, default=5.06e8, help="one H100's vehicle-updates/s (9M day)")
    ap.add_argument("--updates", type=float, default=4.99e10, help="vehicle-updates of the 9M day")
    ap.add_argument("--steps", type=int, default=86400, help="steps of the 9M day (12 h at 0.5 s)")
    ap.add_argument("--demand-scale", type=float, default=9.0, help="9M trips over the fitted run's 1M")
    ap.add_argument("--latency", type=float, default=5e-6, help="a round's cost on a cluster interconnect, s")
    ap.add_argument("--staging", type=float, default=2e-5, help="device-host copies per round of a GPU rank, s")
    ap.add_argument("--bandwidth", type=float, default=1e10, help="interconnect bytes/s")
    a = ap.parse_args()
    fits = {v: fit(sorted(glob.glob(f"{a.logs}/{v}.*.log")), a.fitted_steps) for v in ("inprocess", "mpi")}
    for v, f in fits.items():
        print(f"fitted ({v}, 2 parts, CPU): {f['compute_per_update'] * 1e9:.0f} ns per vehicle-update, "
              f"compute imbalance {f['imbalance']:.3f}, {f['round_cost'] * 1e6:.1f} us per round, "
              f"{f['rounds_per_step']:.0f} rounds and {f['bytes_per_step'] / 1e3:.2f} kB per part and step")
    f = fits["mpi"]
    print()
    print(f"projection, 9M-trip day ({a.updates:.3g} updates, {a.steps} steps), one H100 = {a.gpu_rate:.3g} updates/s, "
          f"round = {a.latency * 1e6:.0f} us network + {a.staging * 1e6:.0f} us staging, imbalance {f['imbalance']:.3f}:")
    print("| K GPUs | compute s | rounds s | bytes s | total s | speed-up over 1 GPU |")
    print("|---|---|---|---|---|---|")
    one = a.updates / a.gpu_rate
    for k in (1, 8, 16, 32, 64):
        compute = one / k * (f["imbalance"] if k > 1 else 1.0)
        rounds = 0.0 if k == 1 else a.steps * f["rounds_per_step"] * (a.latency + a.staging)
        cut_per_part = CUT_LANES.get(k, 0) * 2 / k
        bytes_k = 0.0 if k == 1 else f["bytes_per_step"] * a.demand_scale * cut_per_part / CUT_LANES[2]
        moved = a.steps * bytes_k / a.bandwidth
        total = compute + rounds + moved
        print(f"| {k} | {compute:.1f} | {rounds:.1f} | {moved:.2f} | {total:.1f} | {one / total:.2f} |")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Reads tools/output_digests.sh's lines (name label output digest) and reports every scenario output whose
runs (threads, backends, part counts) did not all give the same bytes. Exit 1 if any did not."""
import collections
import sys

runs = collections.defaultdict(dict)
for line in open(sys.argv[1]) if len(sys.argv) > 1 else sys.stdin:
    name, label, output, digest = line.split()
    runs[(name, output)][label] = digest
bad = 0
for (name, output), by_label in sorted(runs.items()):
    if len(set(by_label.values())) > 1:
        bad += 1
        ref = by_label.get("cpu-t1")
        differ = sorted(l for l, d in by_label.items() if d != ref)
        print(f"{name} {output}: differs from cpu-t1 in {' '.join(differ)}")
print(f"{len(runs)} scenario outputs, {bad} not identical across runs")
sys.exit(1 if bad else 0)

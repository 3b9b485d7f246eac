"""Measures rocking.dask on a LocalCluster (loopback only): the overhead per
task, and the speedup of a 100 x 100 outcome map on 2 workers against 1.

    python examples/dask_benchmark.py [--repeats 3] [--cells 100]

Overhead per task: a full map (`full=True`: every cell in one batch) of
2 x 200 cells split into 200 tasks on one single-thread worker, against
the same map computed locally on one thread; the
difference divided by the number of tasks is what Dask adds to each
(scheduling, pickling the scene and the results, the worker's bookkeeping).
Speedup: the map (window τ 100–200, 4 chunks per worker thread) on 1 worker
and on 2 workers of one thread each; medians of `--repeats` runs.
"""

from __future__ import annotations

import argparse
import statistics
import time

import rocking
import rocking.dask


def timed(f, repeats: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main() -> None:
    from dask.distributed import Client, LocalCluster

    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cells", type=int, default=100, help="cells per axis of the speedup map")
    args = ap.parse_args()
    scene = rocking.Scene("fig3")
    window = {"transient": 100.0, "tau_end": 200.0}

    # Overhead per task: 200 tasks of 2 cells each, in one batch.
    rows = 200
    x, y = ("excitation.a_h", 0.5, 1.0, 2), ("excitation.omega_h", 6.0, 10.0, rows)
    local_time, local = timed(lambda: rocking.outcome_map(scene, x, y, threads=1, full=True, progress=False, **window), args.repeats)
    with LocalCluster(n_workers=1, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster, Client(cluster) as client:
        rocking.dask.outcome_map(client, scene, x, y, full=True, chunks=2, progress=False, **window)  # warm the worker (imports)
        dask_time, remote = timed(
            lambda: rocking.dask.outcome_map(client, scene, x, y, full=True, chunks=rows, progress=False, **window), args.repeats
        )
    assert remote.cells.equals(local.cells)
    print(f"overhead: {rows} tasks in {dask_time:.3f} s on 1 worker vs {local_time:.3f} s locally on 1 thread: "
          f"{1e3 * (dask_time - local_time) / rows:.2f} ms per task")

    # Speedup of an n x n map, 1 vs 2 single-thread workers.
    n = args.cells
    x, y = ("excitation.a_h", 0.1, 3.0, n), ("excitation.omega_h", 6.0, 12.0, n)
    times = {}
    results = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster, Client(cluster) as client:
            rocking.dask.outcome_map(client, scene, x, ("excitation.omega_h", 6.0, 12.0, 2), chunks=2, progress=False, **window)  # warm up
            times[workers], results[workers] = timed(
                lambda: rocking.dask.outcome_map(client, scene, x, y, progress=False, **window), args.repeats
            )
    assert results[1].cells.equals(results[2].cells)
    print(f"{n} x {n} map: 1 worker {times[1]:.2f} s, 2 workers {times[2]:.2f} s (medians of {args.repeats}): "
          f"speedup {times[1] / times[2]:.2f}")


if __name__ == "__main__":
    main()

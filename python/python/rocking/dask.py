"""Sweeps and outcome maps on a Dask cluster (`dask.distributed`).

    >>> from dask.distributed import Client
    >>> import rocking, rocking.dask
    >>> client = Client("scheduler:8786")          # or Client(LocalCluster())
    >>> m = rocking.dask.outcome_map(client, "fig3", ("excitation.a_h", 0.1, 3.0, 100),
    ...                              ("excitation.omega_h", 2.0, 12.0, 100))

The work is split into chunks (shards of a sweep's grid, as
`rocking sweep --shard K/N` splits it; each batch of a map's cells, which
the map's engine hands out on the client), each computed on a worker by
the same library call as on one machine, and joined in index order: the
result is identical, number for number, to `rocking.sweep` and
`rocking.outcome_map`. The input is checked on the client first, so bad
input fails at once with the CLI's message. Workers need `rocking`
installed and, for record scenes, the record files at the same paths.

A value that fails on a worker raises its `RunError` on the client; when
several chunks of a sweep or fragility study fail, the one raised is the
first Dask reports, not necessarily the failure with the smallest index
that `rocking.sweep` (like the CLI) would name. A map names the same
failed cell as `rocking.outcome_map`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterator

from . import _rocking
from ._results import Fragility, OutcomeMap, Sweep
from ._rocking import Scene

if TYPE_CHECKING:
    from . import Progress

Axis = tuple[str, float, float, int]


def _scene(scene: Scene | str) -> Scene:
    return scene if isinstance(scene, Scene) else Scene(scene)


def _tau_end(scene: Scene, tau_end: float | None) -> float:
    from . import _tau_end as resolved

    return resolved(scene, tau_end)


def _worker_threads(client: Any) -> int:
    """Threads over all workers of the cluster (at least 1)."""
    return max(1, sum(client.nthreads().values()))


def _sweep_task(shard: tuple[int, int], scene: Scene, args: tuple[Any, ...], options: dict[str, Any]) -> dict[str, Any]:
    """One shard of a sweep, on a worker."""
    return _rocking._sweep(scene, *args, shard=shard, **options)


def _cells_task(
    indices: list[int], known: list[Any], labels: Any, scene: Scene, x: Axis, y: Axis, options: dict[str, Any]
) -> dict[str, Any]:
    """Cells `indices` of a map, on a worker, packed in arrays; a run stops
    on reaching one of the `known` attractors' cycles or their `labels`
    (a basin map's, or None), as on the client."""
    return _rocking._outcome_cells(scene, x, y, indices, known=known, labels=labels, **options)


def sweep(
    client: Any,
    scene: Scene | str,
    param: str,
    start: float,
    stop: float,
    step: float,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    chunks: int | None = None,
    threads_per_task: int = 1,
) -> Sweep:
    """`rocking.sweep` on the cluster behind `client`, split into `chunks`
    shards (default: 4 per worker thread, at most one per value). Each
    task uses `threads_per_task` threads (1: Dask's worker threads are the
    parallelism). Continuation sweeps cannot be split (each value seeds
    the next): run them with `rocking.sweep`."""
    s = _scene(scene)
    args = (param, start, stop, step)
    options: dict[str, Any] = {"transient": transient, "tau_end": tau_end, "lyapunov": lyapunov}
    count = int(_rocking._sweep(s, *args, check_only=True, **options)["count"])
    n = chunks if chunks is not None else 4 * _worker_threads(client)
    n = max(1, min(int(n), count))
    options["threads"] = threads_per_task
    futures = client.map(
        _sweep_task, [(k, n) for k in range(n)], scene=s, args=args, options=options, pure=False
    )
    return Sweep._assemble(param, client.gather(futures))._keep(
        scene=s,
        start=start,
        stop=stop,
        step=step,
        transient=transient,
        tau_end=_tau_end(s, tau_end),
        continuation="none",
        lyapunov_asked=lyapunov,
    )


def _split(indices: list[int], chunks: int) -> list[list[int]]:
    """`indices` split into `chunks` contiguous runs of nearly equal length."""
    chunks = max(1, min(chunks, len(indices)))
    bounds = [len(indices) * i // chunks for i in range(chunks + 1)]
    return [indices[bounds[i] : bounds[i + 1]] for i in range(chunks)]


def outcome_map(
    client: Any,
    scene: Scene | str,
    x: Axis,
    y: Axis,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    full: bool = False,
    coarse: int = 32,
    chunks: int | None = None,
    threads_per_task: int = 1,
    progress: Progress = None,
) -> OutcomeMap:
    """`rocking.outcome_map` on the cluster behind `client`. The map's
    engine runs here, on the client, as it does on one machine: it hands
    out batches of cells (with refinement, the coarse lattice first, then
    the cells where classes meet; with `full=True`, every cell at once),
    each batch is split into `chunks` tasks (default: 4 per worker thread,
    at most one per cell) computed on the workers, and their cells go back
    to the engine. The map is identical to `rocking.outcome_map`'s for any
    chunking. Each task uses `threads_per_task` threads (1: Dask's worker
    threads are the parallelism). `progress`: as for `rocking.outcome_map`,
    reported as tasks finish. A failed cell raises the `RunError` that
    `rocking.outcome_map` raises (the batch's first failure in cell order)."""
    from distributed import as_completed

    from . import _Reporter

    s = _scene(scene)
    x, y = tuple(x), tuple(y)  # type: ignore[assignment]
    options: dict[str, Any] = {
        "transient": transient,
        "tau_end": tau_end,
        "lyapunov": lyapunov,
        "full": full,
        "coarse": coarse,
    }
    n = chunks if chunks is not None else 4 * _worker_threads(client)

    def executor(indices: list[int], known: list[Any], labels: Any) -> Iterator[dict[str, Any]]:
        # The labels (one int64 per cell) go to every worker once.
        labels = None if labels is None else client.scatter(labels, broadcast=True)
        futures = client.map(
            _cells_task, _split(indices, int(n)), known=known, labels=labels, scene=s, x=x, y=y,
            options={**options, "threads": threads_per_task}, pure=False,
        )
        try:
            for future in as_completed(futures):
                yield future.result()
        finally:
            # Stopped early (a failure, Ctrl-C): the rest is not needed.
            client.cancel(futures)

    with _Reporter(progress, "outcome_map") as report:
        data = _rocking._outcome_map(s, x, y, **options, executor=executor, progress=report)
    return OutcomeMap._of(data)._keep(
        scene=s, x_axis=x, y_axis=y, transient=transient, tau_end=_tau_end(s, tau_end), lyapunov_asked=lyapunov,
        full=full, coarse=coarse,
    )


def _fragility_task(indices: list[int], scene: Scene, args: tuple[Any, ...], options: dict[str, Any]) -> dict[str, Any]:
    """Runs `indices` of a fragility study, on a worker."""
    return _rocking._fragility_runs(scene, *args, indices=indices, **options)


def fragility(
    client: Any,
    records: Any,
    levels: Any,
    blocks: Any = None,
    *,
    base: Scene | None = None,
    im: str = "pga",
    sa_period: float | None = None,
    vertical: str | None = None,
    threshold: float = 0.5,
    chunks: int | None = None,
    threads_per_task: int = 1,
) -> Fragility:
    """`rocking.fragility` on the cluster behind `client`: the runs split
    into `chunks` interleaved sets (default: 4 per worker thread), the fits
    computed on the client from all rows."""
    from . import _records

    given = list(records)
    s = base if base is not None else Scene.defaults()
    levels = [float(v) for v in levels]
    blocks = _rocking._fragility_blocks(s, None if blocks is None else [(float(w), float(h)) for w, h in blocks], im)
    args = (_records(given), levels, blocks)
    count = int(_rocking._fragility_runs(s, *args, im=im, sa_period=sa_period, vertical=vertical, check_only=True)["count"])
    n = chunks if chunks is not None else 4 * _worker_threads(client)
    n = max(1, min(int(n), count))
    options: dict[str, Any] = {"im": im, "sa_period": sa_period, "vertical": vertical, "threads": threads_per_task}
    parts = [list(range(k, count, n)) for k in range(n)]
    futures = client.map(_fragility_task, parts, scene=s, args=args, options=options, pure=False)
    parts = client.gather(futures)
    return Fragility._assemble(parts, len(blocks), levels, threshold)._keep(
        base=s, records=given, record_names=list(parts[0]["records"]), blocks=blocks
    )

"""rocking: exact event-driven simulation of a rigid block that rocks,
slides, slide-rocks, lifts off and tumbles on a shaken base.

    >>> import rocking
    >>> scene = rocking.Scene("fig3", a_h="0.35 g")
    >>> run = rocking.simulate(scene)
    >>> run.t, run.theta_rad, run.summary["outcome"]

Scenes are built by the CLI's config layer (same keys, units and
messages); runs, sweeps, maps and Lyapunov exponents are the library's,
computed without the GIL on all cores and returned as numpy arrays, with
the same numbers as `rocking --batch`, `rocking sweep` and `rocking map`.
`rocking.dask` runs sweeps and maps on a Dask cluster.

Errors: `ConfigError` (bad input, with `key`, `file`, `line`),
`RecordError` (a record file, a `ConfigError`), `RunError` (a run that
failed), each carrying the CLI's one-line message.
"""

from __future__ import annotations

from typing import Any

from . import _rocking
from ._results import SPECTRUM, Fragility, Lyapunov, OutcomeMap, RockingSpectrum, Run, Sweep
from ._rocking import ConfigError, RecordError, RunError, Scene, __version__, presets
from ._table import Table, table

__all__ = [
    "ConfigError",
    "Fragility",
    "Lyapunov",
    "OutcomeMap",
    "RecordError",
    "RockingSpectrum",
    "Run",
    "RunError",
    "Scene",
    "Sweep",
    "Table",
    "__version__",
    "fragility",
    "lyapunov",
    "outcome_map",
    "presets",
    "simulate",
    "spectrum",
    "sweep",
]

Axis = tuple[str, float, float, int]


def _scene(scene: Scene | str) -> Scene:
    """A scene, or the preset of that name."""
    return scene if isinstance(scene, Scene) else Scene(scene)


def simulate(scene: Scene | str) -> Run:
    """One run of `scene` (or of the preset of that name), as `rocking --batch`
    makes it: the time history, events, Poincaré section and summary.json,
    with `analysis.lyapunov` and `analysis.spectrum` when the scene asks
    for them. Releases the GIL while it runs."""
    s = _scene(scene)
    return Run(s, _rocking._simulate(s))


def sweep(
    scene: Scene | str,
    param: str,
    start: float,
    stop: float,
    step: float,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    continuation: str = "none",
    lyapunov: bool = False,
    threads: int | None = None,
) -> Sweep:
    """The bifurcation diagram of config key `param` (e.g. "excitation.a_v")
    over `start, start + step, …` up to `stop` (within half a step), as
    `rocking sweep --param … --from … --to … --step …`: Poincaré points at
    `transient ≤ τ_k ≤ tau_end` (default: the scene's run.tau_end), each
    value classified. `continuation` is "none" (every value from the
    scene's initial state, in parallel), "up" or "down" (each value from
    the previous one's final state). `lyapunov` adds the largest exponent
    of each value. `threads`: worker threads (default one per core).
    Ctrl-C stops it between chunks."""
    s = _scene(scene)
    data = _rocking._sweep(
        s,
        param,
        start,
        stop,
        step,
        transient=transient,
        tau_end=tau_end,
        continuation=continuation,
        lyapunov=lyapunov,
        threads=threads,
    )
    return Sweep._assemble(param, [data])


def outcome_map(
    scene: Scene | str,
    x: Axis,
    y: Axis,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    threads: int | None = None,
) -> OutcomeMap:
    """The outcome map over `x = (key, first, last, count)` and `y` (same),
    as `rocking map --x … --y …`: each cell's steady response from the
    scene's initial state (Poincaré points at `transient ≤ τ_k ≤ tau_end`),
    with its largest Lyapunov exponent if `lyapunov`. Ctrl-C stops it
    between rows."""
    s = _scene(scene)
    data = _rocking._outcome_map(
        s, tuple(x), tuple(y), transient=transient, tau_end=tau_end, lyapunov=lyapunov, threads=threads
    )
    return OutcomeMap._assemble([data])


def lyapunov(scene: Scene | str, method: str | None = None) -> Lyapunov:
    """The Lyapunov exponents of `scene` over its run (discarding
    min(600, tau_end/2) of transient), as `analysis.lyapunov = true`
    computes them; `method` is "tangent", "benettin" or "both" (default:
    the scene's analysis.lyapunov_method)."""
    s = _scene(scene)
    # Checked as `--set analysis.lyapunov=true` is: a scene without harmonic
    # excitation, or an unknown method, is refused with the CLI's message.
    analysis: dict[str, object] = {"lyapunov": True}
    if method is not None:
        analysis["lyapunov_method"] = method
    return Lyapunov._of(_rocking._lyapunov(s.with_(analysis=analysis)))




def _records(records: Any) -> list[tuple[str, str | None]]:
    """Records as (path, unit or None): a path alone, or (path, unit)."""
    out = []
    for r in records:
        if isinstance(r, tuple):
            out.append((str(r[0]), r[1]))
        else:
            out.append((str(r), None))
    return out


def fragility(
    records: Any,
    levels: Any,
    blocks: Any,
    *,
    base: Scene | None = None,
    im: str = "pga",
    threshold: float = 0.5,
    threads: int | None = None,
) -> Fragility:
    """Fragility curves, as `rocking fragility`: every block (width, height
    in m) under every record (a path, or (path, unit) for text records)
    scaled to every intensity level (`im` "pga" in g or "pgv" in m/s); then
    per block the lognormal fits of P(overturning) and P(θ/α ≥ `threshold`
    or overturning). `base` gives friction, impact law, tolerances and the
    record tail (its block and excitation are replaced); default
    `Scene.defaults()`, the CLI's base without --preset. Ctrl-C stops it
    between chunks of runs."""
    s = base if base is not None else Scene.defaults()
    levels = [float(v) for v in levels]
    blocks = [(float(w), float(h)) for w, h in blocks]
    data = _rocking._fragility_runs(s, _records(records), levels, blocks, im=im, threads=threads)
    return Fragility._assemble([data], len(blocks), levels, threshold)


def spectrum(
    record: Any,
    sizes: tuple[float, float, int],
    *,
    unit: str | None = None,
    size: str = "r",
    b_over_h: Any = (0.25,),
    scale: float | None = None,
    pga: float | None = None,
    overturn_scale: bool = False,
    search_step: float = 0.1,
    search_max: float = 5.0,
    rel_tol: float = 1e-3,
    base: Scene | None = None,
    threads: int | None = None,
) -> RockingSpectrum:
    """The rocking spectrum of a record, as `rocking spectrum --record`:
    the peak θ/α (and end: rest, moving, overturned, flight) of blocks of
    `sizes = (from_m, to_m, count)` log-spaced half-diagonals R (`size="r"`)
    or heights H (`"h"`) for each B/H in `b_over_h`, under the record (in
    `unit` for text files) scaled by `scale` or to `pga` (g); with
    `overturn_scale`, each block's smallest overturning scale factor.
    `base` as for `fragility`. Ctrl-C stops it between B/H ratios."""
    s = base if base is not None else Scene.defaults()
    data = _rocking._spectrum(
        s,
        str(record),
        tuple(sizes),
        unit=unit,
        size=size,
        b_over_h=[float(v) for v in b_over_h],
        scale=scale,
        pga=pga,
        overturn_scale=overturn_scale,
        search_step=search_step,
        search_max=search_max,
        rel_tol=rel_tol,
        threads=threads,
    )
    return RockingSpectrum(table(data, SPECTRUM), float(data["pga_g_record"]))


def __dir__() -> list[str]:
    return sorted(__all__)


def __getattr__(name: str) -> Any:
    # `rocking.dask` is imported on first use: dask stays optional.
    if name == "dask":
        import importlib

        return importlib.import_module(".dask", __name__)
    raise AttributeError(f"module 'rocking' has no attribute {name!r}")

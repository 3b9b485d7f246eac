"""rocking: exact event-driven simulation of a rigid block that rocks,
slides, slide-rocks, lifts off and tumbles on a shaken base.

    >>> import rocking
    >>> scene = rocking.Scene("fig3", a_h="0.35 g")     # a unit, or a_h_norm=1.2
    >>> run = rocking.simulate(scene)
    >>> run.t, run.theta_rad, run.summary["outcome"]

Scenes are built by the CLI's config layer (same keys, units and
messages); runs, sweeps, maps and Lyapunov exponents are the library's,
computed without the GIL on all cores and returned as numpy arrays, with
the same numbers as `rocking --batch`, `rocking sweep` and `rocking map`.
`rocking.dask` runs sweeps and maps on a Dask cluster.

Units: a bare number is accepted only in SI units (sizes in m, times in
s), dimensionless, or under a name that says it is normalised (`tau_end`,
`a_h_norm`, …); `help(rocking.Scene)` lists every key with its units.

Long calls (sweeps, maps, fragility, spectra) show progress: a tqdm bar
when tqdm is installed, else a line on stderr every few seconds once a
call has run for 2 s; `progress=callable` gets `(done, total)` instead,
`progress=False` silences it.

Errors: `ConfigError` (bad input, with `key`, `file`, `line`),
`RecordError` (a record file, a `ConfigError`), `RunError` (a run that
failed), each carrying the CLI's one-line message.
"""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, Union

from . import _rocking
from ._results import (
    SLIDING,
    SPECTRUM,
    Fragility,
    Lyapunov,
    OutcomeMap,
    RockingSpectrum,
    Run,
    SlidingSpectrum,
    StackRun,
    Sweep,
)
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
    "SlidingSpectrum",
    "StackRun",
    "Sweep",
    "Table",
    "__version__",
    "fragility",
    "lyapunov",
    "outcome_map",
    "presets",
    "simulate",
    "sliding_spectrum",
    "spectrum",
    "sweep",
]

Axis = tuple[str, float, float, int]

#: `progress=`: None or True (a tqdm bar, else lines on stderr), False
#: (silent), or a callable given `(done, total)` between chunks.
Progress = Union[bool, None, Callable[[int, int], Any]]

# help(rocking.Scene): every key with its units, from the key list the
# config layer accepts (one source for the names).
try:
    Scene.__doc__ = f"{Scene.__doc__}\n\n{_rocking._keys_help()}"
except (AttributeError, TypeError):  # pragma: no cover - an immutable type
    pass


class _StderrProgress:
    """Progress as a line on stderr: only once a call has run for
    `after_s`, then every `every_s`, with an estimate of the time left."""

    def __init__(self, what: str, after_s: float = 2.0, every_s: float = 5.0) -> None:
        self.what, self.after_s, self.every_s = what, after_s, every_s
        self.start = time.monotonic()
        self.last: float | None = None
        self.state = (0, 0)

    def __call__(self, done: int, total: int) -> None:
        self.state = (done, total)
        now = time.monotonic()
        elapsed = now - self.start
        if elapsed < self.after_s or (self.last is not None and now - self.last < self.every_s):
            return
        self.last = now
        left = f", about {elapsed * (total - done) / done:.0f} s left" if 0 < done < total else ""
        print(f"rocking.{self.what}: {done}/{total} done in {elapsed:.0f} s{left}", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.last is not None:
            done, total = self.state
            print(f"rocking.{self.what}: {done}/{total} done in {time.monotonic() - self.start:.0f} s", file=sys.stderr, flush=True)


class _TqdmProgress:
    """Progress as a tqdm bar."""

    def __init__(self, tqdm: Any, what: str) -> None:
        self.bar = tqdm(desc=f"rocking.{what}", total=None, leave=False)

    def __call__(self, done: int, total: int) -> None:
        if self.bar.total != total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)

    def close(self) -> None:
        self.bar.close()


class _Reporter:
    """`progress=` as the callable the extension calls, closed after the call."""

    def __init__(self, progress: Progress, what: str) -> None:
        self.callback: Callable[[int, int], Any] | None
        self.sink: Any = None
        if progress is False:
            self.callback = None
        elif progress is None or progress is True:
            try:
                from tqdm.auto import tqdm
            except ImportError:
                self.sink = _StderrProgress(what)
            else:
                self.sink = _TqdmProgress(tqdm, what)
            self.callback = self.sink
        elif callable(progress):
            self.callback = progress
        else:
            raise TypeError(f"progress={progress!r}: expected True, False, None or a callable taking (done, total)")

    def __enter__(self) -> Callable[[int, int], Any] | None:
        return self.callback

    def __exit__(self, *exc: object) -> None:
        if self.sink is not None:
            self.sink.close()


def _tau_end(scene: Scene, tau_end: float | None) -> float:
    """The window's end a study used: `tau_end`, else the scene's run's."""
    return float(tau_end) if tau_end is not None else float(scene.to_dict()["run"]["tau_end"])


def _scene(scene: Scene | str) -> Scene:
    """A scene, or the preset of that name."""
    return scene if isinstance(scene, Scene) else Scene(scene)


def simulate(scene: Scene | str) -> Run | StackRun:
    """One run of `scene` (or of the preset of that name), as `rocking --batch`
    makes it: the time history, events, Poincaré section and summary.json,
    with `analysis.lyapunov` and `analysis.spectrum` when the scene asks
    for them. A scene with a `[[stack]]` (e.g. the `tombstone` preset)
    gives a `StackRun`: each body's columns, and no section. Releases the
    GIL while it runs; Ctrl-C stops it at once (KeyboardInterrupt)."""
    s = _scene(scene)
    data = _rocking._simulate(s)
    if "blocks" in data:
        return StackRun(s, data)
    return Run(s, data)


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
    progress: Progress = None,
) -> Sweep:
    """The bifurcation diagram of config key `param` (e.g. "excitation.a_v")
    over `start, start + step, …` up to `stop` (within half a step), as
    `rocking sweep --param … --from … --to … --step …`: Poincaré points at
    `transient ≤ τ_k ≤ tau_end` (default: the scene's run.tau_end), each
    value classified. `continuation` is "none" (every value from the
    scene's initial state, in parallel), "up" or "down" (each value from
    the previous one's final state). `lyapunov` adds the largest exponent
    of each value. `threads`: worker threads (default one per core).
    Values are in the config key's own bare unit (normalised, as
    `rocking sweep --from/--to/--step`). A `[[stack]]` scene (e.g.
    "stack-patterns") is classified over every interface and its points are
    its top block's (`theta` = φ/α of the top block); it varies excitation
    and run keys only, from rest, without `continuation` or `lyapunov`.
    `progress`: see the module's help. Ctrl-C stops it between chunks."""
    s = _scene(scene)
    with _Reporter(progress, "sweep") as report:
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
            progress=report,
        )
    return Sweep._assemble(param, [data])._keep(
        scene=s,
        start=start,
        stop=stop,
        step=step,
        transient=transient,
        tau_end=_tau_end(s, tau_end),
        continuation=continuation,
        lyapunov_asked=lyapunov,
    )


def outcome_map(
    scene: Scene | str,
    x: Axis,
    y: Axis,
    *,
    transient: float = 600.0,
    tau_end: float | None = None,
    lyapunov: bool = False,
    threads: int | None = None,
    full: bool = False,
    coarse: int = 32,
    progress: Progress = None,
) -> OutcomeMap:
    """The outcome map over `x = (key, first, last, count)` and `y` (same),
    as `rocking map --x … --y …`: each cell's steady response from the
    scene's initial state (Poincaré points at `transient ≤ τ_k ≤ tau_end`),
    with its largest Lyapunov exponent if `lyapunov`. Same numbers as the
    CLI, cell for cell, for any `threads`.

    By default the map is computed fast, as `rocking map` computes it:
    *early stopping* ends a cell's run as soon as its class is certain (a
    periodic orbit whose section points have recurred long enough, rest,
    tumbling or flight; chaotic and quasi-periodic cells run their whole
    window), and *refinement* computes a lattice of about `coarse` cells
    along the longer axis first, then only the cells near where classes
    meet: a cell inside a neighbourhood of one class inherits that class
    without being run (`computed` false, `max_abs_theta` NaN). An island
    of another class smaller than the map's extent over `coarse` can be
    missed. Without refinement (`lyapunov=True`: an inherited cell would
    have no exponent) every cell is run. `full=True` runs every cell over
    its whole window: the reference, as `rocking map --full` (`coarse` is
    then unused).

    When both axes are initial-state keys (`initial.theta`,
    `initial.theta_dot`, `initial.x_dot`: a basin map), each periodic cell
    is also labelled with the attractor it reaches (`attractor`, numbered
    from 1 in row order of the first cell reaching it; `attractors` lists
    them). There, once the coarser levels have found attractors, a run also
    stops when it follows one of their cycles to 1e-3 of its amplitude for
    a cycle and 4 more periods, or when its section points land ten times
    in a row in cells labelled with one attractor
    (`cells_on_known_attractor` counts them; docs/analysis.md gives the
    criteria and their agreement with `full=True`). A `[[stack]]` scene is
    mapped as `sweep` takes it (its top block's `max_abs_theta`; every
    cell run over its whole window). `progress`: see the module's help (an
    inherited cell counts as done). Ctrl-C stops it between chunks of a few hundred cells."""
    s = _scene(scene)
    with _Reporter(progress, "outcome_map") as report:
        data = _rocking._outcome_map(
            s, tuple(x), tuple(y), transient=transient, tau_end=tau_end, lyapunov=lyapunov, threads=threads,
            full=full, coarse=coarse, progress=report,
        )
    return OutcomeMap._of(data)._keep(
        scene=s, x_axis=tuple(x), y_axis=tuple(y), transient=transient, tau_end=_tau_end(s, tau_end),
        lyapunov_asked=lyapunov, full=full, coarse=coarse,
    )


def lyapunov(scene: Scene | str, method: str | None = None) -> Lyapunov:
    """The Lyapunov exponents of `scene` over its run (discarding
    min(600, tau_end/2) of transient), as `analysis.lyapunov = true`
    computes them; `method` is "tangent", "benettin" or "both" (default:
    the scene's analysis.lyapunov_method). A frame takes all three, as
    the block does; a stack takes "benettin" only: its tangent equations
    are not written, so two trajectories give its largest exponent."""
    s = _scene(scene)
    # Checked as `--set analysis.lyapunov=true` is: a scene without harmonic
    # excitation, or an unknown method, is refused with the CLI's message.
    analysis: dict[str, object] = {"lyapunov": True}
    if method is not None:
        analysis["lyapunov_method"] = method
    return Lyapunov._of(_rocking._lyapunov(s.with_(analysis=analysis)), s)




def _records(records: Any) -> list[tuple[str, str | None, str | None, str | None]]:
    """Records as (path, unit, vertical path, vertical unit), each optional
    part None: a path alone, (path, unit), or (path, unit, vpath, vunit)
    pairing a horizontal with its vertical component."""
    out = []
    for k, r in enumerate(records):
        if isinstance(r, tuple):
            if len(r) == 2:
                out.append((str(r[0]), r[1], None, None))
            elif len(r) == 4:
                out.append((str(r[0]), r[1], None if r[2] is None else str(r[2]), r[3]))
            else:
                raise ConfigError(
                    f"records[{k}]: expected a path, (path, unit) or (path, unit, vertical_path, vertical_unit), "
                    f"got a tuple of {len(r)}"
                )
        else:
            out.append((str(r), None, None, None))
    return out


def fragility(
    records: Any,
    levels: Any,
    blocks: Any = None,
    *,
    base: Scene | None = None,
    im: str = "pga",
    sa_period: float | None = None,
    vertical: str | None = None,
    threshold: float = 0.5,
    threads: int | None = None,
    progress: Progress = None,
) -> Fragility:
    """Fragility curves, as `rocking fragility`: every block (width, height
    in m) under every record (a path, or (path, unit) for text records)
    scaled to every intensity level (`im` "pga" in g, "pgv" in m/s, or the
    dimensionless rocking measures "pga-tan-alpha", PGA/(g tan α), and
    "pgv-p-tan-alpha", PGV·p/(g tan α), which depend on the block, or "sa",
    Sa(T, 5 %) in g at the period `sa_period` in s); then
    per block the lognormal fits of P(overturning) and P(θ/α ≥ `threshold`
    or overturning). A record given as (path, unit, vertical_path,
    vertical_unit) pairs a horizontal with its vertical component, both
    scaled by one factor (the level over the horizontal's intensity);
    `vertical` "record" applies the verticals, "none" runs horizontals only,
    and None (the default) applies them when every record names one, as
    `rocking fragility --vertical`. `base` gives friction, impact law, tolerances and the
    record tail (its block and excitation are replaced); default
    `Scene.defaults()`, the CLI's base without --preset; a `base` with a
    `[[stack]]` runs the stack as given when `blocks` is None, or scaled
    to each block of its own B/H. `progress`: see
    the module's help. Ctrl-C stops it between chunks of runs."""
    s = base if base is not None else Scene.defaults()
    levels = [float(v) for v in levels]
    blocks = _rocking._fragility_blocks(s, None if blocks is None else [(float(w), float(h)) for w, h in blocks], im)
    given = list(records)
    with _Reporter(progress, "fragility") as report:
        data = _rocking._fragility_runs(
            s,
            _records(given),
            levels,
            blocks,
            im=im,
            sa_period=sa_period,
            vertical=vertical,
            threads=threads,
            progress=report,
        )
    return Fragility._assemble([data], len(blocks), levels, threshold)._keep(
        base=s, records=given, record_names=list(data["records"]), blocks=blocks
    )


def spectrum(
    record: Any,
    sizes: tuple[float, float, int],
    *,
    unit: str | None = None,
    record_v: Any = None,
    unit_v: str | None = None,
    size: str = "r",
    b_over_h: Any = None,
    scale: float | None = None,
    pga: float | None = None,
    overturn_scale: bool = False,
    search_step: float = 0.1,
    search_max: float = 5.0,
    rel_tol: float = 1e-3,
    base: Scene | None = None,
    threads: int | None = None,
    progress: Progress = None,
) -> RockingSpectrum:
    """The rocking spectrum of a record, as `rocking spectrum --record`:
    the peak θ/α (and end: rest, moving, overturned, flight) of blocks of
    `sizes = (from_m, to_m, count)` log-spaced half-diagonals R (`size="r"`)
    or heights H (`"h"`) for each B/H in `b_over_h` (default 0.25; a
    `base` scene with a `[[stack]]` is scaled as a whole, keeping its own
    B/H: its bottom width over its total height), under the record (in
    `unit` for text files) scaled by `scale` or to `pga` (g), with its
    vertical component `record_v` (in `unit_v`, default `unit`) scaled by
    the same factor when given; with
    `overturn_scale`, each block's smallest overturning scale factor.
    `base` as for `fragility`. `progress`: see the module's help (counted
    in blocks, reported between B/H ratios). Ctrl-C stops it between B/H
    ratios."""
    s = base if base is not None else Scene.defaults()
    with _Reporter(progress, "spectrum") as report:
        data = _rocking._spectrum(
            s,
            str(record),
            tuple(sizes),
            unit=unit,
            record_v=None if record_v is None else str(record_v),
            unit_v=unit_v,
            size=size,
            b_over_h=None if b_over_h is None else [float(v) for v in b_over_h],
            scale=scale,
            pga=pga,
            overturn_scale=overturn_scale,
            search_step=search_step,
            search_max=search_max,
            rel_tol=rel_tol,
            threads=threads,
            progress=report,
        )
    return RockingSpectrum(table(data, SPECTRUM), float(data["pga_g_record"]))._keep(
        base=s,
        record=record,
        sizes=tuple(sizes),
        size=size,
        b_over_h=tuple(sorted({float(v) for v in data["b_over_h"]})),
        scale=scale,
        pga=pga,
    )


def sliding_spectrum(
    record: Any,
    mu: Any,
    *,
    unit: str | None = None,
    block: tuple[float, float] | None = None,
    kinetic_ratio: float = 1.0,
    scale: float | None = None,
    pga: float | None = None,
    base: Scene | None = None,
    threads: int | None = None,
    progress: Progress = None,
) -> SlidingSpectrum:
    """The sliding spectrum of a record, as `rocking sliding-spectrum
    --record`: the peak and residual sliding displacement (m) at each
    friction coefficient of `mu` (μ_s, increasing; μ_k = `kinetic_ratio`
    μ_s) of the block that cannot rock (rigid-plastic sliding) and of
    `block` = (width, height) in m (default: the base scene's block), under
    the record (in `unit` for text files) scaled by `scale` or to `pga`
    (g). `base` as for `fragility` (its friction and excitation are
    replaced). `progress`: see the module's help (counted in coefficients).
    Ctrl-C stops it between chunks of coefficients."""
    s = base if base is not None else Scene.defaults()
    mu = [float(v) for v in mu]
    given = None if block is None else (float(block[0]), float(block[1]))
    with _Reporter(progress, "sliding_spectrum") as report:
        data = _rocking._sliding_spectrum(
            s,
            str(record),
            mu,
            unit=unit,
            block=given,
            kinetic_ratio=float(kinetic_ratio),
            scale=scale,
            pga=pga,
            threads=threads,
            progress=report,
        )
    return SlidingSpectrum(table(data, SLIDING), float(data["pga_g_record"]), float(data["scale"]))._keep(
        base=s, record=record, mu=tuple(mu), unit=unit, block=given, kinetic_ratio=float(kinetic_ratio), scale=scale, pga=pga
    )


def __dir__() -> list[str]:
    return sorted(__all__)


def __getattr__(name: str) -> Any:
    # `rocking.dask` and `rocking.records` are imported on first use: dask
    # and the packages that hold record sets stay optional.
    if name in ("dask", "records"):
        import importlib

        return importlib.import_module(".dask", __name__)
    raise AttributeError(f"module 'rocking' has no attribute {name!r}")

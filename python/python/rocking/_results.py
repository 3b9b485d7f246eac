"""The result types of `simulate`, `sweep`, `outcome_map` and `lyapunov`.

They only arrange what the extension computed: columns into numpy arrays
and structured `Table`s (the CLI's CSV columns, same names and numbers),
and chunks computed apart (Dask) back into one result, identical to the
single-machine one (a map's cells computed apart are put together by the
extension's map engine). A value that does not exist (no overturning, no
exponent) is NaN in a float column and masked in the masked-array
properties, never 0; a missing period (an int column) is masked. Each
result keeps its inputs (`scene`, the grid, `transient`, `tau_end`,
`records`, …) and converts to pandas (`to_pandas()`) and, where it is a
grid, to xarray (`to_xarray()`) when those are installed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

from ._table import Table, concat, names, table

HISTORY = ("tau", "theta", "theta_dot", "x", "x_dot", "mode", "t_s", "theta_rad", "sliding_m")
EVENTS = (
    "tau",
    "kind",
    "mode_before",
    "mode_after",
    "theta",
    "theta_dot_before",
    "theta_dot_after",
    "x_dot",
    "t_s",
    "theta_rad",
    "sliding_m",
)
POINCARE = ("k", "tau", "theta", "theta_dot", "x", "x_dot", "mode")
POINTS = ("index", "value", "k", "tau", "theta", "theta_dot", "x", "x_dot", "mode")
CLASSES = ("index", "value", "outcome", "period", "max_abs_theta", "lyapunov", "has_lyapunov")
CELLS = ("x", "y", "outcome", "period", "max_abs_theta", "lyapunov", "has_lyapunov", "attractor", "computed")


def _with_extra(order: Sequence[str], columns: Mapping[str, Any]) -> tuple[str, ...]:
    """`order`, then the columns of `columns` it does not name, in their own order."""
    return tuple(order) + tuple(k for k in columns if k not in order)


class Run:
    """One run, as `rocking --batch` writes it.

    `history`, `events` and `poincare` are structured arrays with the
    columns of history.csv, events.csv and poincare.csv (normalised
    `tau`, `theta` = θ/ψ, `x` = x/R … and physical `t_s` in s, `theta_rad`
    in rad, `sliding_m` in m); `summary` is summary.json as a dict. The
    attributes `t`, `tau`, `theta`, … are the history's columns.
    """

    def __init__(self, scene: Any, data: Mapping[str, Any]) -> None:
        self.scene = scene
        #: summary.json as a dict (same keys and numbers as the CLI's file).
        self.summary: dict[str, Any] = data["summary"]
        #: The regular time history (history.csv's columns).
        #: A frame's adds each body's columns after the block's, as its CSV.
        self.history: Table = table(data["history"], _with_extra(HISTORY, data["history"]))
        #: Every event (events.csv's columns; a frame's with `body`).
        self.events: Table = table(data["events"], _with_extra(EVENTS, data["events"]))
        #: The stroboscopic section at τ_k = 2πk/Ω_h (poincare.csv's columns).
        self.poincare: Table = table(data["poincare"], POINCARE)

    @property
    def t(self) -> np.ndarray:
        """Time of each history row, s."""
        return self.history["t_s"]

    @property
    def tau(self) -> np.ndarray:
        """Normalised time τ = p·t of each history row."""
        return self.history["tau"]

    @property
    def theta(self) -> np.ndarray:
        """Normalised rotation Θ = θ/ψ."""
        return self.history["theta"]

    @property
    def theta_rad(self) -> np.ndarray:
        """Rotation θ, rad."""
        return self.history["theta_rad"]

    @property
    def theta_dot(self) -> np.ndarray:
        """Normalised angular velocity dΘ/dτ."""
        return self.history["theta_dot"]

    @property
    def x(self) -> np.ndarray:
        """Normalised horizontal position of the centre of mass X = x/R."""
        return self.history["x"]

    @property
    def x_dot(self) -> np.ndarray:
        """Normalised horizontal velocity dX/dτ."""
        return self.history["x_dot"]

    @property
    def sliding_m(self) -> np.ndarray:
        """Sliding displacement of the base contact, m (+x to the right)."""
        return self.history["sliding_m"]

    @property
    def mode(self) -> np.ndarray:
        """Contact mode of each history row (rest, slide, rock, slide-rock, tumbled, flight)."""
        return self.history["mode"]

    @property
    def outcome(self) -> str:
        """How the run ended: running, rest, tumbled or flight."""
        return str(self.summary["outcome"])

    def __repr__(self) -> str:
        return (
            f"rocking.Run(outcome={self.outcome!r}, tau_end={self.summary['tau_end']!r}, "
            f"{len(self.history)} history rows, {len(self.events)} events, {len(self.poincare)} section points)"
        )


STACK_EVENTS = (
    "tau",
    "t_s",
    "kind",
    "body",
    "mode_before",
    "mode_after",
    "q_dot_before_rad_s",
    "q_dot_after_rad_s",
)


class StackRun:
    """One run of a stack of blocks (a scene with `[[stack]]`), as
    `rocking --batch` writes it.

    `history` has history.csv's columns: `tau`, `t_s`, `mode` (every
    face's contact, bottom to top: `rock-left/closed`, the bottom one
    `slide…` while the stack slides on its floor), `sliding_m` (the
    stack's displacement along the floor caused by sliding, m), then for
    each body
    J from 0 (the bottom block) `theta_J_rad` (its rotation, clockwise),
    `theta_dot_J_rad_s`, `x_J_m` and `y_J_m` (its centre relative to the
    base). `events` has events.csv's, with `body` the block whose lower
    face the event is at. `summary` is summary.json as a dict; `bodies`
    its `physical.bodies` (bottom to top). A stack has no Poincaré section.
    """

    def __init__(self, scene: Any, data: Mapping[str, Any]) -> None:
        self.scene = scene
        #: Number of blocks, bottom to top.
        self.blocks: int = int(data["blocks"])
        #: summary.json as a dict (same keys and numbers as the CLI's file).
        self.summary: dict[str, Any] = data["summary"]
        order = ["tau", "t_s", "mode", "sliding_m"]
        for j in range(self.blocks):
            order += [f"theta_{j}_rad", f"theta_dot_{j}_rad_s", f"x_{j}_m", f"y_{j}_m"]
        #: The regular time history (history.csv's columns).
        self.history: Table = table(data["history"], order)
        #: Every event (events.csv's columns).
        self.events: Table = table(data["events"], STACK_EVENTS)

    @property
    def t(self) -> np.ndarray:
        """Time of each history row, s."""
        return self.history["t_s"]

    def theta_rad(self, body: int) -> np.ndarray:
        """Rotation of block `body` (0 = bottom), rad, clockwise."""
        return self.history[f"theta_{self._body(body)}_rad"]

    def theta_dot_rad_s(self, body: int) -> np.ndarray:
        """Angular velocity of block `body` (0 = bottom), rad/s."""
        return self.history[f"theta_dot_{self._body(body)}_rad_s"]

    @property
    def bodies(self) -> list[dict[str, Any]]:
        """Each block's answer, bottom to top: name, max_rotation_deg,
        overturned, max_sliding_m, max_uplift_m."""
        return list(self.summary["physical"]["bodies"])

    @property
    def outcome(self) -> str:
        """How the run ended: running, rest, tumbled or flight."""
        return str(self.summary["outcome"])

    def _body(self, body: int) -> int:
        if not (isinstance(body, (int, np.integer)) and 0 <= body < self.blocks):
            raise IndexError(f"body {body!r}: a block of this stack, 0 (bottom) to {self.blocks - 1} (top)")
        return int(body)

    def __repr__(self) -> str:
        return (
            f"rocking.StackRun(blocks={self.blocks}, outcome={self.outcome!r}, tau_end={self.summary['tau_end']!r}, "
            f"{len(self.history)} history rows, {len(self.events)} events)"
        )


def _masked(values: np.ndarray, present: np.ndarray) -> np.ma.MaskedArray:
    """`values` masked where not `present`."""
    return np.ma.MaskedArray(values, mask=~np.asarray(present, dtype=bool))


def _pandas() -> Any:
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pd


def _xarray() -> Any:
    try:
        import xarray as xr
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_xarray() needs xarray: pip install xarray") from e
    return xr


def _period_float(period: np.ndarray, outcome: np.ndarray) -> np.ndarray:
    """Periods as floats, NaN where the response is not periodic (for xarray)."""
    return np.where(np.asarray(outcome) == "periodic", np.asarray(period, dtype=float), np.nan)


class _Inputs:
    """What a result was computed from, kept on it."""

    #: The inputs by name (scene, grid, transient, tau_end, records, …).
    inputs: dict[str, Any]

    def _keep(self, **inputs: Any) -> Any:
        self.inputs = dict(inputs)
        for k, v in inputs.items():
            setattr(self, k, v)
        return self


def _responses(d: Mapping[str, Any]) -> dict[str, Any]:
    """The response columns of one chunk as arrays."""
    return {
        "outcome": names(d["outcome"]),
        "period": np.asarray(d["period"]),
        "max_abs_theta": np.asarray(d["max_abs_theta"]),
        "lyapunov": np.asarray(d["lyapunov"]),
        "has_lyapunov": np.asarray(d["has_lyapunov"]),
    }


class Sweep(_Inputs):
    """A bifurcation diagram, as `rocking sweep` computes it.

    `values` are the grid's values (increasing); `outcome`, `period`,
    `max_abs_theta` and `lyapunov` are classes.csv's columns per value
    (`period` masked where the response is not periodic, `lyapunov` where
    none was computed); `points` are points.csv's rows (with `index`, the
    value's index, and the section state `x`, `x_dot`, `mode` besides).
    Its inputs: `scene`, `param`, `start`, `stop`, `step`, `transient`,
    `tau_end` (resolved), `continuation`, `lyapunov_asked`.
    """

    def __init__(self, param: str, classes: Table, points: Table) -> None:
        #: The config key swept.
        self.param = param
        #: One row per value: index, value, outcome, period (0 where not
        #: periodic), max_abs_theta, lyapunov (NaN where none), has_lyapunov.
        self.classes = classes
        #: Every Poincaré point at τ_k ≥ transient, value by value.
        self.points = points

    @classmethod
    def _assemble(cls, param: str, parts: Sequence[Mapping[str, Any]]) -> "Sweep":
        """One sweep from chunks (shards) computed apart, in index order."""
        classes = concat(
            [
                table({"index": np.asarray(p["index"]), "value": np.asarray(p["value"]), **_responses(p)}, CLASSES)
                for p in parts
            ]
        )
        points = concat([table({k: p["points"][k] for k in POINTS}, POINTS) for p in parts])
        # Stable: the points of one value keep their k order.
        classes = classes[np.argsort(classes["index"], kind="stable")]
        points = points[np.argsort(points["index"], kind="stable")]
        return cls(param, classes.view(Table), points.view(Table))

    @property
    def values(self) -> np.ndarray:
        """The parameter values, increasing."""
        return self.classes["value"]

    @property
    def outcome(self) -> np.ndarray:
        """Response class per value: periodic, quasiperiodic, chaotic, tumbled, rest or flight."""
        return self.classes["outcome"]

    @property
    def period(self) -> np.ma.MaskedArray:
        """k of a period-k response (the paper's (1,k) mode); masked otherwise."""
        return _masked(self.classes["period"], self.classes["outcome"] == "periodic")

    @property
    def max_abs_theta(self) -> np.ndarray:
        """Largest |Θ| over each run, transient included."""
        return self.classes["max_abs_theta"]

    @property
    def lyapunov(self) -> np.ma.MaskedArray:
        """Largest Lyapunov exponent per unit τ; masked where none was computed."""
        return _masked(self.classes["lyapunov"], self.classes["has_lyapunov"])

    def to_pandas(self) -> Any:
        """classes.csv as a `pandas.DataFrame` (value, outcome, period,
        max_abs_theta, lyapunov; missing entries are `pd.NA`). Needs pandas."""
        import pandas as pd

        c = self.classes
        return pd.DataFrame(
            {
                "value": np.asarray(c["value"]),
                "outcome": np.asarray(c["outcome"]),
                "period": pd.Series(c["period"], dtype="Int64").where(np.asarray(c["outcome"] == "periodic")),
                "max_abs_theta": np.asarray(c["max_abs_theta"]),
                "lyapunov": pd.Series(c["lyapunov"], dtype="Float64").where(np.asarray(c["has_lyapunov"])),
            }
        )

    def to_xarray(self) -> Any:
        """The classes as an `xarray.Dataset` over the dimension `value`
        (period and lyapunov NaN where missing), with the inputs as
        attributes. Needs xarray."""
        xr = _xarray()
        c = self.classes
        dims = ("value",)
        return xr.Dataset(
            {
                "outcome": (dims, np.asarray(c["outcome"])),
                "period": (dims, _period_float(c["period"], c["outcome"])),
                "max_abs_theta": (dims, np.asarray(c["max_abs_theta"])),
                "lyapunov": (dims, np.asarray(c["lyapunov"])),
            },
            coords={"value": np.asarray(c["value"])},
            attrs=_attrs(getattr(self, "inputs", {})),
        )

    def __repr__(self) -> str:
        return f"rocking.Sweep({self.param!r}, {len(self.classes)} values, {len(self.points)} points)"


def _attrs(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """Inputs as netCDF-safe attributes (numbers and strings; a scene by its repr)."""
    out: dict[str, Any] = {}
    for k, v in inputs.items():
        if v is None:
            continue
        if isinstance(v, bool):  # netCDF has no boolean attribute
            v = int(v)
        out[k] = v if isinstance(v, (int, float, str)) else repr(v)
    return out


class OutcomeMap(_Inputs):
    """An outcome map, as `rocking map` computes it.

    `x` and `y` are the axes' values; `outcome`, `period`, `max_abs_theta`,
    `lyapunov`, `attractor` and `computed` are 2-D arrays indexed `[j, i]`
    (row j = y value, column i = x value); `cells` are map.csv's rows (y
    outer, x inner). A cell that inherited its class while the map was
    refined (`computed` false) was not run: its `max_abs_theta` is NaN.
    `attractor` is the periodic attractor a cell reaches in a basin map
    (both axes initial-state keys), masked elsewhere; `attractors` lists
    them (map.json's entries: `id`, `period`, `point` = (theta, theta_dot,
    x_dot), the representative section point, `cycle`, every point of the
    cycle, and `cells`, how many cells reach it). `cells_run` and
    `cells_stopped_early` count the cells run and those of them whose run
    stopped once its class was certain, `cells_on_known_attractor` those
    that stopped on reaching an attractor found in another cell (basin
    maps). Its inputs: `scene`, `x_axis`,
    `y_axis` (key, first, last, count), `transient`, `tau_end` (resolved),
    `lyapunov_asked`, `full`, `coarse`.
    """

    def __init__(
        self,
        x_key: str,
        y_key: str,
        x: np.ndarray,
        y: np.ndarray,
        cells: Table,
        attractors: list[dict[str, Any]],
        cells_run: int,
        cells_stopped_early: int,
        cells_on_known_attractor: int = 0,
    ) -> None:
        #: The config key along the horizontal axis.
        self.x_key = x_key
        #: The config key along the vertical axis.
        self.y_key = y_key
        #: Horizontal axis values.
        self.x = x
        #: Vertical axis values.
        self.y = y
        #: One row per cell in map.csv's order: x, y, outcome, period (0
        #: where not periodic), max_abs_theta (NaN where not run), lyapunov
        #: (NaN where none), has_lyapunov, attractor (-1 where none),
        #: computed.
        self.cells = cells
        #: A basin map's periodic attractors, numbered as `attractor`.
        self.attractors = attractors
        #: Cells that were run (the others inherited their class).
        self.cells_run = cells_run
        #: Cells run that stopped as soon as their class was certain.
        self.cells_stopped_early = cells_stopped_early
        #: Of those, cells that stopped on reaching a known attractor.
        self.cells_on_known_attractor = cells_on_known_attractor

    @classmethod
    def _of(cls, d: Mapping[str, Any]) -> "OutcomeMap":
        """The map from the extension's columns."""
        cells = table(
            {
                "x": np.asarray(d["x"]),
                "y": np.asarray(d["y"]),
                **_responses(d),
                "attractor": np.asarray(d["attractor"]),
                "computed": np.asarray(d["computed"]),
            },
            CELLS,
        )
        attractors = [
            {**a, "point": tuple(a["point"]), "cycle": np.asarray(a["cycle"], dtype=float).reshape(-1, 3)}
            for a in d["attractors"]
        ]
        return cls(
            d["x_key"],
            d["y_key"],
            np.asarray(d["x_values"]),
            np.asarray(d["y_values"]),
            cells,
            attractors,
            int(d["cells_run"]),
            int(d["cells_stopped_early"]),
            int(d["cells_on_known_attractor"]),
        )

    def _grid(self, name: str) -> np.ndarray:
        return np.asarray(self.cells[name]).reshape(len(self.y), len(self.x))

    @property
    def outcome(self) -> np.ndarray:
        """Response class per cell, `[j, i]`."""
        return self._grid("outcome")

    @property
    def period(self) -> np.ma.MaskedArray:
        """Period per cell, masked where not periodic."""
        return _masked(self._grid("period"), self._grid("outcome") == "periodic")

    @property
    def max_abs_theta(self) -> np.ndarray:
        """Largest |Θ| per cell over the part of its run computed; NaN
        where the cell was not run (it inherited its class)."""
        return self._grid("max_abs_theta")

    @property
    def lyapunov(self) -> np.ma.MaskedArray:
        """Largest Lyapunov exponent per unit τ per cell; masked where none."""
        return _masked(self._grid("lyapunov"), self._grid("has_lyapunov"))

    @property
    def attractor(self) -> np.ma.MaskedArray:
        """The periodic attractor each cell reaches (its `id` in
        `attractors`), in a basin map; masked elsewhere."""
        grid = self._grid("attractor")
        return _masked(grid, grid >= 0)

    @property
    def computed(self) -> np.ndarray:
        """Whether each cell was run (false: it inherited its class)."""
        return self._grid("computed")

    def to_pandas(self) -> Any:
        """map.csv as a `pandas.DataFrame` (missing entries `pd.NA` or NaN). Needs pandas."""
        import pandas as pd

        c = self.cells
        periodic = np.asarray(c["outcome"] == "periodic")
        return pd.DataFrame(
            {
                "x": np.asarray(c["x"]),
                "y": np.asarray(c["y"]),
                "outcome": np.asarray(c["outcome"]),
                "period": pd.Series(c["period"], dtype="Int64").where(periodic),
                "max_abs_theta": np.asarray(c["max_abs_theta"]),
                "lyapunov": pd.Series(c["lyapunov"], dtype="Float64").where(np.asarray(c["has_lyapunov"])),
                "attractor": pd.Series(c["attractor"], dtype="Int64").where(np.asarray(c["attractor"]) >= 0),
                "computed": np.asarray(c["computed"]),
            }
        )

    def to_xarray(self) -> Any:
        """The map as an `xarray.Dataset` over the dimensions (y key, x
        key), e.g. ("excitation.omega_h", "excitation.a_h"), with outcome,
        period, lyapunov and attractor (NaN where missing), max_abs_theta,
        computed, and the inputs and counts as attributes. Needs xarray."""
        xr = _xarray()
        dims = (self.y_key, self.x_key)
        attractor = self._grid("attractor")
        return xr.Dataset(
            {
                "outcome": (dims, self.outcome),
                "period": (dims, _period_float(self._grid("period"), self._grid("outcome"))),
                "max_abs_theta": (dims, self.max_abs_theta),
                "lyapunov": (dims, self._grid("lyapunov")),
                "attractor": (dims, np.where(attractor >= 0, attractor.astype(float), np.nan)),
                "computed": (dims, self.computed),
            },
            coords={self.y_key: self.y, self.x_key: self.x},
            attrs=_attrs(
                {
                    **getattr(self, "inputs", {}),
                    "cells_run": self.cells_run,
                    "cells_stopped_early": self.cells_stopped_early,
                    "cells_on_known_attractor": self.cells_on_known_attractor,
                }
            ),
        )

    def __repr__(self) -> str:
        return (
            f"rocking.OutcomeMap({self.x_key!r} × {self.y_key!r}, {len(self.x)} × {len(self.y)} cells, "
            f"{self.cells_run} run, {len(self.attractors)} attractors)"
        )


@dataclass(frozen=True)
class Lyapunov:
    """Lyapunov exponents of a scene, as `analysis.lyapunov` computes them.

    Exponents are per unit τ (natural log); `per_cycle` per forcing
    period. A response without a finite exponent (tumbled, flight, rest,
    flat phases) has `largest_per_tau = None` and says why in
    `no_exponent`.
    """

    #: tangent, benettin or both.
    method: str
    #: Largest exponent per τ, or None.
    largest_per_tau: float | None
    #: Largest exponent per forcing cycle, or None.
    per_cycle: float | None
    #: Standard error of `largest_per_tau` (batch means), or None.
    stderr: float | None
    #: The finite exponents of (Θ, Θ', X') per τ, largest first (tangent only).
    spectrum: np.ndarray
    #: Why there is no exponent (tumbled, flight, rest, flat-phases), or None.
    no_exponent: str | None
    #: (τ, running estimate per τ) rows.
    convergence: np.ndarray
    #: summary.json's `lyapunov` entry.
    summary: dict[str, Any]
    #: Every field the library returns.
    result: dict[str, Any]
    #: The scene whose exponents these are.
    scene: Any = None

    @classmethod
    def _of(cls, d: Mapping[str, Any], scene: Any = None) -> "Lyapunov":
        r = d["result"]
        conv = np.asarray(r.get("convergence", []), dtype=float).reshape(-1, 2)
        return cls(
            method=str(r["method"]),
            largest_per_tau=r.get("largest_per_tau"),
            per_cycle=r.get("per_cycle"),
            stderr=r.get("stderr"),
            spectrum=np.asarray(r.get("spectrum", []), dtype=float),
            no_exponent=r.get("no_exponent"),
            convergence=conv,
            summary=d["summary"],
            result=r,
            scene=scene,
        )


RUNS = ("run", "block", "width_m", "height_m", "record", "level", "scale", "end", "peak_theta_over_alpha", "t_end_s", "has_t_end")


class Fragility(_Inputs):
    """A fragility study, as `rocking fragility` computes it.

    `runs` has one row per run (block outer, level, record inner) with
    runs.csv's columns (`t_end_s` is the time of overturning or flight,
    NaN where `has_t_end` is false: the block did not overturn); `fits[b]`
    holds block b's counts per level and both lognormal fits
    (P(overturning) and P(θ/α ≥ threshold or overturning)): `median` in
    the unit of the intensity measure, `beta`, their 95 % intervals, or
    `{"error": …}` when the data admit no fit. Its inputs: `base` (the
    scene), `records` (as given), `record_names`, `blocks`, `levels`,
    `im`, `threshold`.
    """

    def __init__(self, im: str, threshold: float, levels: Sequence[float], runs: Table, fits: list[dict[str, Any]]) -> None:
        #: pga_g or pgv_m_s.
        self.im = im
        #: θ/α whose exceedance is counted.
        self.threshold = threshold
        #: Intensity levels.
        self.levels = np.asarray(levels, dtype=float)
        #: One row per run.
        self.runs = runs
        #: Per block: counts per level and both fits.
        self.fits = fits

    @classmethod
    def _assemble(
        cls, parts: Sequence[Mapping[str, Any]], blocks: int, levels: Sequence[float], threshold: float
    ) -> "Fragility":
        from . import _rocking

        runs = concat([table({**p, "record": p["record"], "end": p["end"]}, RUNS) for p in parts])
        runs = runs[np.argsort(runs["run"], kind="stable")].view(Table)
        records = len(parts[0]["records"])
        fits = _rocking._fragility_fits(
            blocks,
            list(levels),
            records,
            threshold,
            [int(i) for i in runs["run"]],
            [str(e) for e in runs["end"]],
            [float(x) for x in runs["peak_theta_over_alpha"]],
        )
        return cls(str(parts[0]["im"]), threshold, levels, runs, fits)

    def to_pandas(self) -> Any:
        """runs.csv as a `pandas.DataFrame` (`t_end_s` NaN where the block
        did not overturn or fly). Needs pandas."""
        return self.runs.to_pandas()

    def fits_to_pandas(self) -> Any:
        """The fits as a `pandas.DataFrame`: one row per block and curve
        ("overturning", "exceedance") with the block's size, the fit's
        fields (median, beta, intervals, …) and `error` where the data
        admit no fit (its fields then missing). Needs pandas."""
        pd = _pandas()
        blocks = getattr(self, "blocks", None)
        rows = []
        for b, fit in enumerate(self.fits):
            for curve in ("overturning", "exceedance"):
                row: dict[str, Any] = {"block": b, "curve": curve}
                if blocks is not None:
                    row["width_m"], row["height_m"] = blocks[b]
                f = fit[curve]
                row.update({k: v for k, v in f.items() if not isinstance(v, (list, dict))})
                rows.append(row)
        return pd.DataFrame(rows)

    def fractions_to_pandas(self) -> Any:
        """Counts and fractions per block and level (fractions.csv) as a
        `pandas.DataFrame`. Needs pandas."""
        pd = _pandas()
        return pd.DataFrame([{"block": fit["block"], **lv} for fit in self.fits for lv in fit["levels"]])

    def to_xarray(self) -> Any:
        """The runs as an `xarray.Dataset` over (block, level, record):
        end, peak_theta_over_alpha, scale and t_end_s (NaN where the block
        did not overturn or fly). Needs xarray."""
        xr = _xarray()
        r = self.runs
        nb, nl = int(r["block"].max()) + 1 if len(r) else 0, len(self.levels)
        nr = len(getattr(self, "record_names", [])) or (len(r) // max(nb * nl, 1))
        if len(r) != nb * nl * nr:
            raise ValueError("to_xarray() needs every run of the study")
        shape = (nb, nl, nr)
        dims = ("block", "level", "record")
        return xr.Dataset(
            {name: (dims, np.asarray(r[name]).reshape(shape)) for name in ("end", "peak_theta_over_alpha", "scale", "t_end_s")},
            coords={
                "block": np.arange(nb),
                "level": self.levels,
                "record": list(getattr(self, "record_names", range(nr))),
                "width_m": ("block", np.asarray(r["width_m"]).reshape(shape)[:, 0, 0]),
                "height_m": ("block", np.asarray(r["height_m"]).reshape(shape)[:, 0, 0]),
            },
            attrs={"im": self.im, "threshold": self.threshold},
        )

    def __repr__(self) -> str:
        return f"rocking.Fragility({len(self.runs)} runs, {len(self.fits)} blocks, im={self.im})"


SPECTRUM = (
    "b_over_h", "alpha_rad", "width_m", "height_m", "r_m", "p_per_s", "scale", "pga_g", "end",
    "peak_theta_over_alpha", "t_end_s", "has_t_end", "overturn_scale", "overturn_pga_g", "overturn_end",
    "has_overturn_scale", "safe_windows",
)


class RockingSpectrum(_Inputs):
    """A rocking spectrum, as `rocking spectrum --record` computes it.

    `blocks` has one row per block (B/H outer, size increasing) with
    spectrum.csv's columns: `t_end_s` is the time of overturning or flight
    (NaN where `has_t_end` is false), `overturn_scale` the smallest scale
    factor found to overturn the block (NaN where `has_overturn_scale` is
    false), `overturn_pga_g` the PGA at that scale. Its inputs: `base`
    (the scene), `record`, `sizes`, `size`, `b_over_h`, `scale`, `pga`.
    """

    def __init__(self, blocks: Table, pga_g_record: float) -> None:
        #: One row per block.
        self.blocks = blocks
        #: The record's PGA as read (scale 1), g.
        self.pga_g_record = pga_g_record

    def to_pandas(self) -> Any:
        """spectrum.csv as a `pandas.DataFrame`. Needs pandas."""
        return self.blocks.to_pandas()

    def to_xarray(self) -> Any:
        """The spectrum as an `xarray.Dataset` over (b_over_h, size), the
        size being the half-diagonal `r_m` or the height `height_m` as
        asked (`size`), with every float column of spectrum.csv and `end`.
        Needs xarray."""
        xr = _xarray()
        b = self.blocks
        ratios = np.unique(np.asarray(b["b_over_h"]))
        n = len(b) // max(len(ratios), 1)
        size = "height_m" if getattr(self, "size", "r") == "h" else "r_m"
        shape = (len(ratios), n)
        dims = ("b_over_h", size)
        columns = ("width_m", "height_m", "r_m", "alpha_rad", "p_per_s", "peak_theta_over_alpha", "t_end_s", "overturn_scale", "overturn_pga_g", "end")
        data = {c: (dims, np.asarray(b[c]).reshape(shape)) for c in columns if c != size}
        return xr.Dataset(
            data,
            coords={"b_over_h": ratios, size: np.asarray(b[size]).reshape(shape)[0]},
            attrs={"pga_g_record": self.pga_g_record},
        )

    def __repr__(self) -> str:
        return f"rocking.RockingSpectrum({len(self.blocks)} blocks)"


SLIDING = (
    "block", "width_m", "height_m", "mu", "mu_k", "end", "peak_sliding_m", "residual_sliding_m", "has_residual",
    "peak_theta_over_alpha", "t_overturn_s", "t_flight_s",
)


class SlidingSpectrum(_Inputs):
    """A sliding spectrum, as `rocking sliding-spectrum --record` computes it.

    `rows` has sliding_spectrum.csv's columns, one row per block and
    friction coefficient, the block that cannot rock (`block ==
    "slide-only"`, rigid-plastic sliding) first, then the given block
    (`"block"`), μ increasing. Displacements in m; `residual_sliding_m` is
    NaN where `has_residual` is false (the block overturned or flew);
    `width_m`/`height_m` are NaN on the slide-only rows, `t_overturn_s` and
    `t_flight_s` NaN unless the run ended so. Its inputs: `base`, `record`,
    `mu`, `unit`, `block`, `kinetic_ratio`, `scale`, `pga`.
    """

    def __init__(self, rows: Table, pga_g_record: float, scale: float) -> None:
        #: One row per block and μ.
        self.rows = rows
        #: The record's PGA as read (scale 1), g.
        self.pga_g_record = pga_g_record
        #: The scale factor the record was run at.
        self.scale_used = scale

    @property
    def slide_only(self) -> Table:
        """The rows of the block that cannot rock."""
        return self.rows[np.asarray(self.rows["block"]) == "slide-only"]

    @property
    def given(self) -> Table:
        """The rows of the given block."""
        return self.rows[np.asarray(self.rows["block"]) == "block"]

    def to_pandas(self) -> Any:
        """sliding_spectrum.csv as a `pandas.DataFrame`. Needs pandas."""
        return self.rows.to_pandas()

    def __repr__(self) -> str:
        return f"rocking.SlidingSpectrum({len(self.rows) // 2} coefficients)"

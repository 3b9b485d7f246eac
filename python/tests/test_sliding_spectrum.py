"""rocking.sliding_spectrum: sliding_spectrum.csv of `rocking sliding-spectrum --record`."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import rocking
from conftest import REPO, as_python, read_csv

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"
SLIDING_ARGS = {"--record": "record", "--unit": "unit", "--mu": "mu", "--kinetic-ratio": "kinetic_ratio", "--block": "block"}


def cell(text: str) -> float:
    """A CSV number, NaN for an empty cell (Python's missing value)."""
    return float(text) if text else math.nan


def test_the_sliding_spectrum_is_the_clis(cli, tmp_path: Path) -> None:
    # Kobe on the statue: it slides at low μ, overturns at μ = 0.3 (no
    # residual there), and μ_k = 0.9 μ_s exercises the kinetic ratio.
    out = tmp_path / "out"
    cli.ok(
        "sliding-spectrum", "--record", str(KOBE), "--unit", "m/s2", "--preset", "elcentro-statue",
        "--mu", "0.1,0.2,0.3", "--kinetic-ratio", "0.9", "--out", str(out), "-q",
    )
    s = rocking.sliding_spectrum(
        KOBE, [0.1, 0.2, 0.3], unit="m/s2", kinetic_ratio=0.9, base=rocking.Scene("elcentro-statue"), progress=False
    )
    rows = read_csv(out / "sliding_spectrum.csv")
    r = s.rows
    assert len(r) == len(rows) == 6
    assert list(r["block"]) == [row["block"] for row in rows]
    assert list(r["end"]) == [row["end"] for row in rows]
    for name in ("width_m", "height_m", "mu", "mu_k", "peak_sliding_m", "residual_sliding_m", "peak_theta_over_alpha", "t_overturn_s", "t_flight_s"):
        got, want = [float(v) for v in r[name]], [cell(row[name]) for row in rows]
        assert all((g == w) or (math.isnan(g) and math.isnan(w)) for g, w in zip(got, want)), (name, got, want)
    assert list(r["has_residual"]) == [bool(row["residual_sliding_m"]) for row in rows]
    assert "overturned" in list(s.given["end"]) and len(s.slide_only) == 3
    assert all(s.slide_only["peak_theta_over_alpha"] == 0.0)


def test_bad_coefficients_are_refused_with_the_clis_message_naming_python_arguments(cli, tmp_path: Path) -> None:
    expected = as_python(
        cli.error("sliding-spectrum", "--record", str(KOBE), "--unit", "m/s2", "--mu", "0.3,0.1", "--out", str(tmp_path / "o")),
        SLIDING_ARGS,
    )
    with pytest.raises(rocking.ConfigError) as e:
        rocking.sliding_spectrum(KOBE, [0.3, 0.1], unit="m/s2", progress=False)
    assert str(e.value) == expected
    assert str(e.value).startswith("mu: ")

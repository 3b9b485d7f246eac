"""rocking.spectrum: spectrum.csv of `rocking spectrum --record`."""

from __future__ import annotations

from pathlib import Path

import pytest

import rocking
from conftest import REPO, SPECTRUM_ARGS, as_python, floats, read_csv

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"


def test_the_spectrum_is_the_clis(cli, tmp_path: Path) -> None:
    out = tmp_path / "out"
    cli.ok(
        "spectrum", "--record", str(KOBE), "--unit", "m/s2", "--from", "0.2", "--to", "3", "--count", "5",
        "--b-over-h", "0.2,0.3", "--pga", "0.5", "--overturn-scale", "--search-max", "2", "--out", str(out), "-q",
    )
    s = rocking.spectrum(KOBE, (0.2, 3.0, 5), unit="m/s2", b_over_h=[0.2, 0.3], pga=0.5, overturn_scale=True, search_max=2.0)
    rows = read_csv(out / "spectrum.csv")
    b = s.blocks
    assert len(b) == len(rows) == 10
    for name in ("b_over_h", "alpha_rad", "width_m", "height_m", "r_m", "p_per_s", "scale", "pga_g", "peak_theta_over_alpha"):
        assert list(b[name]) == floats(rows, name), name
    assert list(b["end"]) == [r["end"] for r in rows]
    assert [float(x) if h else None for x, h in zip(b["overturn_scale"], b["has_overturn_scale"])] == [
        float(r["overturn_scale"]) if r["overturn_scale"] else None for r in rows
    ]
    assert [e or None for e in b["overturn_end"]] == [r["overturn_end"] or None for r in rows]
    assert [int(w) for w in b["safe_windows"]] == [int(r["safe_windows"]) for r in rows]
    assert any(b["has_overturn_scale"]) and not all(b["end"] == "overturned")


def test_bad_sizes_are_refused_with_the_clis_message_naming_python_arguments(cli, tmp_path: Path) -> None:
    expected = as_python(cli.error("spectrum", "--record", str(KOBE), "--unit", "m/s2", "--from", "3", "--to", "0.2", "--out", str(tmp_path)), SPECTRUM_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.spectrum(KOBE, (3.0, 0.2, 50), unit="m/s2")
    assert str(e.value) == expected


def test_a_vertical_record_runs_with_the_horizontal_scaled_by_the_same_factor(tmp_path) -> None:
    # a_h = 0.24 g, a_v = -0.096 g (the vertical step at -0.4 times the
    # horizontal): the 0.5 x 2 m block (tan α = 0.25) lifts off only with
    # the vertical, since 0.24 > 0.25 (1 - 0.096) but 0.24 < 0.25.
    h = tmp_path / "h.dat"
    v = tmp_path / "v.dat"
    h.write_text("0 0\n0.001 1.0\n2.0 1.0\n")
    v.write_text("0 0\n0.001 -0.4\n2.0 -0.4\n")
    common = dict(unit="g", size="h", b_over_h=[0.25], pga=0.24)
    with_v = rocking.spectrum(h, (2.0, 2.0, 1), record_v=v, **common)
    without = rocking.spectrum(h, (2.0, 2.0, 1), **common)
    assert float(with_v.blocks["peak_theta_over_alpha"][0]) > 0.0
    assert float(without.blocks["peak_theta_over_alpha"][0]) == 0.0


def test_a_record_whose_peak_suggests_a_wrong_unit_warns_as_the_cli_does() -> None:
    kobe = REPO / "assets" / "records" / "kobe-1995.dat"
    # Kobe is in m/s²: read as g its PGA is 6.8 g.
    with pytest.warns(UserWarning, match="record=.*kobe-1995.dat: PGA 6.803 g as read in g is implausible"):
        rocking.spectrum(kobe, (0.5, 1.0, 2), unit="g", progress=False)
    with pytest.warns(UserWarning, match="PGA 6.803 g as read in g"):
        rocking.sliding_spectrum(kobe, [0.2, 0.4], unit="g", progress=False)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rocking.spectrum(kobe, (0.5, 1.0, 2), unit="m/s2", progress=False)

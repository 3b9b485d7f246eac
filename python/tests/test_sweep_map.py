"""rocking.sweep and rocking.outcome_map: the same numbers as `rocking sweep` and `rocking map`."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import rocking
from conftest import floats, read_csv

# A short window keeps the CLI and the binding quick; fig3's paper window
# is 600–800.
WINDOW = ["--transient", "100", "--tau-end", "200"]


def cli_sweep(cli, tmp_path: Path, *extra: str) -> Path:
    out = tmp_path / "sweep"
    cli.ok("sweep", "--preset", "fig3", "--param", "excitation.a_v", "--from", "1.5", "--to", "2.5", "--step", "0.1", *WINDOW, *extra, "--out", str(out), "-q")
    return out


def assert_sweep_is(sweep: rocking.Sweep, out: Path) -> None:
    classes = read_csv(out / "classes.csv")
    assert list(sweep.values) == floats(classes, "value")
    assert list(sweep.outcome) == [r["outcome"] for r in classes]
    assert [None if m else int(p) for p, m in zip(sweep.period.data, np.ma.getmaskarray(sweep.period))] == [
        int(r["period"]) if r["period"] else None for r in classes
    ]
    assert list(sweep.max_abs_theta) == floats(classes, "max_abs_theta")
    assert [None if m else float(v) for v, m in zip(sweep.lyapunov.data, np.ma.getmaskarray(sweep.lyapunov))] == [
        float(r["lyapunov"]) if r["lyapunov"] else None for r in classes
    ]
    points = read_csv(out / "points.csv")
    assert len(sweep.points) == len(points)
    for name in ("value", "tau", "theta", "theta_dot"):
        assert list(sweep.points[name]) == floats(points, name), name
    assert list(sweep.points["k"].astype(int)) == [int(r["k"]) for r in points]


def test_a_sweep_is_the_clis(cli, tmp_path: Path) -> None:
    out = cli_sweep(cli, tmp_path)
    sweep = rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200)
    assert len(sweep.values) == 11
    assert sweep.values[8] == 2.3  # the typed decimal grid, as the CLI's
    assert_sweep_is(sweep, out)


def test_a_continuation_sweep_is_the_clis(cli, tmp_path: Path) -> None:
    out = cli_sweep(cli, tmp_path, "--continuation", "down")
    sweep = rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, continuation="down")
    assert_sweep_is(sweep, out)


def test_a_sweep_with_lyapunov_exponents_is_the_clis(cli, tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    cli.ok("sweep", "--preset", "fig3", "--param", "excitation.a_v", "--from", "2.0", "--to", "2.1", "--step", "0.1", *WINDOW, "--lyapunov", "--out", str(out), "-q")
    sweep = rocking.sweep("fig3", "excitation.a_v", 2.0, 2.1, 0.1, transient=100, tau_end=200, lyapunov=True)
    assert_sweep_is(sweep, out)
    assert not np.ma.getmaskarray(sweep.lyapunov).all()


def test_results_do_not_depend_on_the_thread_count() -> None:
    one = rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, threads=1)
    many = rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, threads=3)
    assert one.classes.equals(many.classes)
    assert one.points.equals(many.points)


def test_an_outcome_map_is_the_clis(cli, tmp_path: Path) -> None:
    out = tmp_path / "map"
    cli.ok("map", "--preset", "fig3", "--x", "excitation.a_h", "0.5", "3.0", "4", "--y", "excitation.omega_h", "6", "10", "3", *WINDOW, "--out", str(out), "-q")
    m = rocking.outcome_map("fig3", ("excitation.a_h", 0.5, 3.0, 4), ("excitation.omega_h", 6, 10, 3), transient=100, tau_end=200)
    rows = read_csv(out / "map.csv")
    assert len(m.cells) == 12 and m.outcome.shape == (3, 4)
    assert list(m.cells["x"]) == floats(rows, "x")
    assert list(m.cells["y"]) == floats(rows, "y")
    assert list(m.cells["outcome"]) == [r["outcome"] for r in rows]
    assert list(m.cells["max_abs_theta"]) == floats(rows, "max_abs_theta")
    assert [int(p) if o == "periodic" else None for p, o in zip(m.cells["period"], m.cells["outcome"])] == [
        int(r["period"]) if r["period"] else None for r in rows
    ]
    assert all(r["lyapunov"] == "" for r in rows) and np.ma.getmaskarray(m.lyapunov).all()
    np.testing.assert_array_equal(m.x, [0.5, 0.5 + 2.5 / 3, 0.5 + 5.0 / 3, 3.0])
    np.testing.assert_array_equal(m.y, [6.0, 8.0, 10.0])
    # [j, i]: row j is y[j], column i is x[i].
    assert m.outcome[2, 1] == rows[2 * 4 + 1]["outcome"]
    assert len(set(m.outcome.ravel())) > 1


def test_sweep_and_map_convert_to_pandas() -> None:
    import pytest

    pd = pytest.importorskip("pandas")
    sweep = rocking.sweep("fig3", "excitation.a_v", 2.0, 2.2, 0.1, transient=100, tau_end=200)
    df = sweep.to_pandas()
    assert list(df.columns) == ["value", "outcome", "period", "max_abs_theta", "lyapunov"]
    assert df["lyapunov"].isna().all() and str(df["period"].dtype) == "Int64"
    m = rocking.outcome_map("fig3", ("excitation.a_h", 0.5, 1.0, 2), ("excitation.a_v", 2.0, 2.2, 2), transient=100, tau_end=200)
    assert isinstance(m.to_pandas(), pd.DataFrame) and len(m.to_pandas()) == 4

"""rocking.outcome_map on the map engine: early stopping and refinement
(the default) or every cell over its whole window (`full=True`), cell for
cell the maps of `rocking map` and `rocking map --full`, with the
attractors of a basin map told apart."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rocking
from conftest import read_csv, read_json

# A short window keeps the CLI and the binding quick; fig3's paper window
# is 600–800.
WINDOW = {"transient": 100, "tau_end": 200}
CLI_WINDOW = ["--transient", "100", "--tau-end", "200"]
# 12 × 9 cells refined from a 4-cell lattice: some cells are inherited,
# some computed, and several classes meet (rest, periodic, tumbled).
X = ("excitation.a_h", 0.5, 3.0, 12)
Y = ("excitation.omega_h", 4.0, 12.0, 9)
COARSE = 4


def cli_map(cli, out: Path, x: tuple, y: tuple, *extra: str, preset: str = "fig3") -> list[dict[str, str]]:
    cli.ok("map", "--preset", preset, "--x", *map(str, x), "--y", *map(str, y), *CLI_WINDOW, *extra, "--out", str(out), "-q")
    return read_csv(out / "map.csv")


def assert_map_is(m: rocking.OutcomeMap, out: Path) -> None:
    """`m` is map.csv and map.json of `out`, cell for cell and bit for bit."""
    rows = read_csv(out / "map.csv")
    c = m.cells
    assert len(c) == len(rows)
    assert list(c["x"]) == [float(r["x"]) for r in rows]
    assert list(c["y"]) == [float(r["y"]) for r in rows]
    assert list(c["outcome"]) == [r["outcome"] for r in rows]
    assert [int(p) if o == "periodic" else None for p, o in zip(c["period"], c["outcome"])] == [
        int(r["period"]) if r["period"] else None for r in rows
    ]
    # Missing (an inherited cell) is NaN here and empty in the CSV.
    assert [None if np.isnan(v) else float(v) for v in c["max_abs_theta"]] == [
        float(r["max_abs_theta"]) if r["max_abs_theta"] else None for r in rows
    ]
    assert [None if a < 0 else int(a) for a in c["attractor"]] == [int(r["attractor"]) if r["attractor"] else None for r in rows]
    assert [bool(v) for v in c["computed"]] == [r["computed"] == "true" for r in rows]
    meta = read_json(out / "map.json")
    assert (m.cells_run, m.cells_stopped_early) == (meta["cells_run"], meta["cells_stopped_early"])
    assert [(a["id"], a["period"], a["point"], a["cells"]) for a in m.attractors] == [
        (a["id"], a["period"], (a["point"]["theta"], a["point"]["theta_dot"], a["point"]["x_dot"]), a["cells"])
        for a in meta["attractors"]
    ]


def test_the_fast_map_is_the_clis_cell_for_cell(cli, tmp_path: Path) -> None:
    out = tmp_path / "map"
    cli_map(cli, out, X, Y, "--coarse", str(COARSE))
    m = rocking.outcome_map("fig3", X, Y, coarse=COARSE, progress=False, **WINDOW)
    assert_map_is(m, out)
    # Refined: some cells inherited their class (no max |Θ|), the rest ran.
    assert 0 < m.cells_run < len(m.cells) and m.cells_run == int(m.computed.sum())
    assert np.isnan(m.max_abs_theta[~m.computed]).all() and not np.isnan(m.max_abs_theta[m.computed]).any()
    assert len(set(m.outcome.ravel())) > 1
    # Not a basin map: no attractor anywhere.
    assert np.ma.getmaskarray(m.attractor).all() and m.attractors == []


def test_full_is_the_clis_full_map(cli, tmp_path: Path) -> None:
    out = tmp_path / "map"
    cli_map(cli, out, X, Y, "--full")
    m = rocking.outcome_map("fig3", X, Y, full=True, progress=False, **WINDOW)
    assert_map_is(m, out)
    assert m.computed.all() and m.cells_run == len(m.cells) and m.cells_stopped_early == 0
    assert m.full is True


def test_the_map_does_not_depend_on_the_thread_count() -> None:
    one = rocking.outcome_map("fig3", X, Y, coarse=COARSE, threads=1, progress=False, **WINDOW)
    two = rocking.outcome_map("fig3", X, Y, coarse=COARSE, threads=2, progress=False, **WINDOW)
    assert one.cells.equals(two.cells)
    assert (one.cells_run, one.cells_stopped_early) == (two.cells_run, two.cells_stopped_early)


# Fig. 4's scene at A_v = 1: over the initial state (a basin map), its
# period-1 orbit and a period-6 orbit within this short window.
BASIN_SCENE = {"a_v_norm": 1.0}
BASIN_X = ("initial.theta", -0.6, 0.6, 9)
BASIN_Y = ("initial.theta_dot", -0.6, 0.6, 9)


def test_a_basin_map_tells_its_attractors_apart(cli, tmp_path: Path) -> None:
    scene = rocking.Scene("fig4", **BASIN_SCENE)
    m = rocking.outcome_map(scene, BASIN_X, BASIN_Y, progress=False, **WINDOW)
    ids = [a["id"] for a in m.attractors]
    assert len(ids) >= 2 and ids == list(range(1, len(ids) + 1))
    # Each attractor's cells carry its id; every periodic cell has one.
    periodic = m.outcome == "periodic"
    assert (~np.ma.getmaskarray(m.attractor) == periodic).all()
    for a in m.attractors:
        assert int((m.attractor == a["id"]).sum()) == a["cells"]
        assert a["cycle"].shape == (a["period"], 3) and tuple(a["cycle"][0]) == a["point"]
    # Distinct attractors, not one orbit seen twice.
    assert len({a["point"] for a in m.attractors}) == len(ids)
    df = m.to_pandas()
    assert str(df["attractor"].dtype) == "Int64" and df["attractor"].isna().tolist() == (~periodic.ravel()).tolist()
    # The CLI labels the same cells with the same numbers.
    out = tmp_path / "basin"
    cli.ok(
        "map", "--preset", "fig4", "--set", "excitation.a_v=1.0", "--x", *map(str, BASIN_X), "--y", *map(str, BASIN_Y),
        *CLI_WINDOW, "--out", str(out), "-q",
    )
    assert_map_is(m, out)


def test_a_map_converts_with_its_new_columns() -> None:
    m = rocking.outcome_map("fig3", X, Y, coarse=COARSE, progress=False, **WINDOW)
    df = m.to_pandas()
    assert list(df.columns) == ["x", "y", "outcome", "period", "max_abs_theta", "lyapunov", "attractor", "computed"]
    assert df["computed"].tolist() == m.cells["computed"].tolist()
    assert df["attractor"].isna().all()
    xr = pytest.importorskip("xarray")
    ds = m.to_xarray()
    assert isinstance(ds, xr.Dataset)
    np.testing.assert_array_equal(ds["computed"].values, m.computed)
    assert np.isnan(ds["attractor"].values).all()
    assert ds.attrs["cells_run"] == m.cells_run and ds.attrs["coarse"] == COARSE and ds.attrs["full"] == 0


def test_coarse_is_checked_as_the_cli_checks_it(cli, tmp_path: Path) -> None:
    from conftest import MAP_ARGS, as_python

    expected = as_python(
        cli.error("map", "--preset", "fig3", "--x", *map(str, X), "--y", *map(str, Y), "--coarse", "1", "--out", str(tmp_path / "o")),
        MAP_ARGS,
    )
    with pytest.raises(rocking.ConfigError) as e:
        rocking.outcome_map("fig3", X, Y, coarse=1)
    assert str(e.value) == expected == "coarse=1: must be >= 2"


def test_a_failed_cell_is_the_clis_run_error(cli, tmp_path: Path) -> None:
    x, y = ("excitation.a_h", 0.5, 3.0, 4), ("excitation.omega_h", 6, 10, 3)
    expected = cli.error(
        "map", "--preset", "fig3", "--set", "run.max_steps=50", "--x", *map(str, x), "--y", *map(str, y), *CLI_WINDOW,
        "--out", str(tmp_path / "o"), code=1,
    )
    with pytest.raises(rocking.RunError) as e:
        rocking.outcome_map(rocking.Scene("fig3", max_steps=50), x, y, progress=False, **WINDOW)
    assert str(e.value) == expected

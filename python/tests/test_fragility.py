"""rocking.fragility (and on Dask): the runs and fits of `rocking fragility`."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import rocking
from conftest import REPO, floats, read_csv

ELCENTRO = REPO / "assets" / "records" / "elcentro-1940-ns.dat"
KOBE = REPO / "assets" / "records" / "kobe-1995.dat"
LEVELS = [0.1, 0.4, 0.7, 1.0]
BLOCKS = [(0.6, 2.0), (0.3, 1.2)]


def cli_fragility(cli, tmp_path: Path) -> Path:
    suite = tmp_path / "suite.txt"
    suite.write_text(f"{ELCENTRO} g\n{KOBE} m/s2\n")
    out = tmp_path / "out"
    cli.ok(
        "fragility", "--suite", str(suite), "--levels", ",".join(map(str, LEVELS)),
        "--block", "0.6x2.0", "--block", "0.3x1.2", "--out", str(out), "-q",
    )
    return out


def local() -> rocking.Fragility:
    return rocking.fragility([(ELCENTRO, "g"), (KOBE, "m/s2")], LEVELS, BLOCKS)


def test_the_runs_and_fits_are_the_clis(cli, tmp_path: Path) -> None:
    out = cli_fragility(cli, tmp_path)
    f = local()
    rows = read_csv(out / "runs.csv")
    assert len(f.runs) == len(rows) == 2 * 4 * 2
    assert list(f.runs["record"]) == [r["record"] for r in rows]
    assert list(f.runs["end"]) == [r["end"] for r in rows]
    for name in ("run", "width_m", "height_m", "level", "scale", "peak_theta_over_alpha"):
        assert list(f.runs[name].astype(float)) == floats(rows, name), name
    t_cli = [r["t_overturn_s"] or r["t_flight_s"] or None for r in rows]
    assert [float(t) if h else None for t, h in zip(f.runs["t_end_s"], f.runs["has_t_end"])] == [
        float(t) if t else None for t in t_cli
    ]
    meta = json.loads((out / "fragility.json").read_text())
    for mine, theirs in zip(f.fits, meta["fits"]):
        for curve in ("overturning", "exceedance"):
            expected = {k: v for k, v in theirs[curve].items() if k != "band"}
            assert mine[curve] == expected, curve
    fractions = read_csv(out / "fractions.csv")
    mine = [lv for b in f.fits for lv in b["levels"]]
    assert [lv["overturned"] for lv in mine] == [int(r["overturned"]) for r in fractions]
    assert [lv["fraction_exceeded"] for lv in mine] == [float(r["fraction_exceeded"]) for r in fractions]


def test_a_fragility_on_the_cluster_is_the_local_one() -> None:
    distributed = pytest.importorskip("distributed")
    import rocking.dask

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = rocking.dask.fragility(client, [(ELCENTRO, "g"), (KOBE, "m/s2")], LEVELS, BLOCKS, chunks=5)
    f = local()
    assert remote.runs.equals(f.runs)
    assert remote.fits == f.fits


def test_a_bad_record_in_a_suite_is_a_record_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.dat"
    bad.write_text("0.0 0.1\n0.01 zz\n")
    with pytest.raises(rocking.RecordError) as e:
        rocking.fragility([(bad, "g")], LEVELS, BLOCKS)
    assert (e.value.file, e.value.line) == (str(bad), 2)


def test_a_base_scene_sets_friction_as_the_clis_base_does(cli, tmp_path: Path) -> None:
    suite = tmp_path / "suite.txt"
    suite.write_text(f"{KOBE} m/s2\n")
    out = tmp_path / "out"
    cli.ok("fragility", "--suite", str(suite), "--levels", "0.5,1.0", "--block", "0.3x1.2", "--set", "friction.static=0.3", "--out", str(out), "-q")
    f = rocking.fragility([(KOBE, "m/s2")], [0.5, 1.0], [(0.3, 1.2)], base=rocking.Scene.defaults(friction={"static": 0.3}))
    rows = read_csv(out / "runs.csv")
    assert list(f.runs["end"]) == [r["end"] for r in rows]
    assert list(f.runs["peak_theta_over_alpha"]) == floats(rows, "peak_theta_over_alpha")


def test_record_names_are_never_cut(tmp_path: Path) -> None:
    # Two records whose names share their first 16 characters: a fixed
    # 16-character field once made them one record in a groupby.
    a = tmp_path / "RSN1063_NORTHR_RRS228.dat"
    b = tmp_path / "RSN1063_NORTHR_RRS318.dat"
    a.write_bytes(KOBE.read_bytes())
    b.write_bytes(ELCENTRO.read_bytes())
    f = rocking.fragility([(a, "m/s2"), (b, "g")], [0.2], [(0.3, 1.2)], progress=False)
    assert list(f.runs["record"]) == ["RSN1063_NORTHR_RRS228", "RSN1063_NORTHR_RRS318"]
    assert f.record_names == ["RSN1063_NORTHR_RRS228", "RSN1063_NORTHR_RRS318"]
    pd = pytest.importorskip("pandas")
    assert isinstance(f.to_pandas(), pd.DataFrame)
    assert f.to_pandas().groupby("record").size().to_dict() == {"RSN1063_NORTHR_RRS228": 1, "RSN1063_NORTHR_RRS318": 1}


def test_a_record_level_or_block_given_twice_is_refused_naming_both() -> None:
    with pytest.raises(rocking.ConfigError, match=r"records\[0\] and records\[1\]: the record .*elcentro-1940-ns.dat is listed twice"):
        rocking.fragility([(ELCENTRO, "g"), (ELCENTRO.parent / "." / ELCENTRO.name, "g")], LEVELS, BLOCKS)
    with pytest.raises(rocking.ConfigError, match=r"levels\[0\] and levels\[2\] are both 0.1"):
        rocking.fragility([(ELCENTRO, "g")], [0.1, 0.2, 0.1], BLOCKS)
    with pytest.raises(rocking.ConfigError, match=r"blocks\[0\] and blocks\[1\] are both 0.6 x 2 m"):
        rocking.fragility([(ELCENTRO, "g")], LEVELS, [(0.6, 2.0), (0.6, 2)])


def _step(path: Path, level: float) -> Path:
    """A step record: 0 at t = 0, `level` g from 1 ms on, for 2 s."""
    path.write_text(f"0 0\n0.001 {level}\n2.0 {level}\n")
    return path


def test_paired_vertical_records_run_as_the_clis_and_move_the_uplift_threshold(cli, tmp_path: Path) -> None:
    # a_h = s g, a_v = -0.4 s g: the 0.5 x 2 m block (tan α = 0.25) lifts
    # off where s > 0.25 (1 - 0.4 s), i.e. s > 0.2273, and at s > 0.25
    # without the vertical; 0.24 lies between.
    h = _step(tmp_path / "h.dat", 1.0)
    v = _step(tmp_path / "v.dat", -0.4)
    levels = [0.20, 0.24, 0.26]
    with_v = rocking.fragility([(h, "g", v, "g")], levels, [(0.5, 2.0)])
    assert [p > 0 for p in with_v.runs["peak_theta_over_alpha"]] == [False, True, True]
    without = rocking.fragility([(h, "g", v, "g")], levels, [(0.5, 2.0)], vertical="none")
    assert [p > 0 for p in without.runs["peak_theta_over_alpha"]] == [False, False, True]
    suite = tmp_path / "suite.txt"
    suite.write_text("h.dat g + v.dat g\n")
    out = tmp_path / "out"
    cli.ok("fragility", "--suite", str(suite), "--levels", "0.20,0.24,0.26", "--block", "0.5x2.0", "--out", str(out), "-q")
    rows = read_csv(out / "runs.csv")
    assert list(with_v.runs["peak_theta_over_alpha"].astype(float)) == floats(rows, "peak_theta_over_alpha")
    with pytest.raises(rocking.ConfigError, match=r"records\[0\] names a vertical component but records\[1\] does not"):
        rocking.fragility([(h, "g", v, "g"), (ELCENTRO, "g")], levels, [(0.5, 2.0)])
    with pytest.raises(rocking.ConfigError, match=r'vertical="record": records\[1\] names no vertical'):
        rocking.fragility([(h, "g", v, "g"), (ELCENTRO, "g")], levels, [(0.5, 2.0)], vertical="record")


def test_sa_levels_scale_each_record_by_its_pseudo_spectral_acceleration(cli, tmp_path: Path) -> None:
    # A 0.3 g step from t = 0: Sa(T, 5 %) = 0.3 (1 + exp(-ζπ/√(1-ζ²))) for a
    # period whose first overshoot lies inside the record.
    step = tmp_path / "step.dat"
    step.write_text("0 0.3\n2.0 0.3\n")
    zeta = 0.05
    sa = 0.3 * (1 + np.exp(-zeta * np.pi / np.sqrt(1 - zeta * zeta)))
    f = rocking.fragility([(step, "g")], [0.2, 0.5], [(0.5, 2.0)], im="sa", sa_period=0.5)
    assert abs(float(f.runs["scale"][1]) - 0.5 / sa) < 1e-12
    with pytest.raises(rocking.ConfigError, match="sa_period"):
        rocking.fragility([(step, "g")], [0.2], [(0.5, 2.0)], im="sa")

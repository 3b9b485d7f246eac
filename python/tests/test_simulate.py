"""rocking.simulate: the same numbers as `rocking --batch`."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rocking
from conftest import floats, read_csv, read_json

SETS = ["excitation.a_h=0.35 g", "run.tau_end=300"]


def batch(cli, tmp_path: Path, preset: str, sets: list[str]) -> Path:
    out = tmp_path / "out"
    cli.ok("--batch", "--preset", preset, *[a for s in sets for a in ("--set", s)], "--out", str(out), "-q")
    return out


def assert_columns_equal(table: np.ndarray, rows: list[dict[str, str]]) -> None:
    assert len(table) == len(rows)
    for name in table.dtype.names or ():
        if table.dtype[name].kind == "U":
            assert list(table[name]) == [r[name] for r in rows], name
        else:
            # Exact: the CLI writes shortest round-trip numbers.
            assert list(table[name].astype(float)) == floats(rows, name), name


def without_wall_time(summary: dict) -> dict:
    s = {**summary, "solver": {**summary["solver"]}}
    del s["solver"]["wall_s"]
    return s


def test_history_events_poincare_and_summary_are_the_clis(cli, tmp_path: Path) -> None:
    out = batch(cli, tmp_path, "fig3", SETS)
    run = rocking.simulate(rocking.Scene("fig3", a_h="0.35 g", tau_end=300))
    assert_columns_equal(run.history, read_csv(out / "history.csv"))
    assert_columns_equal(run.events, read_csv(out / "events.csv"))
    assert_columns_equal(run.poincare, read_csv(out / "poincare.csv"))
    assert without_wall_time(run.summary) == without_wall_time(read_json(out / "summary.json"))
    assert run.summary["solver"]["wall_s"] > 0
    assert len(run.events) > 10 and len(run.poincare) > 10


def test_the_summary_has_the_configured_analyses_as_the_cli_writes_them(cli, tmp_path: Path) -> None:
    sets = ["run.tau_end=200", "analysis.lyapunov=true", "analysis.spectrum=true", "analysis.spectrum_window=all"]
    out = batch(cli, tmp_path, "fig3", sets)
    run = rocking.simulate(
        rocking.Scene("fig3", tau_end=200, analysis={"lyapunov": True, "spectrum": True, "spectrum_window": "all"})
    )
    expected = read_json(out / "summary.json")
    assert "lyapunov" in expected and "spectrum" in expected
    assert run.summary["lyapunov"] == expected["lyapunov"]
    assert run.summary["spectrum"] == expected["spectrum"]
    assert without_wall_time(run.summary) == without_wall_time(expected)


def test_columns_are_numpy_arrays_in_both_unit_systems() -> None:
    scene = rocking.Scene("fig3", tau_end=100)
    run = rocking.simulate(scene)
    assert isinstance(run.theta, np.ndarray) and run.theta.dtype == np.float64
    np.testing.assert_array_equal(run.t, run.tau / scene.p_per_s)
    np.testing.assert_array_equal(run.theta_rad, run.theta * scene.psi_rad)
    assert run.tau[0] == 0.0 and run.tau[-1] == pytest.approx(100.0)
    assert set(np.unique(run.mode)) <= {"rest", "slide", "rock", "slide-rock", "tumbled", "flight"}
    assert run.events.dtype.names == (
        "tau", "kind", "mode_before", "mode_after", "theta", "theta_dot_before",
        "theta_dot_after", "x_dot", "t_s", "theta_rad", "sliding_m",
    )
    assert run.poincare["k"].dtype == np.int64
    assert run.outcome == run.summary["outcome"]
    assert not any(np.isnan(run.history[n]).any() for n in run.history.dtype.names if run.history.dtype[n].kind == "f")


def test_tables_convert_to_pandas() -> None:
    pd = pytest.importorskip("pandas")
    run = rocking.simulate(rocking.Scene("fig3", tau_end=50))
    df = run.events.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(run.events.dtype.names)
    assert df["kind"].tolist() == list(run.events["kind"])
    np.testing.assert_array_equal(df["tau"].to_numpy(), run.events["tau"])


def test_lyapunov_is_the_batch_summarys(cli, tmp_path: Path) -> None:
    out = batch(cli, tmp_path, "fig3", ["run.tau_end=200", "analysis.lyapunov=true", "analysis.lyapunov_method=both"])
    lyap = rocking.lyapunov(rocking.Scene("fig3", tau_end=200), method="both")
    expected = read_json(out / "summary.json")["lyapunov"]
    assert lyap.summary == expected
    assert lyap.method == "both"
    assert lyap.largest_per_tau == expected["largest_per_tau"]
    assert lyap.spectrum.shape == (len(expected["spectrum"]),)
    assert lyap.convergence.ndim == 2 and lyap.convergence.shape[1] == 2 and len(lyap.convergence) > 0


def test_a_tumbling_block_has_no_exponent() -> None:
    scene = rocking.Scene("fig3", a_h_norm=3.0, omega_h_norm=4.0, tau_end=200)
    assert rocking.simulate(scene).outcome == "tumbled"
    lyap = rocking.lyapunov(scene)
    assert lyap.largest_per_tau is None and lyap.per_cycle is None
    assert lyap.no_exponent == "tumbled"
    assert lyap.summary["no_exponent"] == "tumbled"


def test_an_unknown_lyapunov_method_is_refused_like_the_cli(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--preset", "fig3", "--set", "analysis.lyapunov=true", "--set", "analysis.lyapunov_method=magic", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.lyapunov("fig3", method="magic")
    assert str(e.value) == expected and e.value.key == "analysis.lyapunov_method"


def test_an_implausible_record_warns_like_the_cli(cli, tmp_path: Path) -> None:
    rec = tmp_path / "loud.dat"
    rec.write_text("0.00 0.0\n0.01 8.0\n0.02 -8.0\n0.03 0.0\n")
    sets = ["excitation.kind=record", f"excitation.file_h={rec}", "excitation.unit_h=g", "run.tail_s=1"]
    p = cli.run("--batch", *[a for s in sets for a in ("--set", s)], "--out", str(tmp_path / "o"), "-q")
    assert p.returncode == 0, p.stderr
    lines = [line.removeprefix("warning: ") for line in p.stderr.splitlines() if line.startswith("warning: ")]
    assert len(lines) == 1 and "implausible" in lines[0]
    scene = rocking.Scene(kind="record", file_h=rec, unit_h="g", tail_s=1)
    assert scene.warnings == lines
    with pytest.warns(UserWarning) as caught:
        run = rocking.simulate(scene)
    assert [str(w.message) for w in caught] == lines
    assert run.summary["config"]["excitation"]["file_h"] == str(rec.resolve())

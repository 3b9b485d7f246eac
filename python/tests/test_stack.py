"""A stack of blocks ([[stack]], docs/model.md §18) from Python: the CLI's
run, columns and answer, and its spectrum scaled as a whole."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rocking
from conftest import REPO, floats, read_csv, read_json

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"


def test_the_tombstone_runs_as_the_cli_runs_it(cli, tmp_path: Path) -> None:
    cli.ok("--batch", "--preset", "tombstone", "--out", str(tmp_path / "o"), "-q")
    summary = read_json(tmp_path / "o" / "summary.json")
    run = rocking.simulate("tombstone")
    assert isinstance(run, rocking.StackRun)
    assert run.blocks == 3
    assert run.summary["physical"] == summary["physical"]
    assert run.outcome == "tumbled"
    assert [b["name"] for b in run.bodies] == ["bottom block", "middle block", "top block"]
    assert [b["overturned"] for b in run.bodies] == [False, False, True]
    # Every column of history.csv and events.csv, the same numbers (the
    # CSV writes each float in full, so they round-trip exactly).
    history = read_csv(tmp_path / "o" / "history.csv")
    assert list(run.history.dtype.names) == list(history[0].keys())
    for name in run.history.dtype.names:
        if name == "mode":
            assert list(run.history["mode"]) == [r["mode"] for r in history]
        else:
            assert np.array_equal(run.history[name], floats(history, name)), name
    events = read_csv(tmp_path / "o" / "events.csv")
    assert list(run.events.dtype.names) == list(events[0].keys())
    assert list(run.events["kind"]) == [r["kind"] for r in events] == ["uplift", "impact", "tumble"]
    assert list(run.events["body"]) == [int(r["body"]) for r in events] == [2, 2, 2]
    assert np.array_equal(run.events["q_dot_after_rad_s"], floats(events, "q_dot_after_rad_s"))
    # The top stone goes over leftward: its rotation passes its own
    # slenderness, atan(0.27/0.80), before the run ends.
    assert -run.theta_rad(2).min() > 0.9 * np.arctan(0.27 / 0.80)
    with pytest.raises(IndexError, match="0 \\(bottom\\) to 2 \\(top\\)"):
        run.theta_rad(3)


def test_a_stack_sliding_on_its_base_runs_as_the_cli_runs_it(cli, tmp_path: Path) -> None:
    keys = {"stack[0].static": 0.3, "stack[0].kinetic": 0.25}
    sets = [a for k, v in keys.items() for a in ("--set", f"{k}={v}")]
    cli.ok("--batch", "--preset", "statue-on-pedestal", *sets, "--out", str(tmp_path / "o"), "-q")
    summary = read_json(tmp_path / "o" / "summary.json")
    run = rocking.simulate(rocking.Scene("statue-on-pedestal", config=keys))
    assert run.summary["physical"] == summary["physical"]
    history = read_csv(tmp_path / "o" / "history.csv")
    assert list(run.history.dtype.names)[:4] == ["tau", "t_s", "mode", "sliding_m"]
    assert np.array_equal(run.history["sliding_m"], floats(history, "sliding_m"))
    kinds = list(run.events["kind"])
    assert "slip" in kinds and "stick" in kinds
    # The pedestal slides under the rocking statue, and both ride on it.
    physical = run.summary["physical"]
    assert physical["max_sliding_m"] >= np.abs(run.history["sliding_m"]).max() > 1e-4
    assert [b["max_sliding_m"] for b in run.bodies] == [physical["max_sliding_m"]] * 2
    assert physical["mode_time_s"]["slide-rock"] + physical["mode_time_s"]["slide"] > 0.0
    assert run.summary["energy"]["loss_friction"] > 0.0


def test_a_slipping_face_is_refused_naming_its_key() -> None:
    scene = rocking.Scene("tombstone", config={"stack[2].static": 0.05})
    with pytest.raises(rocking.ConfigError, match="stack block 3's lower face would slip"):
        rocking.simulate(scene)


def test_a_stack_spectrum_keeps_its_shape_and_agrees_with_the_cli(cli, tmp_path: Path) -> None:
    cli.ok(
        "spectrum", "--preset", "tombstone", "--record", str(KOBE), "--unit", "m/s2",
        "--from", "0.3", "--to", "3", "--count", "12", "--out", str(tmp_path / "s"), "-q",
    )
    rows = read_csv(tmp_path / "s" / "spectrum.csv")
    sp = rocking.spectrum(KOBE, (0.3, 3, 12), unit="m/s2", base=rocking.Scene("tombstone"))
    assert sp.b_over_h == (0.75 / 1.35,)
    for name in ("r_m", "width_m", "height_m", "peak_theta_over_alpha"):
        assert np.array_equal(np.asarray(sp.blocks[name]), floats(rows, name)), name
    assert list(sp.blocks["end"]) == [r["end"] for r in rows]
    with pytest.raises(rocking.ConfigError, match="b_over_h: a \\[\\[stack\\]\\] is scaled as a whole"):
        rocking.spectrum(KOBE, (0.3, 3, 12), unit="m/s2", base=rocking.Scene("tombstone"), b_over_h=[0.2])


def test_a_stack_sweeps_and_maps_as_the_cli_does(cli, tmp_path: Path) -> None:
    # stack-patterns at A_h = 1.0 rocks in a period-4 cycle, at 1.2 in a
    # period-1 one (its section classified over both interfaces).
    window = ["--transient", "400", "--tau-end", "600"]
    cli.ok("sweep", "--preset", "stack-patterns", "--param", "excitation.a_h", "--from", "1.0", "--to", "1.2",
           "--step", "0.2", *window, "--out", str(tmp_path / "s"), "-q")
    sweep = rocking.sweep("stack-patterns", "excitation.a_h", 1.0, 1.2, 0.2, transient=400, tau_end=600)
    classes = read_csv(tmp_path / "s" / "classes.csv")
    assert list(sweep.outcome) == [r["outcome"] for r in classes] == ["periodic", "periodic"]
    assert [int(r["period"]) for r in classes] == [4, 1]
    assert list(sweep.max_abs_theta) == floats(classes, "max_abs_theta")
    points = read_csv(tmp_path / "s" / "points.csv")
    for name in ("tau", "theta", "theta_dot"):
        assert list(sweep.points[name]) == floats(points, name), name
    cli.ok("map", "--preset", "stack-patterns", "--x", "excitation.a_h", "1.0", "1.2", "2", "--y",
           "excitation.phase_h", "0", "1", "2", *window, "--out", str(tmp_path / "m"), "-q")
    m = rocking.outcome_map("stack-patterns", ("excitation.a_h", 1.0, 1.2, 2), ("excitation.phase_h", 0, 1, 2),
                            transient=400, tau_end=600)
    cells = read_csv(tmp_path / "m" / "map.csv")
    assert list(m.cells["outcome"]) == [r["outcome"] for r in cells]
    assert list(m.cells["max_abs_theta"]) == floats(cells, "max_abs_theta")
    # What a stack cannot vary or compute is refused with the CLI's words.
    with pytest.raises(rocking.ConfigError, match="block.width: is not read by a \\[\\[stack\\]\\]"):
        rocking.sweep("stack-patterns", "block.width", 0.1, 0.3, 0.1, tau_end=700)
    with pytest.raises(rocking.ConfigError, match="tau_end: not given, and the scene's run.tau_end = 55.70 ends before transient=600"):
        rocking.sweep("stack-patterns", "excitation.a_h", 1.0, 1.2, 0.2)
    with pytest.raises(rocking.ConfigError, match="sweep without continuation"):
        rocking.sweep("stack-patterns", "excitation.a_h", 1.0, 1.2, 0.2, tau_end=700, continuation="up")


def test_a_stack_fragility_runs_the_stack_as_given_without_blocks(cli, tmp_path: Path) -> None:
    cli.ok(
        "fragility", "--preset", "tombstone", "--records", str(KOBE), "--unit", "m/s2",
        "--levels", "0.3,0.6,0.9", "--out", str(tmp_path / "f"), "-q",
    )
    rows = read_csv(tmp_path / "f" / "runs.csv")
    f = rocking.fragility([(KOBE, "m/s2")], [0.3, 0.6, 0.9], base=rocking.Scene("tombstone"), progress=False)
    assert f.blocks == [(0.75, 1.35)]
    assert list(f.runs["end"]) == [r["end"] for r in rows] == ["rest", "overturned", "overturned"]
    assert np.array_equal(f.runs["peak_theta_over_alpha"], floats(rows, "peak_theta_over_alpha"))
    with pytest.raises(rocking.ConfigError, match="im: a \\[\\[stack\\]\\] has no one slenderness"):
        rocking.fragility([(KOBE, "m/s2")], [0.5], base=rocking.Scene("tombstone"), im="pga-tan-alpha", progress=False)
    with pytest.raises(rocking.ConfigError, match="blocks: give at least one block"):
        rocking.fragility([(KOBE, "m/s2")], [0.5], progress=False)


def test_a_stacks_largest_exponent_is_the_clis(cli, tmp_path: Path) -> None:
    sets = ["run.tau_end=400", "analysis.lyapunov=true", "analysis.lyapunov_method=benettin"]
    cli.ok("--batch", "--preset", "stack-patterns", *[a for s in sets for a in ("--set", s)], "--out", str(tmp_path / "o"), "-q")
    expected = read_json(tmp_path / "o" / "summary.json")["lyapunov"]
    lyap = rocking.lyapunov(rocking.Scene("stack-patterns", tau_end=400), method="benettin")
    assert lyap.summary == expected
    assert lyap.method == "benettin" and lyap.largest_per_tau < 0
    # Two trajectories give the largest exponent only.
    assert lyap.spectrum.shape == (0,)
    run = rocking.simulate(rocking.Scene("stack-patterns", tau_end=400, analysis={"lyapunov": True, "lyapunov_method": "benettin"}))
    assert run.summary["lyapunov"] == expected


def test_a_stack_asked_for_tangent_exponents_is_refused_like_the_cli(cli, tmp_path: Path) -> None:
    sets = ["--set", "analysis.lyapunov=true", "--set", "analysis.lyapunov_method=tangent"]
    expected = cli.error("--batch", "--preset", "stack-patterns", *sets, "--out", str(tmp_path))
    assert "\"benettin\"" in expected
    with pytest.raises(rocking.ConfigError) as e:
        rocking.lyapunov(rocking.Scene("stack-patterns"), method="tangent")
    assert str(e.value) == expected
    # Unasked, a stack's method is the one it has.
    assert rocking.lyapunov(rocking.Scene("stack-patterns", tau_end=400)).method == "benettin"

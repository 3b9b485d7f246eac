"""A rocking frame ([frame], docs/model.md §16) from Python: the CLI's run and answer."""

from __future__ import annotations

from pathlib import Path

import pytest

import rocking
from conftest import floats, read_csv, read_json


def test_the_frame_preset_runs_as_the_cli_runs_it(cli, tmp_path: Path) -> None:
    cli.ok("--batch", "--preset", "rocking-frame", "--out", str(tmp_path / "o"), "-q")
    summary = read_json(tmp_path / "o" / "summary.json")
    run = rocking.simulate("rocking-frame")
    physical = run.summary["physical"]
    assert physical == summary["physical"]
    assert [b["name"] for b in physical["bodies"]] == ["column 1", "column 2", "beam"]
    assert run.summary["config"]["frame"] == {"width": 0.7, "height": 4.2, "columns": 2, "beam_mass_ratio": 2.0}
    # Every column of history.csv and events.csv, each body's included.
    for name in ("history", "events"):
        rows = read_csv(tmp_path / "o" / f"{name}.csv")
        table = getattr(run, name)
        assert list(table.dtype.names) == list(rows[0].keys()), name
        for col in table.dtype.names:
            if col in ("mode", "kind", "mode_before", "mode_after", "body"):
                assert list(table[col]) == [r[col] for r in rows], col
            else:
                assert list(table[col]) == floats(rows, col), col
    assert set(run.events["body"]) == {"columns"}


def test_a_frame_from_its_section_and_the_blocks_width_keyword_stay_apart() -> None:
    lone = rocking.Scene("rocking-frame", frame={"beam_mass_ratio": 0.0})
    assert lone.to_dict()["frame"]["beam_mass_ratio"] == 0.0
    assert rocking.simulate(lone).summary["physical"]["overturned"]
    # `width=` is the block's, as it always was: with [frame] it is refused.
    with pytest.raises(rocking.ConfigError, match="one of \\[block\\] and \\[frame\\]"):
        rocking.Scene("rocking-frame", width=1.0)


def test_a_frames_spectrum_is_the_clis(cli, tmp_path: Path) -> None:
    # A frame's tangent dynamics are generated from its equations: both
    # exponents, by default, as the CLI writes them.
    shaking = {"kind": "harmonic", "a_h": "0.5 g", "omega_h": "1.5 Hz"}
    sets = ["excitation.kind=harmonic", 'excitation.a_h="0.5 g"', 'excitation.omega_h="1.5 Hz"', "run.tau_end=400"]
    sets += ["analysis.lyapunov=true"]
    cli.ok("--batch", "--preset", "rocking-frame", *[a for s in sets for a in ("--set", s)], "--out", str(tmp_path / "o"), "-q")
    expected = read_json(tmp_path / "o" / "summary.json")["lyapunov"]
    lyap = rocking.lyapunov(rocking.Scene("rocking-frame", excitation=shaking, tau_end=400))
    assert lyap.summary == expected
    assert lyap.method == "tangent"
    assert lyap.spectrum.shape == (2,) and lyap.spectrum[0] < 0

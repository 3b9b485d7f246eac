"""Exceptions carry the CLI's one-line message (its stderr minus `error: `)."""

from __future__ import annotations

from pathlib import Path

import pytest

import rocking
from conftest import MAP_ARGS, SWEEP_ARGS, as_python


def test_a_bad_unit_names_the_key(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--preset", "fig3", "--set", "excitation.a_h=0.35 furlong", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene("fig3", a_h="0.35 furlong")
    assert str(e.value) == expected
    assert e.value.key == "excitation.a_h"
    assert isinstance(e.value, ValueError)


def test_an_unknown_key_and_an_out_of_range_value(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--set", "excitation.a_x=1", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene(config={"excitation.a_x": 1})
    assert str(e.value) == expected and e.value.key == "excitation.a_x"
    expected = cli.error("--batch", "--set", "friction.static=-1", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene(friction={"static": -1})
    assert str(e.value) == expected
    assert e.value.key is not None and e.value.key.startswith("friction.static")


def test_an_unknown_preset(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--preset", "nope", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene("nope")
    assert str(e.value) == expected


def test_a_toml_syntax_error_names_the_file_and_line(cli, tmp_path: Path) -> None:
    f = tmp_path / "bad.toml"
    f.write_text('[block]\nwidth = 0.4\nheight = = 1\n')
    expected = cli.error("--batch", "--config", str(f), "--out", str(tmp_path / "o"))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene(file=f)
    assert str(e.value) == expected
    assert (e.value.file, e.value.line) == (str(f), 3)


def test_a_bad_record_is_a_record_error_with_file_and_line(cli, tmp_path: Path) -> None:
    rec = tmp_path / "motion.dat"
    rec.write_text("0.00 0.01\n0.01 0.02\n0.02 oops\n")
    sets = ["excitation.kind=record", f"excitation.file_h={rec}", "excitation.unit_h=g"]
    args = ["--batch", *[a for s in sets for a in ("--set", s)], "--out", str(tmp_path / "o")]
    expected = cli.error(*args)
    with pytest.raises(rocking.RecordError) as e:
        rocking.Scene(kind="record", file_h=rec, unit_h="g")
    assert str(e.value) == expected
    assert e.value.key == "excitation.file_h"
    assert e.value.file == str(rec)
    assert e.value.line == 3
    assert isinstance(e.value, rocking.ConfigError)


def test_a_missing_record_has_no_line(tmp_path: Path) -> None:
    with pytest.raises(rocking.RecordError) as e:
        rocking.Scene(kind="record", file_h=tmp_path / "absent.dat", unit_h="g")
    assert e.value.file == str(tmp_path / "absent.dat") and e.value.line is None


def test_keywords_that_name_no_single_key() -> None:
    with pytest.raises(rocking.ConfigError, match="several sections") as e:
        rocking.Scene(static=0.5)
    assert e.value.key == "static"
    with pytest.raises(rocking.ConfigError, match="unknown key") as e:
        rocking.Scene(a_z=0.5)
    with pytest.raises(rocking.ConfigError, match="expected a number"):
        rocking.Scene(a_h=[1, 2])


def test_a_failed_run_is_a_run_error_with_the_clis_message(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--preset", "fig3", "--set", "run.max_steps=20", "--out", str(tmp_path), code=1)
    with pytest.raises(rocking.RunError) as e:
        rocking.simulate(rocking.Scene("fig3", max_steps=20))
    assert str(e.value) == expected


def test_sweep_and_map_input_errors_are_the_clis_naming_python_arguments(cli, tmp_path: Path) -> None:
    out = str(tmp_path / "o")
    expected = as_python(cli.error("sweep", "--preset", "fig3", "--param", "excitation.a_q", "--from", "1", "--to", "2", "--step", "0.5", "--out", out), SWEEP_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.sweep("fig3", "excitation.a_q", 1, 2, 0.5)
    assert str(e.value) == expected
    expected = as_python(cli.error("sweep", "--preset", "fig3", "--param", "excitation.a_v", "--from", "1", "--to", "2", "--step", "0", "--out", out), SWEEP_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.sweep("fig3", "excitation.a_v", 1, 2, 0)
    assert str(e.value) == expected
    expected = as_python(cli.error("sweep", "--preset", "fig3", "--param", "excitation.a_v", "--from", "1", "--to", "2", "--step", "0.5", "--transient", "900", "--out", out), SWEEP_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.sweep("fig3", "excitation.a_v", 1, 2, 0.5, transient=900)
    assert str(e.value) == expected
    expected = as_python(cli.error("map", "--preset", "fig3", "--x", "excitation.a_v", "1", "2", "3", "--y", "excitation.a_v", "1", "2", "3", "--out", out), MAP_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.outcome_map("fig3", ("excitation.a_v", 1, 2, 3), ("excitation.a_v", 1, 2, 3))
    assert str(e.value) == expected
    expected = as_python(cli.error("map", "--preset", "fig3", "--x", "excitation.a_v", "2", "1", "3", "--y", "excitation.a_h", "1", "2", "3", "--out", out), MAP_ARGS)
    with pytest.raises(rocking.ConfigError) as e:
        rocking.outcome_map("fig3", ("excitation.a_v", 2, 1, 3), ("excitation.a_h", 1, 2, 3))
    assert str(e.value) == expected
    with pytest.raises(rocking.ConfigError) as e:
        rocking.sweep("fig3", "excitation.a_v", 1, 2, 0.5, threads=0)
    assert str(e.value) == "threads=0: must be >= 1"


def test_lyapunov_of_a_pulse_is_refused_like_the_cli(cli, tmp_path: Path) -> None:
    expected = cli.error("--batch", "--set", "excitation.kind=pulse", "--set", "analysis.lyapunov=true", "--out", str(tmp_path))
    with pytest.raises(rocking.ConfigError) as e:
        rocking.lyapunov(rocking.Scene(kind="pulse"))
    assert str(e.value) == expected

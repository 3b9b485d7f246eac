"""rocking.Scene: presets, files, dicts and keywords, through the CLI's config layer."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

import rocking
from conftest import read_json


def test_a_preset_scene_resolves_like_the_cli(cli, tmp_path: Path) -> None:
    cli.ok("--batch", "--preset", "fig3", "--set", "excitation.a_h=0.35 g", "--out", str(tmp_path / "o"), "-q")
    summary = read_json(tmp_path / "o" / "summary.json")
    scene = rocking.Scene("fig3", a_h="0.35 g")
    assert scene.to_dict() == summary["config"]
    assert scene.resolved() == summary["resolved"]


def test_keywords_dicts_sections_and_dotted_keys_are_the_same_assignments() -> None:
    a = rocking.Scene("fig3", a_h="0.35 g", friction={"static": 0.7})
    b = rocking.Scene("fig3", config={"excitation.a_h": "0.35 g", "friction": {"static": 0.7}})
    c = rocking.Scene("fig3", config={"excitation": {"a_h": "0.35 g"}, "friction.static": 0.7})
    assert a.to_dict() == b.to_dict() == c.to_dict()
    assert a.to_dict()["friction"]["static"] == 0.7
    assert a.to_dict() != rocking.Scene("fig3").to_dict()


def test_a_scene_from_a_file_and_from_summary_json(tmp_path: Path, cli) -> None:
    f = tmp_path / "scene.toml"
    f.write_text('[block]\nwidth = "0.4 m"\nheight = "1.2 m"\n[excitation]\na_h = "0.3 g"\nomega_h = "2 Hz"\n')
    scene = rocking.Scene(file=f)
    cli.ok("--batch", "--config", str(f), "--out", str(tmp_path / "o"), "-q")
    summary = read_json(tmp_path / "o" / "summary.json")
    assert scene.to_dict() == summary["config"]
    # summary.json repeats its run, as `--config out/summary.json` does.
    again = rocking.Scene(file=tmp_path / "o" / "summary.json")
    assert again.to_dict() == summary["config"]


def test_with_returns_a_modified_copy() -> None:
    base = rocking.Scene("fig3")
    changed = base.with_(a_v_norm=2.3)
    assert changed.to_dict()["excitation"]["a_v"] == 2.3
    assert base.to_dict()["excitation"]["a_v"] != 2.3
    # t_end replaces the preset's tau_end, as `--set run.t_end=…` does.
    timed = base.with_(t_end="2 s")
    assert timed.to_dict()["run"]["tau_end"] == pytest.approx(2.0 * base.p_per_s, rel=1e-15)


def test_geometry_is_in_physical_units() -> None:
    s = rocking.Scene(width="0.6 m", height="0.8 m")
    assert s.r_m == pytest.approx(0.5)
    assert s.psi_rad == pytest.approx(0.6435011087932844)
    assert s.p_per_s == pytest.approx((3 * 9.81 / 2.0) ** 0.5)


def test_a_scene_pickles_and_is_resolved_again() -> None:
    s = rocking.Scene("fig3", a_h="0.35 g", friction={"static": 0.6})
    t = pickle.loads(pickle.dumps(s))
    assert isinstance(t, rocking.Scene)
    assert t.to_dict() == s.to_dict()
    assert repr(t) == repr(s)


def test_presets_are_the_clis(cli) -> None:
    names = rocking.presets()
    assert "default" in names and "fig3" in names
    listed = cli.run("--list-presets").stdout
    for n in names:
        assert n in listed


def test_a_preset_name_is_accepted_where_a_scene_is() -> None:
    assert rocking.simulate("fig3").summary["config"] == rocking.Scene("fig3").to_dict()

"""The units rule of the Python API: a bare number only where its meaning
is SI, dimensionless or stated by the name (`tau_end`, `*_norm`)."""

from __future__ import annotations

import pydoc
from pathlib import Path

import pytest

import rocking


@pytest.mark.parametrize(
    ("kwargs", "key", "hint"),
    [
        ({"a_h": 0.35}, "excitation.a_h", 'a_h="0.35 g", or write the normalised value as a_h_norm=0.35'),
        ({"omega_h": 8}, "excitation.omega_h", 'omega_h="8 Hz"'),
        ({"initial": {"theta": 0.1}}, "initial.theta", 'initial.theta="0.1 rad"'),
        ({"config": {"excitation.a_v": 2.3}}, "excitation.a_v", "excitation.a_v_norm=2.3"),
        ({"output_dt": 0.02}, "run.output_dt", 'output_dt="0.02 s"'),
    ],
)
def test_a_bare_number_where_the_config_reads_a_normalised_value_is_refused(kwargs, key, hint) -> None:
    with pytest.raises(rocking.ConfigError, match="a bare number is ambiguous") as e:
        rocking.Scene("fig3", **kwargs)
    assert e.value.key == key
    assert hint in str(e.value)


def test_the_norm_spelling_is_the_configs_bare_number(tmp_path: Path) -> None:
    f = tmp_path / "scene.toml"
    f.write_text("[excitation]\na_h = 0.35\nomega_h = 6\n[initial]\ntheta = 0.1\n")
    # A file starts from the scenario's defaults, as Scene.defaults() does.
    from_file = rocking.Scene(file=f).to_dict()
    for scene in (
        rocking.Scene.defaults(a_h_norm=0.35, omega_h_norm=6, theta_norm=0.1),
        rocking.Scene.defaults(config={"excitation.a_h_norm": 0.35, "excitation": {"omega_h_norm": 6}, "initial.theta_norm": 0.1}),
        rocking.Scene.defaults(excitation={"a_h_norm": 0.35, "omega_h_norm": 6}, initial={"theta_norm": 0.1}),
    ):
        assert scene.to_dict() == from_file
    with pytest.raises(rocking.ConfigError, match="_norm spelling takes a number"):
        rocking.Scene(a_h_norm="0.35 g")


def test_si_dimensionless_and_tau_end_take_bare_numbers() -> None:
    s = rocking.Scene("fig3", width=0.6, height=1.8, phase_h=0.5, tau_end=300, friction={"static": 0.7}, rtol=1e-9)
    d = s.to_dict()
    assert (d["block"]["width"], d["block"]["height"], d["excitation"]["phase_h"]) == (0.6, 1.8, 0.5)
    assert d["run"]["tau_end"] == 300 and d["friction"]["static"] == 0.7
    t = rocking.Scene("fig3", t_end=2.0)
    assert t.to_dict()["run"]["tau_end"] == pytest.approx(2.0 * t.p_per_s, rel=1e-15)


def test_numpy_numbers_are_accepted_integers_included() -> None:
    np = pytest.importorskip("numpy")
    s = rocking.Scene("fig3", max_steps=np.int64(20_000), width=np.float32(0.5), analysis={"spectrum": np.bool_(True)})
    d = s.to_dict()
    assert d["run"]["max_steps"] == 20_000 and d["block"]["width"] == 0.5 and d["analysis"]["spectrum"] is True


def test_help_lists_every_key_with_its_unit() -> None:
    assert rocking._rocking._undocumented_keys() == []
    text = pydoc.render_doc(rocking.Scene, renderer=pydoc.plaintext)
    for section, keys in [("excitation", ["a_h", "omega_h", "file_h", "pga_h"]), ("run", ["tau_end", "t_end", "output_dt"])]:
        assert f"[{section}]" in text
        for key in keys:
            assert f"    {key}: " in text, key
    assert "a_h_norm: units of psi*g" in text
    assert "block width B: m" in text


def test_an_array_where_a_number_belongs_is_one_clear_error() -> None:
    np = pytest.importorskip("numpy")
    with pytest.raises(rocking.ConfigError, match="expected a number") as e:
        rocking.Scene("fig3", width=np.array([0.5, 0.6]))
    assert e.value.key == "block.width"

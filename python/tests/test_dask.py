"""rocking.dask: chunks on a LocalCluster of 2 worker processes (loopback
only) give results identical to the single-machine ones."""

from __future__ import annotations

from typing import Iterator

import numpy as np
import pytest

import rocking
import rocking.dask

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client() -> Iterator[object]:
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    )
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def test_a_sweep_on_the_cluster_is_the_local_one(client) -> None:
    scene = rocking.Scene("fig3", a_h="0.3 g")
    local = rocking.sweep(scene, "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200)
    for chunks in (None, 3, 11):
        remote = rocking.dask.sweep(client, scene, "excitation.a_v", 1.5, 2.5, 0.1, transient=100, tau_end=200, chunks=chunks)
        assert remote.classes.equals(local.classes)
        assert remote.points.equals(local.points)
    # Both workers took part.
    assert len(client.scheduler_info()["workers"]) == 2


def assert_same_map(remote: rocking.OutcomeMap, local: rocking.OutcomeMap) -> None:
    assert remote.cells.equals(local.cells)
    # Byte for byte, NaN included.
    assert remote.cells.tobytes() == local.cells.tobytes()
    np.testing.assert_array_equal(remote.x, local.x)
    np.testing.assert_array_equal(remote.y, local.y)
    assert (remote.cells_run, remote.cells_stopped_early) == (local.cells_run, local.cells_stopped_early)
    assert len(remote.attractors) == len(local.attractors)
    for a, b in zip(remote.attractors, local.attractors):
        assert (a["id"], a["period"], a["point"], a["cells"]) == (b["id"], b["period"], b["point"], b["cells"])
        assert a["cycle"].tobytes() == b["cycle"].tobytes()


def test_a_map_on_the_cluster_is_the_local_one(client) -> None:
    # Refined from a 4-cell lattice: several batches, each split over the
    # workers.
    x, y = ("excitation.a_h", 0.5, 3.0, 12), ("excitation.omega_h", 4, 12, 9)
    local = rocking.outcome_map("fig3", x, y, transient=100, tau_end=200, coarse=4, progress=False)
    assert local.cells_run < 12 * 9
    for chunks in (3, 17):
        calls: list[tuple[int, int]] = []
        remote = rocking.dask.outcome_map(
            client, "fig3", x, y, transient=100, tau_end=200, coarse=4, chunks=chunks,
            progress=lambda done, total: calls.append((done, total)),
        )
        assert_same_map(remote, local)
        assert calls[-1] == (12 * 9, 12 * 9)
    assert remote.outcome.shape == (9, 12)
    full = rocking.outcome_map("fig3", x, y, transient=100, tau_end=200, full=True, progress=False)
    assert_same_map(rocking.dask.outcome_map(client, "fig3", x, y, transient=100, tau_end=200, full=True, chunks=5), full)


def test_a_basin_map_on_the_cluster_is_the_local_one(client) -> None:
    scene = rocking.Scene("fig4", a_v_norm=1.0)
    x, y = ("initial.theta", -0.6, 0.6, 9), ("initial.theta_dot", -0.6, 0.6, 9)
    # A coarse lattice of stride 2: the workers are told the attractors
    # the first level found, and cells stop on reaching them there too.
    local = rocking.outcome_map(scene, x, y, transient=100, tau_end=200, coarse=5, progress=False)
    assert len(local.attractors) >= 2
    assert local.cells_on_known_attractor > 0
    remote = rocking.dask.outcome_map(client, scene, x, y, transient=100, tau_end=200, coarse=5, chunks=4)
    assert_same_map(remote, local)
    assert remote.cells_on_known_attractor == local.cells_on_known_attractor


def test_a_failed_cell_on_a_worker_is_the_local_run_error(client) -> None:
    scene = rocking.Scene("fig3", max_steps=50)
    x, y = ("excitation.a_h", 0.5, 3.0, 4), ("excitation.omega_h", 6, 10, 3)
    with pytest.raises(rocking.RunError) as local:
        rocking.outcome_map(scene, x, y, transient=100, tau_end=200, progress=False)
    with pytest.raises(rocking.RunError) as remote:
        rocking.dask.outcome_map(client, scene, x, y, transient=100, tau_end=200, chunks=5)
    assert str(remote.value) == str(local.value)


def test_bad_input_fails_on_the_client_with_the_clis_message(client) -> None:
    with pytest.raises(rocking.ConfigError, match="^param=excitation.a_q: unknown key"):
        rocking.dask.sweep(client, "fig3", "excitation.a_q", 1, 2, 0.5)
    with pytest.raises(rocking.ConfigError, match="^continuation=sideways: "):
        rocking.sweep("fig3", "excitation.a_v", 1, 2, 0.5, continuation="sideways")


def test_a_failed_value_on_a_worker_is_a_run_error(client) -> None:
    with pytest.raises(rocking.RunError, match="simulation failed"):
        rocking.dask.sweep(client, rocking.Scene("fig3", max_steps=50), "excitation.a_v", 2.0, 2.2, 0.1, transient=100, tau_end=200)

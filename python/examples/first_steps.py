# %% [markdown]
# # First steps with `rocking` from Python
#
# A notebook in the percent format (open it in Jupyter with jupytext, or
# run it as a script: `python examples/first_steps.py`). It builds a scene
# with engineering units, runs it, looks at the events, sweeps one
# parameter and maps two, and runs the same sweep on a local Dask cluster.
# CI runs it (tests/test_example.py).

# %%
import numpy as np

import rocking

# The paper's Fig. 3 block, shaken at 0.35 g instead of the preset's amplitude.
scene = rocking.Scene("fig3", a_h="0.35 g", tau_end=400)
print(scene)
print(f"R = {scene.r_m:.3f} m, alpha = {np.degrees(scene.psi_rad):.2f} deg, p = {scene.p_per_s:.3f} rad/s")

# %% [markdown]
# ## One run
# The history is in normalised units (`tau`, `theta` = θ/α) and physical
# ones (`t` in s, `theta_rad`, `sliding_m`); `summary` is the CLI's
# summary.json.

# %%
run = rocking.simulate(scene)
print(run)
print("outcome:", run.summary["outcome"], "| impacts:", run.summary["impacts"])
print(f"largest rotation {np.abs(run.theta_rad).max():.4f} rad at t = {run.t[np.abs(run.theta_rad).argmax()]:.2f} s")
impacts = run.events[run.events["kind"] == "impact"]
print(f"{len(impacts)} impacts; the first at t = {impacts['t_s'][0]:.3f} s")
try:
    print(run.events.to_pandas().groupby("kind").size())
except ImportError:
    print("(pandas is not installed: skipping the DataFrame view)")

# %% [markdown]
# ## A bifurcation diagram over the vertical amplitude

# %%
sweep = rocking.sweep(scene, "excitation.a_v", 1.5, 2.5, 0.1, transient=200, tau_end=400)
for value, outcome, period in zip(sweep.values, sweep.outcome, sweep.period.filled(0)):
    print(f"a_v = {value:.1f}: {outcome}{f' (period {period})' if period else ''}")

# %% [markdown]
# ## An outcome map over amplitude and frequency

# %%
m = rocking.outcome_map(scene, ("excitation.a_h", 0.5, 3.0, 6), ("excitation.omega_h", 4.0, 10.0, 4), transient=200, tau_end=400)
for j, omega in enumerate(m.y):
    print(f"omega_h = {omega:4.1f}: " + " ".join(f"{o[:5]:>5}" for o in m.outcome[j]))
# Each cell's run stopped as soon as its class was certain; on a larger
# map, cells inside a region of one class inherit it without being run
# (`m.computed`). `full=True` runs every cell over its whole window.
print(f"{m.cells_run} of {m.outcome.size} cells run, {m.cells_stopped_early} of them stopped early")

# %% [markdown]
# ## The same sweep on a Dask cluster
# Here a local one with two workers; on a real cluster pass
# `Client("scheduler-address:8786")`. The result is identical. (Worker
# *processes* started from a script re-import the script, so this local
# cluster uses threads: the work releases the GIL, so they run in
# parallel all the same.)

# %%
try:
    from dask.distributed import Client, LocalCluster
except ImportError:
    print("(dask[distributed] is not installed: skipping the cluster)")
else:
    import rocking.dask

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            remote = rocking.dask.sweep(client, scene, "excitation.a_v", 1.5, 2.5, 0.1, transient=200, tau_end=400)
    assert remote.classes.equals(sweep.classes) and remote.points.equals(sweep.points)
    print("the cluster's sweep is identical to the local one:", len(remote.points), "points")

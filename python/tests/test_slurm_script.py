"""examples/slurm-sweep.sh: its array tasks and merge give the files of one `rocking sweep`."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from conftest import REPO

SCRIPT = REPO / "examples" / "slurm-sweep.sh"
SWEEP = "--preset fig3 --param excitation.a_v --from 1.5 --to 2.5 --step 0.1 --transient 100 --tau-end 200"


def test_the_array_tasks_and_the_merge_write_one_sweeps_files(cli, tmp_path: Path) -> None:
    out = tmp_path / "out"
    env = {**os.environ, "ROCKING": str(cli.exe), "SWEEP": SWEEP, "OUT": str(out)}
    # What Slurm sets in each array task of `--array=0-2`.
    for k in range(3):
        task = {**env, "SLURM_ARRAY_TASK_ID": str(k), "SLURM_ARRAY_TASK_COUNT": "3", "SLURM_CPUS_PER_TASK": "1"}
        p = subprocess.run(["bash", str(SCRIPT)], env=task, capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
    p = subprocess.run(["bash", str(SCRIPT), "merge"], env=env, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    whole = tmp_path / "whole"
    cli.ok("sweep", *SWEEP.split(), "--out", str(whole), "-q")
    for name in ("classes.csv", "points.csv", "sweep.json"):
        assert (out / "merged" / name).read_bytes() == (whole / name).read_bytes(), name

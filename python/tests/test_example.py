"""The notebook-style example runs to the end."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "first_steps.py"


def test_the_first_steps_example_runs() -> None:
    p = subprocess.run([sys.executable, str(EXAMPLE)], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    assert "outcome:" in p.stdout
    assert "the cluster's sweep is identical to the local one" in p.stdout

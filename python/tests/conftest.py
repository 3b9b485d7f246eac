"""Shared fixtures: the CLI binary the Python results are compared with."""

from __future__ import annotations

import csv
import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[2]


def cli_path() -> Path:
    """The `rocking` binary: $ROCKING_CLI, else the repository's
    target/debug or target/release build (`cargo build` at the root)."""
    env = os.environ.get("ROCKING_CLI")
    candidates = [Path(env)] if env else [REPO / "target" / "debug" / "rocking", REPO / "target" / "release" / "rocking"]
    for c in candidates:
        if c.is_file():
            return c
    raise RuntimeError(
        f"the rocking CLI is needed to compare with: build it with `cargo build` at {REPO} or set ROCKING_CLI"
    )


class Cli:
    """Runs the CLI and reads what it wrote."""

    def __init__(self, exe: Path) -> None:
        self.exe = exe

    def run(self, *args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([str(self.exe), *args], capture_output=True, text=True, timeout=600)

    def ok(self, *args: str) -> None:
        p = self.run(*args)
        assert p.returncode == 0, p.stderr

    def error(self, *args: str, code: int = 2) -> str:
        """The CLI's one-line error for `args`, without `error: `."""
        p = self.run(*args)
        assert p.returncode == code, (p.returncode, p.stderr)
        lines = [line for line in p.stderr.splitlines() if line.startswith("error: ")]
        assert len(lines) == 1, p.stderr
        return lines[0].removeprefix("error: ")


@pytest.fixture(scope="session")
def cli() -> Cli:
    return Cli(cli_path())


#: The Python argument of each CLI flag, per function: Python's messages
#: are the CLI's with the flag written as the argument that gave the value
#: (`--threads 0: …` → `threads=0: …`).
SWEEP_ARGS = {"--param": "param", "--from": "start", "--to": "stop", "--step": "step", "--transient": "transient", "--tau-end": "tau_end", "--continuation": "continuation", "--threads": "threads"}
MAP_ARGS = {"--x": "x", "--y": "y", "--transient": "transient", "--tau-end": "tau_end", "--coarse": "coarse", "--threads": "threads"}
SPECTRUM_ARGS = {"--record": "record", "--unit": "unit", "--from": "sizes[0]", "--to": "sizes[1]", "--count": "sizes[2]", "--b-over-h": "b_over_h", "--scale": "scale", "--pga": "pga"}


def as_python(message: str, args: dict[str, str]) -> str:
    """A CLI message with its flags written as Python arguments: `--flag
    VALUE` (a number, or a word ending in a colon) as `name=VALUE`, a flag
    alone as `name`."""
    import re

    def one(m: re.Match[str]) -> str:
        flag, value = m.group(1), m.group(2)
        if flag not in args:
            return m.group(0)
        return f"{args[flag]}={value}" if value else args[flag]

    return re.sub(r"(--[a-z][a-z-]*)(?: ([-.0-9]\S*|\S+:(?=\s|$)))?", one, message)


def read_csv(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_json(path: Path) -> Any:
    return json.loads(path.read_text())


def floats(rows: list[dict[str, str]], name: str) -> list[float]:
    """Column `name` parsed: the CLI writes shortest round-trip numbers, so
    equal floats mean equal bits."""
    return [float(r[name]) for r in rows]

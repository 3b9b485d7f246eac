"""The build backend of `pip install ./python` and `pip wheel ./python`:
maturin's, with the wheel's platform tag checked and set by maturin's
auditwheel (`--compatibility pypi`: the oldest manylinux policy the
extension's symbols allow, e.g. manylinux_2_35 built on Debian 12).

maturin's own PEP 517 backend builds with `--compatibility off` (tag
`linux_x86_64`, which no other machine's pip accepts) unless told
otherwise, and `[tool.maturin] compatibility` in pyproject.toml does not
override that; MATURIN_PEP517_ARGS does. A user's own MATURIN_PEP517_ARGS
is kept as given.
"""

from __future__ import annotations

import os

if "--compatibility" not in os.environ.get("MATURIN_PEP517_ARGS", ""):
    os.environ["MATURIN_PEP517_ARGS"] = f"{os.environ.get('MATURIN_PEP517_ARGS', '')} --compatibility pypi".strip()

from maturin import (  # noqa: E402 - after the environment is set
    build_editable,
    build_sdist,
    build_wheel,
    get_requires_for_build_sdist,
    get_requires_for_build_wheel,
    prepare_metadata_for_build_wheel,
)

__all__ = [
    "build_editable",
    "build_sdist",
    "build_wheel",
    "get_requires_for_build_sdist",
    "get_requires_for_build_wheel",
    "prepare_metadata_for_build_wheel",
]

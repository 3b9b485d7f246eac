"""The wheel `pip wheel ./python` builds is tagged manylinux, so a lab can
build it once and install it on its other Linux machines. CI builds that
wheel once, installs the package from it and names it in $ROCKING_WHEEL."""

from __future__ import annotations

import os
import platform
import re
from pathlib import Path

import pytest

import rocking


def test_the_shared_wheel_is_tagged_manylinux() -> None:
    wheel = os.environ.get("ROCKING_WHEEL")
    if not wheel:
        pytest.skip("no wheel named: CI builds one with `pip wheel ./python` and sets ROCKING_WHEEL")
    name = Path(wheel).name
    # name-version-python-abi-platform.whl; the platform tag names the
    # oldest glibc the extension's symbols need (maturin's auditwheel check).
    m = re.fullmatch(r"rocking-([^-]+)-(cp\d+)-(cp\d+|abi3)-(.+)\.whl", name)
    assert m is not None, name
    assert m.group(1) == rocking.__version__
    platforms = m.group(4).split(".")
    assert all(re.fullmatch(rf"manylinux_\d+_\d+_{platform.machine()}", p) for p in platforms), name
    # The installed package is that wheel's, not a build of the source folder.
    assert "site-packages" in Path(rocking.__file__).parts

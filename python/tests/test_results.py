"""Results keep their inputs, convert to pandas and xarray, mark missing
values as missing (never 0), and use signed integer indices."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import rocking
from conftest import REPO

KOBE = REPO / "assets" / "records" / "kobe-1995.dat"


def test_a_sweep_and_a_map_keep_their_inputs_and_convert_to_xarray() -> None:
    scene = rocking.Scene("fig3", a_h="0.3 g")
    s = rocking.sweep(scene, "excitation.a_v", 2.0, 2.2, 0.1, transient=100, progress=False)
    assert s.scene is scene and (s.start, s.stop, s.step, s.transient) == (2.0, 2.2, 0.1, 100)
    assert s.tau_end == scene.to_dict()["run"]["tau_end"]
    assert s.classes["index"].dtype == np.int64 and s.points["index"].dtype == np.int64
    assert s.points["k"].dtype == np.int64
    # No exponent was asked for: missing, not 0.
    assert np.isnan(s.classes["lyapunov"]).all() and np.ma.getmaskarray(s.lyapunov).all()
    m = rocking.outcome_map(scene, ("excitation.a_h", 0.5, 1.0, 2), ("excitation.omega_h", 6, 10, 3), transient=100, tau_end=200, progress=False)
    assert m.x_axis == ("excitation.a_h", 0.5, 1.0, 2) and m.tau_end == 200 and m.scene is scene
    xr = pytest.importorskip("xarray")
    ds = m.to_xarray()
    assert isinstance(ds, xr.Dataset)
    assert ds["outcome"].dims == ("excitation.omega_h", "excitation.a_h")
    np.testing.assert_array_equal(ds["excitation.a_h"].values, m.x)
    np.testing.assert_array_equal(ds["outcome"].values, m.outcome)
    assert ds.attrs["tau_end"] == 200
    sx = s.to_xarray()
    np.testing.assert_array_equal(sx["value"].values, s.values)


def test_a_block_that_did_not_overturn_has_no_time_and_fits_convert_to_pandas() -> None:
    pd = pytest.importorskip("pandas")
    f = rocking.fragility([(KOBE, "m/s2")], [0.05, 1.5], [(0.3, 1.2)], progress=False)
    assert f.runs["run"].dtype == np.int64 and f.runs["block"].dtype == np.int64
    rest = f.runs["end"] != "overturned"
    assert rest.any() and np.isnan(f.runs["t_end_s"][rest]).all()
    assert (f.runs["t_end_s"][~rest] > 0).all()
    assert f.blocks == [(0.3, 1.2)] and f.levels.tolist() == [0.05, 1.5] and f.base is not None
    fits = f.fits_to_pandas()
    assert isinstance(fits, pd.DataFrame) and list(fits["curve"]) == ["overturning", "exceedance"]
    assert fits.loc[0, "width_m"] == 0.3
    fractions = f.fractions_to_pandas()
    assert list(fractions["level"]) == [0.05, 1.5]
    assert f.to_pandas()["t_end_s"].isna().tolist() == rest.tolist()
    xr = pytest.importorskip("xarray")
    ds = f.to_xarray()
    assert ds["end"].shape == (1, 2, 1) and list(ds["record"].values) == ["kobe-1995"]


def test_a_spectrum_keeps_its_inputs_and_marks_missing_scales() -> None:
    s = rocking.spectrum(KOBE, (0.5, 2.0, 3), unit="m/s2", b_over_h=[0.2, 0.3], overturn_scale=True, search_max=1.0, progress=False)
    assert s.sizes == (0.5, 2.0, 3) and s.b_over_h == (0.2, 0.3) and s.record == KOBE
    b = s.blocks
    assert np.isnan(b["overturn_scale"][~b["has_overturn_scale"]]).all()
    assert np.isnan(b["t_end_s"][~b["has_t_end"]]).all()
    xr = pytest.importorskip("xarray")
    ds = s.to_xarray()
    assert ds["peak_theta_over_alpha"].dims == ("b_over_h", "r_m") and ds["peak_theta_over_alpha"].shape == (2, 3)


def test_numpy_integers_are_accepted_for_integer_arguments() -> None:
    one = rocking.sweep("fig3", "excitation.a_v", 2.0, 2.1, 0.1, transient=100, tau_end=200, threads=np.int64(1), progress=False)
    m = rocking.outcome_map("fig3", ("excitation.a_h", 0.5, 1.0, np.int64(2)), ("excitation.omega_h", 6, 10, np.int32(2)), transient=100, tau_end=200, progress=False)
    assert len(one.values) == 2 and m.outcome.shape == (2, 2)


def test_python_m_pytest_in_the_package_folder_imports_the_installed_package() -> None:
    # `python -m pytest` puts the working folder on sys.path: the package
    # source there must not shadow the installed package (with its
    # extension).
    here = Path(__file__).resolve().parents[1]
    p = subprocess.run([sys.executable, "-c", "import rocking; print(rocking._rocking.__name__)"], cwd=here, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "rocking._rocking"

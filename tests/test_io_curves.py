"""Load-curve and pull-off Datasets: metadata, provenance, atomic writes."""
import numpy as np
import pytest

from dhfield import model
from dhfield.io import read_netcdf
from dhfield.io.curves import CURVE_VARIABLES, load_curve_dataset, pull_off_dataset, write_load_curve


def test_every_variable_has_units_and_long_name():
    ds = load_curve_dataset(model.load_curve(1.0, 0.9, n=5))
    for name in CURVE_VARIABLES:
        assert {"units", "long_name"} <= set(ds[name].attrs)
    for key in ("Conventions", "source", "references", "history", "param_mu", "param_beta0"):
        assert key in ds.attrs


def test_round_trip_values_and_attrs(tmp_path):
    curve = model.load_curve(2.0, 0.8, n=9)
    path = write_load_curve(curve, tmp_path / "x.nc")
    ds = read_netcdf(path)
    ref = load_curve_dataset(curve)
    for name in CURVE_VARIABLES:
        np.testing.assert_array_equal(ds[name].values, ref[name].values)
        assert ds[name].attrs == ref[name].attrs
    assert ds.attrs["param_beta0"] == 0.8


def test_pull_off_dataset_shape():
    mu, beta0 = np.array([0.5, 1.0, 5.0]), np.array([0.8, 0.9])
    p = model.pull_off(mu[:, None], beta0[None, :])
    ds = pull_off_dataset(mu, beta0, {"W_star": p.W_star, "a_star": p.a_star})
    assert ds["W_star"].dims == ("mu", "beta0") and ds["W_star"].shape == (3, 2)
    assert "pull-off" in ds["W_star"].attrs["long_name"]


def test_unknown_suffix_is_an_error(tmp_path):
    with pytest.raises(ValueError, match=r"\.nc or \.csv"):
        write_load_curve(model.load_curve(1.0, 0.9, n=3), tmp_path / "x.txt")
    assert list(tmp_path.iterdir()) == []


def test_written_files_get_default_permissions(tmp_path):
    import os

    path = write_load_curve(model.load_curve(1.0, 0.9, n=3), tmp_path / "x.nc")
    umask = os.umask(0)
    os.umask(umask)
    assert (path.stat().st_mode & 0o777) == (0o666 & ~umask)

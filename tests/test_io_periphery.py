"""Periphery Datasets (dhfield.io.periphery): schema units, canonical (beta0, mu) dims, round trip."""
import numpy as np
import pytest

from dhfield.models import dh_elliptic as model, dh_elliptic_periphery as periphery
from dhfield.core import schema
from dhfield.io import read_netcdf
from dhfield.io import periphery as iop

THETA = np.linspace(0.0, 0.5 * np.pi, 4)


def test_pull_off_periphery_round_trip(tmp_path):
    mu, beta0 = np.array([[1.0, 3.0]]), np.array([[0.85]])
    po = model.pull_off(mu=mu, beta0=beta0)
    prof = periphery.periphery_at_pull_off(po, THETA)
    law = periphery.cohesive_law(po.a_star, po.c_star, po.ellipticity, po.v, THETA[[0, -1]], n_points=5)
    ds = iop.pull_off_periphery_dataset(po, prof, law, beta0=beta0[:, 0], mu=mu[0])
    for name in iop.PROFILE_VARIABLES:
        assert ds[name].dims == ("beta0", "mu", "theta")
        assert ds[name].attrs["units"] == "1"
        assert ds[name].attrs["long_name"].startswith(schema.attrs(name, nondimensional=True)["long_name"])
    assert ds["law_stress"].dims == ("beta0", "mu", "law_theta", "sample")
    assert ds["theta"].attrs["units"] == schema.units("theta") == "rad"
    back = read_netcdf(iop.write_dataset(ds, tmp_path / "p.nc"))
    for name in ds.variables:
        np.testing.assert_array_equal(back[name].values, ds[name].values)
        assert back[name].attrs == ds[name].attrs, name
        assert back[name].dims == ds[name].dims
    for name in ds.coords:
        assert "_FillValue" not in back[name].encoding, name
    np.testing.assert_array_equal(back["work_of_adhesion"].values[0, 1], prof.work_of_adhesion[0, 1])


def test_beta0_and_mu_are_keyword_only():
    """(beta0, mu) is GRID_DIMS' order, (mu, beta0) was the old one: a positional grid would swap them silently."""
    grid = ([1.0], [0.9])
    for call in (lambda: iop.pull_off_periphery_dataset(*grid, None, None),
                 lambda: iop.equal_beta_dataset(*grid, None, {}),
                 lambda: iop.eq30_dataset(*grid, 1, 1, 1, 1, 1),
                 lambda: iop.load_curve_periphery_dataset(*grid, {}, {})):
        with pytest.raises(TypeError, match="positional"):
            call()

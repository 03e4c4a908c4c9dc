"""netCDF of adhesive BEM solutions: round trip of values, units, long_name and CF flags."""
import numpy as np
import pytest
from numpy.testing import assert_array_equal

from dhfield.analysis.bem_start import AdhesiveOptions
from dhfield.bem import adhesive_pull_off
from dhfield.io.solution import (PHASES, REGIONS, pull_off_dataset, read_solution, state_dataset,
                                 write_solution)


@pytest.fixture(scope="module")
def small_result():
    # N = 16: a coarse but complete path (loading, unloading, refinement); 300 CG iterations
    # per state bound the cost of the states that do not converge on so coarse a grid.
    return adhesive_pull_off(mu=1.0, beta0=0.8, n=16, progress=False, options=AdhesiveOptions(max_iter=300))


def _attrs_round_trip(ds, back):
    for name in ds.variables:
        for key in ("units", "long_name", "flag_meanings"):
            if key in ds[name].attrs:
                assert back[name].attrs[key] == ds[name].attrs[key], (name, key)


def test_pull_off_round_trip(tmp_path, small_result):
    res = small_result
    ds = pull_off_dataset(res)
    back = read_solution(write_solution(res, tmp_path / "po.nc"))
    _attrs_round_trip(ds, back)
    for key in ("W_star", "a_star", "b_star", "c_star", "d_star", "delta_star"):
        assert float(back[f"{key}_pull_off"]) == getattr(res, key)
    # the record's ellipticities, stored under the names of the state's (beta_ab, beta_cd)
    assert float(back["beta_ab_pull_off"]) == res.ellipticity
    assert float(back["beta_cd_pull_off"]) == res.adhesive_ellipticity
    assert back["W_star_pull_off"].attrs["units"] == "1" and "Eq. (34)" in back["W_star_pull_off"].attrs["description"]
    st = res.path.pull_off_state
    # fields are stored (y, x) (rows y, columns x); the solver's arrays are (x, y)
    assert back["gap"].dims == ("y", "x")
    assert_array_equal(back["pressure"].values, st.pressure.T)
    assert_array_equal(back["gap"].values, st.gap.T)
    # the region flags are the contact mask and the majority cohesive cells
    region = back["region"].transpose("x", "y").values
    assert_array_equal(region == REGIONS.index("contact"), st.contact)
    assert_array_equal(region == REGIONS.index("cohesive_zone"), (st.cohesive > 0.5) & ~st.contact)
    assert list(back["region"].attrs["flag_values"]) == [0, 1, 2]
    # the path, step by step, with its flags
    assert back.sizes["step"] == res.n_steps
    assert_array_equal(back["approach_path"].values, res.path.approach)
    assert_array_equal(back["converged_path"].values.astype(bool), res.path.converged)
    meanings = back["phase"].attrs["flag_meanings"].split()
    assert meanings[:len(PHASES)] == list(PHASES)
    assert_array_equal(np.array(meanings)[back["phase"].values], res.path.phase)
    assert_array_equal(back["residual_path"].values, res.path.residual)
    # W* per step is the load in the normalisation of Eq. (34) (R = dgamma = 1)
    sin_skew = back.attrs["param_sin_skew"]
    assert_array_equal(back["W_star_path"].values, res.path.load * sin_skew / (2 * np.pi))
    assert back.attrs["param_beta0"] == 0.8 and back.attrs["converged"] == int(res.converged)
    assert back.attrs["n_failures"] == len(res.failures)


def test_state_dataset_si_units():
    from test_dh_elliptic_periphery import _radial_dugdale_state

    state, _, _ = _radial_dugdale_state(16)
    ds = state_dataset(state)
    assert ds["pressure"].attrs["units"] == "Pa" and ds["gap"].attrs["units"] == "m"
    assert ds["load"].attrs["units"] == "N" and ds["x"].attrs["units"] == "m"
    assert ds.attrs["param_law"] == "dugdale" and ds.attrs["param_law_range"] == 0.4
    nd = state_dataset(state, nondimensional=True)
    assert nd["gap"].attrs["units"] == "1" and "c_r^2/R" in nd["gap"].attrs["long_name"]


def test_write_is_checked_and_atomic(tmp_path, small_result):
    with pytest.raises(ValueError, match="out"):
        write_solution(small_result, tmp_path / "missing" / "x.nc")
    with pytest.raises(ValueError, match="out"):
        write_solution(small_result, tmp_path)
    assert list(tmp_path.iterdir()) == []
    bad = tmp_path / "not.nc"
    bad.write_text("no")
    with pytest.raises(ValueError, match="not.nc"):
        read_solution(bad)


def test_fields_are_stored_y_by_x_and_old_files_still_read(tmp_path):
    """Issue 17: fields were stored (x, y), so ds.gap.plot() put x on the vertical axis.  The stored
    gap now has rows y and columns x (xarray's default plot is the right way up); a file of the old
    layout is turned on reading."""
    import xarray as xr

    from test_dh_elliptic_periphery import _radial_dugdale_state

    state, _, _ = _radial_dugdale_state(16)
    ds = state_dataset(state)
    assert ds["gap"].dims == ("y", "x") and ds["region"].dims == ("y", "x")
    assert_array_equal(ds["gap"].sel(x=ds.x[3], y=ds.y[5]).values, state.gap[3, 5])
    old = ds.transpose(..., "x", "y")          # the layout of files written before the change
    path = tmp_path / "old.nc"
    old.to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert raw["gap"].dims == ("x", "y")
    back = read_solution(path)
    assert back["gap"].dims == ("y", "x")
    assert_array_equal(back["gap"].values, state.gap.T)


def test_si_variables_of_a_pull_off(tmp_path, small_result):
    """With the contact's parameters the file carries the SI pull-off, the SI force path and the inputs,
    with their schema units.  Contact chosen so that beta0 = 0.8 is hit: principal radii with
    R'/R'' of beta0 = 0.8 (dhfield.core.geometry, Eq. 9), and sigma0 for mu = 1 (Eq. 35)."""
    from dhfield.core import geometry
    from dhfield.analysis.dimensional import contact_parameters_from_principal_radii
    from dhfield.io.solution import SI_INPUT_KEYS, SI_PULL_OFF_KEYS, pull_off_si

    res = small_result
    ratio = float(geometry.radius_ratio(res.beta0))
    r1, r2 = 4e-3 * np.sqrt(ratio), 4e-3 / np.sqrt(ratio)         # R = sqrt(R'R'') = 4 mm
    e_star, dgamma = 1e6, 0.05                                     # E* = E/(2(1 - nu^2)), E = 1.5 MPa
    sigma0 = res.mu * (e_star ** 2 * dgamma / 4e-3) ** (1.0 / 3.0)  # Eq. (35) inverted
    params = contact_parameters_from_principal_radii(1.5e6, 0.5, 1.5e6, 0.5, r1, r2, dgamma, sigma0)
    assert float(params.mu) == pytest.approx(res.mu, rel=1e-12)
    params = type(params)(**{**params.__dict__, "beta0": res.beta0, "mu": res.mu})  # exact case of the result
    back = read_solution(write_solution(res, tmp_path / "si.nc", params=params))
    si = pull_off_si(res, params)
    for key in SI_PULL_OFF_KEYS:
        assert float(back[f"{key}_pull_off"]) == si[key]
    for key in SI_INPUT_KEYS:
        assert float(back[key]) == si[key]
    assert back["force_pull_off"].attrs["units"] == "N" and back["semi_major_pull_off"].attrs["units"] == "m"
    assert back["max_adhesive_stress"].attrs["units"] == "Pa" and back["force_path"].attrs["units"] == "N"
    # the load unit of Eq. (34), 2 pi R dgamma/sin(theta_skew), and the path's load in R dgamma
    sin_skew = float(geometry.sin_skew_angle(res.beta0))
    assert si["force"] == pytest.approx(res.W_star * 2 * np.pi * 4e-3 * dgamma / sin_skew, rel=1e-12)
    np.testing.assert_allclose(back["force_path"].values, res.path.load * 4e-3 * dgamma, rtol=1e-12)
    np.testing.assert_allclose(back["force_path"].values * sin_skew / (2 * np.pi * 4e-3 * dgamma),
                               back["W_star_path"].values, rtol=1e-12)
    c_r = (4e-3 ** 2 * dgamma / e_star) ** (1.0 / 3.0)                 # Eq. (33)
    assert si["semi_major"] == pytest.approx(res.a_star * c_r, rel=1e-12)
    assert back.attrs["length_unit_m"] == pytest.approx(c_r, rel=1e-12)
    with pytest.raises(ValueError, match="params must describe the solved case"):
        pull_off_si(res, type(params)(**{**params.__dict__, "mu": 2.0 * res.mu}))

"""JKR: closed-form pull-off, stationarity, inverse, units, bad input."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.models import jkr
from tests._reference import circular_pull_off

#: closed forms evaluated in double precision
TOL_EXACT = 1e-14
#: central differences with h = 1e-5: truncation ~h^2 |W'''| ~ 1e-10
TOL_STATIONARY = 1e-8

R, E, DG = 2e-6, 1.5e9, 0.04  # SI: m, Pa, J/m^2


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_pull_off_matches_closed_form(control):
    ref = circular_pull_off()[("jkr", control)]
    s = jkr.pull_off_nondimensional(1.0, 1.0, control=control)
    assert_allclose([s["W_star"], s["a_star"], s["delta_star"]],
                    [ref["W_star"], ref["a_star"], ref["delta_star"]], rtol=TOL_EXACT)


@pytest.mark.parametrize("control,key", [("load", "W_star"), ("displacement", "delta_star")])
def test_pull_off_is_stationary(control, key):
    a = float(jkr.pull_off_nondimensional(1.0, 1.0, control=control)["a_star"])
    h = 1e-5
    d = (jkr.load_curve_nondimensional(a + h)[key] - jkr.load_curve_nondimensional(a - h)[key]) / (2 * h)
    assert abs(d) < TOL_STATIONARY


def test_dimensional_and_inverse():
    po = jkr.pull_off(R, E, DG)
    assert_allclose(po.force, -1.5 * np.pi * R * DG, rtol=TOL_EXACT)
    assert_allclose(po.semi_major ** 3, 9 * np.pi * DG * R**2 / (8 * E), rtol=TOL_EXACT)
    assert_allclose(jkr.pull_off_force(R, E, DG, control="displacement"), -5 / 6 * np.pi * R * DG,
                    rtol=TOL_EXACT)
    a = np.linspace(po.semi_major, 5 * po.semi_major, 7)
    c = jkr.load_curve(a, R, E, DG)
    assert_allclose(jkr.contact_radius(c.force, R, E, DG), a, rtol=1e-7)  # sqrt at pull-off: ~sqrt(eps)
    assert_allclose(c.approach, a**2 / R - np.sqrt(2 * np.pi * a * DG / E), rtol=1e-12)


def test_unit_neutral():
    """The same problem in m/Pa and in um/MPa gives the same nondimensional curve."""
    a = np.array([1e-8, 5e-8, 2e-7])
    c1 = jkr.load_curve(a, R, E, DG)
    # um, uN, MPa (= uN/um^2); J/m^2 = uN/um is unchanged
    c2 = jkr.load_curve(a * 1e6, R * 1e6, E * 1e-6, DG)
    assert_allclose(c2.force, c1.force * 1e6, rtol=1e-12)  # uN
    assert_allclose(c2.approach, c1.approach * 1e6, rtol=1e-12)


@pytest.mark.parametrize("kwargs,name", [
    (dict(contact_radius=-1e-9), "contact_radius"),
    (dict(effective_radius=0.0), "effective_radius"),
    (dict(reduced_modulus=-1.0), "reduced_modulus"),
    (dict(work_of_adhesion=np.nan), "work_of_adhesion"),
])
def test_bad_input_load_curve(kwargs, name):
    args = dict(contact_radius=1e-8, effective_radius=R, reduced_modulus=E, work_of_adhesion=DG)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        jkr.load_curve(**args)


def test_bad_input_other():
    with pytest.raises(ValueError, match="control"):
        jkr.pull_off(R, E, DG, control="force")
    with pytest.raises(ValueError, match="load"):
        jkr.contact_radius(-2 * np.pi * R * DG, R, E, DG)
    with pytest.raises(ValueError, match="load"):
        jkr.contact_radius("x", R, E, DG)

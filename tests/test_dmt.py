"""DMT/Bradley: closed forms, units, bad input."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.models import dmt
from tests._reference import circular_pull_off

#: closed forms evaluated in double precision
TOL_EXACT = 1e-14

R, E, DG = 2e-6, 1.5e9, 0.04


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_pull_off(control):
    ref = circular_pull_off()[("dmt", control)]
    s = dmt.pull_off_nondimensional(1.0, 1.0, control=control)
    assert_allclose([s["W_star"], s["a_star"], s["delta_star"]],
                    [ref["W_star"], ref["a_star"], ref["delta_star"]], atol=TOL_EXACT)
    assert_allclose(dmt.pull_off_force(R, E, DG, control=control), -2 * np.pi * R * DG, rtol=TOL_EXACT)


def test_curve_and_inverse():
    a = np.geomspace(1e-9, 1e-6, 9)
    c = dmt.load_curve(a, R, E, DG)
    assert_allclose(c.force, 4 * E * a**3 / (3 * R) - 2 * np.pi * R * DG, rtol=TOL_EXACT)
    assert_allclose(c.approach, a**2 / R, rtol=TOL_EXACT)
    assert_allclose(dmt.contact_radius(c.force, R, E, DG), a, rtol=1e-6)  # a^3 from a difference ~ 2 pi R dg


def test_bad_input():
    with pytest.raises(ValueError, match="contact_radius"):
        dmt.load_curve(-1.0, R, E, DG)
    with pytest.raises(ValueError, match="effective_radius"):
        dmt.pull_off(-R, E, DG)
    with pytest.raises(ValueError, match="work_of_adhesion"):
        dmt.load_curve(1e-8, R, E, np.inf)
    with pytest.raises(ValueError, match="load"):
        dmt.contact_radius(-3 * np.pi * R * DG, R, E, DG)
    with pytest.raises(ValueError, match="control"):
        dmt.pull_off(R, E, DG, control="")

"""The separated Maugis-Dugdale sphere (dhfield.models.maugis_dugdale_separated): limits and the join with MD."""
import numpy as np
import pytest

from dhfield.models import maugis_dugdale_separated as ds
from dhfield.models import maugis_dugdale as md
from dhfield.core.transition import maugis_parameter

#: both sides are closed forms (quadratic roots): agreement to rounding
TOL_CLOSED = 1e-12

_D_UNIT = (9.0 * np.pi**2 / 16.0) ** (1.0 / 3.0)  # delta* per Maugis D (physics notes, Sec. 5)
_A_UNIT = (3.0 * np.pi / 4.0) ** (1.0 / 3.0)  # a* per Maugis A


@pytest.mark.parametrize("mu", [0.05, 0.3, 1.0, 3.0, 30.0])
def test_branch_joins_the_md_curve_at_zero_contact(mu):
    # the end of the separated branch is the a = 0 end point of the MD contact curve (Maugis 1992)
    c = ds.zone_radius_at_contact(mu)
    sep = ds.separated_branch(c, mu)
    end = md.load_curve_nondimensional(0.0, mu)
    np.testing.assert_allclose(c, end["c_star"], rtol=TOL_CLOSED)
    np.testing.assert_allclose(sep["W_star"], end["W_star"], rtol=TOL_CLOSED)
    np.testing.assert_allclose(sep["delta_star"], end["delta_star"], rtol=TOL_CLOSED)


@pytest.mark.parametrize("mu", [0.1, 1.0, 10.0])
def test_branch_in_maugis_units(mu):
    # independent form in Maugis' units (derived in the test from the same assumptions):
    # P = -lambda pi x^2/2, D = x^2/2 - 8 lambda x/(3 pi) - 2/(pi lambda), x = c/(pi dgamma R^2/K)^(1/3)
    lam = maugis_parameter(mu)
    x = np.linspace(0.0, ds.zone_radius_at_contact(mu) / _A_UNIT, 7)
    sep = ds.separated_branch(x * _A_UNIT, mu)
    np.testing.assert_allclose(sep["W_star"], -lam * np.pi * x**2 / 4.0, rtol=TOL_CLOSED, atol=1e-15)
    d = x**2 / 2.0 - 8.0 * lam * x / (3.0 * np.pi) - 2.0 / (np.pi * lam)
    np.testing.assert_allclose(sep["delta_star"], d * _D_UNIT, rtol=TOL_CLOSED)


def test_branch_starts_force_free_at_the_dugdale_range():
    st = ds.separated_branch(0.0, 2.0)
    assert st["W_star"] == 0.0
    assert st["delta_star"] == -ds.dugdale_range(2.0) == -0.5


@pytest.mark.parametrize("bad", [-1.0, np.nan, np.inf])
def test_bad_inputs_are_named(bad):
    with pytest.raises(ValueError, match="c_star"):
        ds.separated_branch(bad, 1.0)
    with pytest.raises(ValueError, match="mu"):
        ds.zone_radius_at_contact(bad)


def test_beyond_contact_is_refused():
    with pytest.raises(ValueError, match="zone_radius_at_contact"):
        ds.separated_branch(1.01 * ds.zone_radius_at_contact(1.0), 1.0)

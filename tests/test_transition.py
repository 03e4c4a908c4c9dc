"""mu (Eq. 35) <-> Maugis lambda, from the two definitions."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.core.transition import MAUGIS_PER_TABOR, maugis_parameter, tabor_from_maugis

#: both sides are closed forms in double precision
TOL_EXACT = 1e-14


def test_constant_from_the_definitions(rng):
    r, e, dg, s0 = rng.uniform(1e-7, 1e-3, 5), rng.uniform(1e6, 1e11, 5), rng.uniform(1e-3, 1, 5), \
        rng.uniform(1e6, 1e10, 5)
    mu = s0 * np.cbrt(r / (e * e * dg))  # Eq. (35)
    k = 4 * e / 3
    lam = 2 * s0 * np.cbrt(r / (np.pi * dg * k * k))  # Maugis (1992)
    assert_allclose(maugis_parameter(mu), lam, rtol=TOL_EXACT)
    assert_allclose(MAUGIS_PER_TABOR, 1.1272516517868, rtol=1e-12)  # notes: ~1.1272
    assert_allclose(tabor_from_maugis(maugis_parameter(mu)), mu, rtol=TOL_EXACT)


def test_scalar_in_scalar_out():
    assert np.ndim(maugis_parameter(1.0)) == 0


@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, np.inf])
def test_bad_input(bad):
    with pytest.raises(ValueError, match="mu"):
        maugis_parameter(bad)
    with pytest.raises(ValueError, match="lam"):
        tabor_from_maugis(bad)


def test_unchecked_core_is_the_checked_value():
    """checked=False (internal callers, mu validated once) skips the check, not a digit."""
    mu = np.array([1e-6, 0.3, 1.0, 7.0, 1e12])
    assert np.array_equal(maugis_parameter(mu, checked=False), maugis_parameter(mu))
    assert np.ndim(maugis_parameter(1.0, checked=False)) == 0

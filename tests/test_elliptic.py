"""Carlson forms of Eqs. (B1)-(B3) against the printed Legendre forms and quadrature."""
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipk

from dhfield.core.elliptic import complete_k, ellipsoid_integrals, ellipsoid_integrals_legendre

#: Legendre forms lose ~k^-2 digits to cancellation; 1e-12 is ample for k^2 >= 0.02.
LEGENDRE_RTOL = 1e-12
#: quad with epsrel=1e-13 on a smooth algebraic integrand.
QUAD_RTOL = 1e-11


@pytest.mark.parametrize("beta", [0.3, 0.8, 0.99])
@pytest.mark.parametrize("l", [0.0, 0.01, 1.0, 30.0])
def test_carlson_matches_printed_legendre_forms(beta, l):
    a = 1.7
    got = ellipsoid_integrals(l, a, beta * a)
    ref = ellipsoid_integrals_legendre(l, a, beta * a)
    np.testing.assert_allclose(got, ref, rtol=LEGENDRE_RTOL)


@pytest.mark.parametrize("beta", [0.3, 0.8, 1.0])
def test_integrals_against_quadrature(beta):
    a, l = 1.3, 0.4
    b = beta * a
    refs = [
        quad(lambda w: 1 / np.sqrt((a**2 + w) * (b**2 + w) * w), l, np.inf, epsrel=1e-13, epsabs=0)[0],
        quad(lambda w: 1 / np.sqrt((a**2 + w) ** 3 * (b**2 + w) * w), l, np.inf, epsrel=1e-13, epsabs=0)[0],
        quad(lambda w: 1 / np.sqrt((a**2 + w) * (b**2 + w) ** 3 * w), l, np.inf, epsrel=1e-13, epsabs=0)[0],
    ]
    np.testing.assert_allclose(ellipsoid_integrals(l, a, b), refs, rtol=QUAD_RTOL)


def test_circle_closed_forms():
    # Circle a = b: I1(l) = 2 asin(a/sqrt(a^2+l))/a (elementary integral).
    a, l = 2.0, 3.0
    i1, i2, i3 = ellipsoid_integrals(l, a, a)
    assert i1 == pytest.approx(2 * np.arcsin(a / np.sqrt(a**2 + l)) / a, rel=1e-14)
    assert i2 == pytest.approx(i3, rel=1e-14)


def test_complete_integrals_match_scipy_parameter_convention():
    beta = np.array([0.2, 0.7, 0.95])
    np.testing.assert_allclose(complete_k(beta), ellipk(1 - beta**2), rtol=1e-14)
    assert complete_k(1.0) == pytest.approx(np.pi / 2, rel=1e-15)

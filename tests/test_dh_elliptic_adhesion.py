"""Work of adhesion along a ray, Eq. (31)."""
import numpy as np
import pytest
from scipy.integrate import quad

from dhfield.models import hertz
from dhfield.models.dh_elliptic_adhesion import graded_rule, work_of_adhesion

#: The issue's bound for Eq. (31); the graded Gauss rule reaches ~1e-14.
DGAMMA_RTOL = 1e-10


def _gj98(a, c, v):
    """Greenwood & Johnson (1998) closed form, R = E* = 1 (notes Sec. 5)."""
    return v * (1 + v) * 2 / (3 * np.pi) * (c - a) ** 2 * (c + 2 * a)


@pytest.mark.parametrize("a, c, v", [(1.0, 1.5, 0.7), (0.01, 3.0, 0.2), (2.0, 2.001, 30.0),
                                     (1e-3, 10.0, 0.01), (1.5, 1.6, 5.0)])
def test_circle_equals_gj98_closed_form(a, c, v):
    assert work_of_adhesion(a, c, 1.0, v) == pytest.approx(_gj98(a, c, v), rel=DGAMMA_RTOL)


def test_circle_is_independent_of_theta():
    th = np.linspace(0, np.pi / 2, 7)
    np.testing.assert_allclose(work_of_adhesion(0.8, 1.9, 1.0, 0.5, th), _gj98(0.8, 1.9, 0.5), rtol=DGAMMA_RTOL)


def _ray_quadrature(a, c, beta, v, th):
    """Adaptive quadrature of int sigma dh/dr dr along the ray, gradient of Eq. (13)."""
    b, d = beta * a, beta * c
    po, pc = hertz.max_pressure(a, beta), hertz.max_pressure(c, beta)
    ct, st = np.cos(th), np.sin(th)
    rab = a * b / np.hypot(b * ct, a * st)
    rcd = c * d / np.hypot(d * ct, c * st)
    r1, r2 = hertz.principal_radii_from_ellipticity(beta)

    def f(r):
        x, y = r * ct, r * st
        gx, gy = hertz.surface_displacement_gradient(x, y, a, b, po)
        dh = (1 + v) * (ct * (x / r1 + gx) + st * (y / r2 + gy))
        return v * pc * np.sqrt(max(0.0, 1 - (x / c) ** 2 - (y / d) ** 2)) * dh

    return quad(f, rab, rcd, epsabs=0, epsrel=1e-12, limit=500)[0]


@pytest.mark.parametrize("beta", [0.3, 0.8, 0.99])
@pytest.mark.parametrize("a, c, th", [(1.0, 1.5, 0.0), (0.05, 3.0, 0.0), (1.0, 1.5, 0.7),
                                      (0.05, 3.0, 1.2), (1.0, 1.2, np.pi / 2)])
def test_ellipse_matches_adaptive_quadrature(beta, a, c, th):
    assert work_of_adhesion(a, c, beta, 0.6, th) == pytest.approx(_ray_quadrature(a, c, beta, 0.6, th),
                                                                  rel=DGAMMA_RTOL)


def test_symmetry_in_theta():
    th = 0.4
    vals = work_of_adhesion(1.0, 1.4, 0.7, 0.3, [th, -th, np.pi - th, np.pi + th])
    np.testing.assert_allclose(vals, vals[0], rtol=1e-13)


def test_scaling_in_v():
    # sigma is proportional to v and dh/dr to (1 + v).
    w1 = work_of_adhesion(1.0, 1.4, 0.7, 1.0)
    w3 = work_of_adhesion(1.0, 1.4, 0.7, 3.0)
    assert w3 / w1 == pytest.approx(3 * 4 / 2, rel=1e-13)


def test_graded_rule_integrates_near_singular_function():
    # int_0^{pi/2} eps/(eps^2 + t^2) dt = atan(pi/(2 eps)); pole at t = i eps.
    eps = 1e-4
    t, w = graded_rule(np.array(eps))
    assert np.sum(w * eps / (eps**2 + t**2)) == pytest.approx(np.arctan(np.pi / (2 * eps)), rel=1e-11)


def test_bad_input():
    with pytest.raises(ValueError, match="adhesive_semi_major"):
        work_of_adhesion(1.0, 0.5, 0.8, 1.0)
    with pytest.raises(ValueError, match="theta"):
        work_of_adhesion(1.0, 1.5, 0.8, 1.0, np.nan)


def test_issue11_ragged_rule_is_graded_rule_per_element():
    from dhfield.models.dh_elliptic_adhesion import graded_rule, ragged_graded_rule

    t1 = np.array([1e-30, 1e-7, 0.01, 0.3, 1.2, np.pi / 2])
    t, w, first, owner = ragged_graded_rule(t1)
    assert np.array_equal(first, np.flatnonzero(np.r_[True, np.diff(owner) != 0]))
    for i, t1_i in enumerate(t1):
        ti, wi = graded_rule(np.array([t1_i]))
        np.testing.assert_allclose(t[owner == i].ravel(), ti.ravel(), rtol=1e-15, atol=0)
        np.testing.assert_allclose(w[owner == i].ravel(), wi.ravel(), rtol=1e-14, atol=0)

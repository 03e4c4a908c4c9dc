"""Elliptical Hertz contact, Eqs. (7)-(15)."""
import numpy as np
import pytest
from scipy.integrate import dblquad, quad
from scipy.special import ellipe, ellipk

from dhfield.models import hertz

#: Eqs. (13)-(15) vs adaptive quadrature of Eq. (12b): both near machine precision;
#: 1e-10 is the issue's bound, with three orders of margin observed.
QUAD_RTOL = 1e-10
#: Printed Legendre forms vs Carlson forms: cancellation costs ~1/k^2 digits at beta = 0.99.
LEGENDRE_RTOL = 1e-12


def _eq12_quadrature(x, y, a, b, p0):
    """Direct adaptive quadrature of Eq. (12) (E* = 1), the test oracle."""
    l = hertz.ellipse_root(x, y, a, b)

    def f(w):
        return (1 - x**2 / (a**2 + w) - y**2 / (b**2 + w)) / np.sqrt((a**2 + w) * (b**2 + w) * w)

    # split at l + a^2 so quad sees the w^-1/2 end point singularity on a finite panel
    i1 = quad(f, l, l + a**2, epsabs=0, epsrel=1e-13, limit=200)[0]
    i2 = quad(f, l + a**2, np.inf, epsabs=0, epsrel=1e-13, limit=200)[0]
    return p0 * a * b / 2 * (i1 + i2)


@pytest.mark.parametrize("beta", [0.3, 0.8, 0.99, 1.0])
def test_outside_displacement_matches_quadrature(beta, rng):
    a = 1.0
    b = beta * a
    p0 = hertz.max_pressure(a, beta)
    r = a * rng.uniform(1.0001, 4.0, 40)
    th = rng.uniform(0, 2 * np.pi, 40)
    # radial scaling of the ellipse boundary keeps every point outside
    x = r * np.cos(th)
    y = r * np.sin(th) * beta
    got = hertz.surface_displacement(x, y, a, b, p0)
    ref = np.array([_eq12_quadrature(xi, yi, a, b, p0) for xi, yi in zip(x, y)])
    np.testing.assert_allclose(got, ref, rtol=QUAD_RTOL)


@pytest.mark.parametrize("beta", [0.3, 0.8, 0.99])
def test_max_pressure_and_f1_match_printed_eqs_8_11(beta):
    m = 1 - beta**2
    k, e = ellipk(m), ellipe(m)
    s = np.sqrt((e / beta**2 - k) * (k - e))
    a, r, es = 2.0, 3.0, 5.0
    assert hertz.max_pressure(a, beta, r, es) == pytest.approx(es / (2 * r) * m * a / (beta * s),
                                                               rel=LEGENDRE_RTOL)  # Eq. (8)
    assert hertz.load_factor(beta) ** 3 == pytest.approx(4 / (np.pi * m) * beta**1.5 * s,
                                                         rel=LEGENDRE_RTOL)  # Eq. (11)


def test_circle_limits_are_exact():
    a, r, e = 1.5, 2.0, 3.0
    assert hertz.max_pressure(a, 1.0, r, e) == pytest.approx(2 * e * a / (np.pi * r), rel=1e-15)
    assert hertz.load_factor(1.0) == pytest.approx(1.0, rel=1e-15)
    assert hertz.load(a, 1.0, r, e) == pytest.approx(4 * e * a**3 / (3 * r), rel=1e-15)
    assert hertz.approach(a, 1.0, r, e) == pytest.approx(a**2 / r, rel=1e-15)
    # continuity: no 0/0 next to the circle
    assert hertz.max_pressure(a, 1 - 1e-12, r, e) == pytest.approx(2 * e * a / (np.pi * r), rel=1e-10)


def test_circle_outside_displacement_closed_form():
    # Johnson (1985) Eq. 3.42b, both bodies with E*: omega = p0/(2aE*) [(2a^2 - r^2) asin(a/r) + a sqrt(r^2 - a^2)]
    a, p0 = 1.0, 0.7
    r = np.linspace(1.0, 5.0, 50)
    ref = p0 / (2 * a) * ((2 * a**2 - r**2) * np.arcsin(a / r) + a * np.sqrt(r**2 - a**2))
    np.testing.assert_allclose(hertz.surface_displacement(r, 0 * r, a, a, p0), ref, rtol=1e-13)


@pytest.mark.parametrize("beta", [0.5, 0.9, 1.0])
def test_load_is_integral_of_pressure(beta):
    # Eq. (10) vs the integral of Eq. (7) over the ellipse (independent 2-D quadrature).
    a, r, e = 1.2, 1.0, 1.0
    b = beta * a
    p0 = hertz.max_pressure(a, beta, r, e)
    val = dblquad(lambda y, x: hertz.pressure(x, y, a, b, p0), -a, a,
                  lambda x: -b * np.sqrt(max(0, 1 - (x / a) ** 2)),
                  lambda x: b * np.sqrt(max(0, 1 - (x / a) ** 2)), epsabs=1e-12, epsrel=1e-10)[0]
    assert hertz.load(a, beta, r, e) == pytest.approx(val, rel=1e-8)


@pytest.mark.parametrize("beta", [0.3, 0.8, 1.0])
def test_contact_condition_inside(beta, rng):
    # Inside the ellipse omega = delta - z: the gap vanishes (Eqs. 2, 13a, 14).
    a = 1.3
    t = rng.uniform(0, 2 * np.pi, 50)
    s = np.sqrt(rng.uniform(0, 1, 50))
    x, y = a * s * np.cos(t), beta * a * s * np.sin(t)
    np.testing.assert_allclose(hertz.gap(x, y, a, beta), 0.0, atol=1e-14)


def test_gap_positive_outside_and_continuous_at_edge():
    a, beta = 1.0, 0.7
    x = np.linspace(1.0, 3.0, 200)
    h = hertz.gap(x, 0 * x, a, beta)
    assert abs(h[0]) < 1e-14
    assert np.all(h[1:] > 0)
    # square-root start of the slope: h ~ (x - a)^{3/2}
    h1, h2 = hertz.gap([1.0 + 1e-6, 1.0 + 4e-6], [0, 0], a, beta)
    assert h2 / h1 == pytest.approx(8.0, rel=1e-3)


def test_gradient_matches_finite_differences(rng):
    a, b, p0 = 1.0, 0.6, 0.8
    x, y, eps = 1.4, 0.5, 1e-6
    gx, gy = hertz.surface_displacement_gradient(x, y, a, b, p0)
    f = lambda xx, yy: hertz.surface_displacement(xx, yy, a, b, p0)
    assert gx == pytest.approx((f(x + eps, y) - f(x - eps, y)) / (2 * eps), rel=1e-8)
    assert gy == pytest.approx((f(x, y + eps) - f(x, y - eps)) / (2 * eps), rel=1e-8)


def test_ellipse_root_solves_its_equation(rng):
    a, b = 2.0, 0.5
    x, y = rng.uniform(-10, 10, 500), rng.uniform(-10, 10, 500)
    l = hertz.ellipse_root(x, y, a, b)
    outside = (x / a) ** 2 + (y / b) ** 2 > 1
    np.testing.assert_allclose((x**2 / (a**2 + l) + y**2 / (b**2 + l))[outside], 1.0, rtol=1e-13)
    assert np.all(l[~outside] == 0)


@pytest.mark.parametrize("call, name", [
    (lambda: hertz.max_pressure(-1.0, 0.5), "semi_major"),
    (lambda: hertz.max_pressure(1.0, 1.5), "beta"),
    (lambda: hertz.load(1.0, 0.5, effective_radius=0.0), "effective_radius"),
    (lambda: hertz.gap(np.nan, 0.0, 1.0, 0.5), "x"),
])
def test_bad_input(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_max_pressure_unchecked_core_is_the_checked_value():
    """checked=False (the closure solves, inputs validated once) skips the checks, not a digit."""
    a, beta = np.geomspace(1e-3, 10.0, 7), np.linspace(0.1, 1.0, 7)
    assert np.array_equal(hertz.max_pressure(a, beta, 2.0, 3.0, checked=False), hertz.max_pressure(a, beta, 2.0, 3.0))
    with pytest.raises(ValueError, match="reduced_modulus"):
        hertz.max_pressure(1.0, 0.5, 1.0, -1.0)

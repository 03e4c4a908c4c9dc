"""Extended double-Hertz fields, Eqs. (16)-(27)."""
import numpy as np
import pytest
from scipy.integrate import quad

from dhfield.models import dh_elliptic_fields as dh
from dhfield.models import hertz

STATE = dict(semi_major=1.1, adhesive_semi_major=1.6, beta=0.8, scaling=0.9)
#: All identities below are exact algebra on Carlson-form fields: rounding level.
IDENTITY_ATOL = 1e-13


def _ring(rng, inner, outer, beta, n=200):
    t = rng.uniform(0, 2 * np.pi, n)
    s = rng.uniform(inner, outer, n)
    return s * np.cos(t), beta * s * np.sin(t)


def test_contact_condition_inside_contact(rng):
    x, y = _ring(rng, 0.0, 1.1, 0.8)
    np.testing.assert_allclose(dh.gap(x, y, **STATE), 0.0, atol=IDENTITY_ATOL)


def test_annulus_identity_every_theta(rng):
    # In the adhesive annulus h = (1 + v) h_Hertz (module docstring; notes Sec. 3).
    x, y = _ring(rng, 1.1 * (1 + 1e-9), 1.6, 0.8)
    h = dh.gap(x, y, **STATE)
    h_h = hertz.gap(x, y, 1.1, 0.8)
    np.testing.assert_allclose(h, (1 + 0.9) * h_h, rtol=1e-11, atol=IDENTITY_ATOL)


def test_edge_stress_is_sigma0_all_round():
    t = np.linspace(0, np.pi / 2, 30)
    a, b = 1.1, 0.88
    x, y = a * np.cos(t) * (1 + 1e-14), b * np.sin(t) * (1 + 1e-14)
    s = dh.adhesive_stress(x, y, **STATE)
    np.testing.assert_allclose(s, dh.max_adhesive_stress(**STATE), rtol=1e-10)


def test_pressure_pieces_eqs_16_22():
    a, c, beta, v = 1.1, 1.6, 0.8, 0.9
    po_ab, po_cd = hertz.max_pressure(a, beta), hertz.max_pressure(c, beta)
    x = np.array([0.0, 1.3, 2.0])
    p = dh.pressure(x, 0 * x, **STATE)
    assert p[0] == pytest.approx((1 + v) * po_ab - v * po_cd, rel=1e-14)
    assert p[1] == pytest.approx(-v * po_cd * np.sqrt(1 - (1.3 / c) ** 2), rel=1e-14)  # Eq. (22b)
    assert p[2] == 0.0


def test_load_is_integral_of_pressure():
    # Eq. (25) vs quadrature of Eqs. (16)/(22).  With equal beta both ellipses are similar,
    # so in the scaled coordinates x = c s cos(phi), y = d s sin(phi) the pressure depends
    # on s only and W = 2 pi c d int_0^1 p(s) s ds (split at the contact edge s = a/c).
    a, c, beta = 1.1, 1.6, 0.8
    d = beta * c
    f = lambda s: float(dh.pressure(c * s, 0.0, **STATE)) * s
    val = 2 * np.pi * c * d * (quad(f, 0, a / c, epsabs=0, epsrel=1e-13)[0]
                               + quad(f, a / c, 1, epsabs=0, epsrel=1e-13)[0])
    assert dh.load(**STATE) == pytest.approx(val, rel=1e-11)


def test_circle_reduces_to_greenwood_johnson():
    # GJ98 (notes Sec. 5): W = 4E*/(3R)[a^3 - v(c^3 - a^3)], delta = [a^2 - v(c^2 - a^2)]/R,
    # sigma0 = (2E* v/(pi R)) sqrt(c^2 - a^2).
    a, c, v = 0.9, 1.7, 0.6
    assert dh.load(a, c, 1.0, v) == pytest.approx(4 / 3 * (a**3 - v * (c**3 - a**3)), rel=1e-14)
    assert dh.approach(a, c, 1.0, v) == pytest.approx(a**2 - v * (c**2 - a**2), rel=1e-14)
    assert dh.max_adhesive_stress(a, c, 1.0, v) == pytest.approx(2 * v / np.pi * np.sqrt(c**2 - a**2), rel=1e-14)


def test_v_zero_is_hertz(rng):
    x, y = _ring(rng, 0, 3, 0.7)
    np.testing.assert_allclose(dh.gap(x, y, 1.0, 2.0, 0.7, 0.0), hertz.gap(x, y, 1.0, 0.7), atol=1e-15)


def test_dimensional_scaling():
    # Lengths x L, E* x S: pressure scales S, displacement L (R scaled by L).
    L, S = 1e-6, 2e9
    base = dh.surface_displacement(1.3, 0.4, 1.1, 1.6, 0.8, 0.9)
    scaled = dh.surface_displacement(1.3 * L, 0.4 * L, 1.1 * L, 1.6 * L, 0.8, 0.9, effective_radius=L,
                                     reduced_modulus=S)
    assert scaled == pytest.approx(base * L, rel=1e-13)


@pytest.mark.parametrize("kw, name", [
    (dict(adhesive_semi_major=1.0), "adhesive_semi_major"),
    (dict(beta=0.0), "beta"),
    (dict(scaling=-1.0), "scaling"),
    (dict(semi_major=np.inf), "semi_major"),
])
def test_bad_input(kw, name):
    with pytest.raises(ValueError, match=name):
        dh.load(**{**STATE, **kw})

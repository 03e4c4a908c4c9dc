"""Crossed-cylinder geometry (Eqs. 2-6) and the Hertz ellipticity relation."""
import numpy as np
import pytest
from scipy.special import ellipe, ellipk

from dhfield.core import geometry as g


def test_principal_radii_eqs_3_4():
    r1, r2 = g.principal_radii(2.0, np.pi / 3)  # cos = 1/2
    assert r1 == pytest.approx(4.0, rel=1e-15)  # Eq. (3): 2/(1 - 1/2)
    assert r2 == pytest.approx(4.0 / 3.0, rel=1e-15)  # Eq. (4): 2/(1 + 1/2)
    assert g.effective_radius(r1, r2) == pytest.approx(np.sqrt(16 / 3), rel=1e-15)


def test_perpendicular_cylinders_are_a_sphere_of_radius_rc():
    r1, r2 = g.principal_radii(3.0, np.pi / 2)
    assert r1 == pytest.approx(3.0) and r2 == pytest.approx(3.0)
    assert g.ellipticity_from_skew_angle(np.pi / 2) == pytest.approx(1.0, abs=1e-15)


def test_reduced_modulus_eq_6():
    # Two identical steels E = 210 GPa, nu = 0.3: E* = E/(2(1 - nu^2)).
    assert g.reduced_modulus(210e9, 0.3, 210e9, 0.3) == pytest.approx(210e9 / (2 * 0.91), rel=1e-14)


@pytest.mark.parametrize("beta", [0.1, 0.3, 0.8, 0.99])
def test_radius_ratio_matches_legendre_form(beta):
    m = 1 - beta**2
    k, e = ellipk(m), ellipe(m)
    assert g.radius_ratio(beta) == pytest.approx((e / beta**2 - k) / (k - e), rel=1e-11)


def test_radius_ratio_is_one_at_circle_and_continuous():
    assert g.radius_ratio(1.0) == 1.0
    # Series of the Legendre ratio: K ~ pi/2 (1 + m/4), E ~ pi/2 (1 - m/4), 1/beta^2 ~ 1 + m
    # give rho - 1 ~ (3/4) m = (3/2) eps with m = 1 - beta^2 ~ 2 eps, beta = 1 - eps.
    eps = 1e-7
    assert (g.radius_ratio(1 - eps) - 1) / eps == pytest.approx(1.5, rel=1e-5)


def test_inverse_round_trip():
    beta = np.array([0.05, 0.3, 0.8, 0.9, 0.99, 0.999999, 1.0])
    np.testing.assert_allclose(g.ellipticity_from_radius_ratio(g.radius_ratio(beta)), beta, rtol=1e-13)
    np.testing.assert_allclose(g.ellipticity_from_skew_angle(g.skew_angle(beta)), beta, rtol=1e-9)


def test_sin_skew_consistent_with_principal_radii():
    theta = 1.1
    r1, r2 = g.principal_radii(1.0, theta)
    beta = g.ellipticity_from_radius_ratio(r1 / r2)
    assert g.sin_skew_angle(beta) == pytest.approx(np.sin(theta), rel=1e-12)
    assert g.skew_angle(beta) == pytest.approx(theta, rel=1e-12)


@pytest.mark.parametrize("call, name", [
    (lambda: g.radius_ratio(1.2), "beta"),
    (lambda: g.radius_ratio(0.0), "beta"),
    (lambda: g.radius_ratio(np.nan), "beta"),
    (lambda: g.principal_radii(-1.0, 1.0), "cylinder_radius"),
    (lambda: g.principal_radii(1.0, 2.0), "skew_angle"),
    (lambda: g.reduced_modulus(1e9, 0.7, 1e9, 0.3), "nu1"),
    (lambda: g.reduced_modulus(-1e9, 0.3, 1e9, 0.3), "e1"),
    (lambda: g.effective_radius(1.0, 0.0), "r_minor"),
    (lambda: g.skew_angle(1.5), "beta"),
    (lambda: g.ellipticity_from_radius_ratio(0.5), "ratio"),
])
def test_bad_input_names_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_issue9_principal_radii_at_tiny_angles_are_finite():
    # Before: skew_angle = 1e-12 gave R' = inf (1 - cos lost to rounding), reported as r_major.
    # 1 - cos(t) = 2 sin^2(t/2) ~ t^2/2: R' = 2 R_c/t^2.
    from dhfield.core import geometry as g

    r1, r2 = g.principal_radii(1.0, 1e-12)
    assert float(r1) == pytest.approx(2e24, rel=1e-12) and float(r2) == pytest.approx(0.5, rel=1e-12)


def test_unchecked_path_is_the_same_computation():
    # checked=False (inputs validated once at a public entry, issue 16) skips only the check:
    # the values are bit-identical to the checked path, and the checked path still refuses.
    beta = np.array([0.05, 0.3, 0.8, 0.999, 1.0])
    assert np.array_equal(g.radius_ratio(beta, checked=False), g.radius_ratio(beta))
    assert np.array_equal(g.sin_skew_angle(beta, checked=False), g.sin_skew_angle(beta))
    rho = g.radius_ratio(beta)
    assert np.array_equal(g.ellipticity_from_radius_ratio(rho, checked=False), g.ellipticity_from_radius_ratio(rho))
    with pytest.raises(ValueError, match="ratio"):
        g.ellipticity_from_radius_ratio(0.5)


def test_unchecked_cores_are_the_checked_values():
    """checked=False (dhfield.analysis.dimensional validates the SI inputs once) skips the checks, not a digit."""
    rc, th = np.array([1e-3, 0.02, 5.0]), np.array([0.1, 1.0, np.pi / 2])
    unchecked, checked = g.principal_radii(rc, th, checked=False), g.principal_radii(rc, th)
    assert all(np.array_equal(u, c) for u, c in zip(unchecked, checked))
    assert np.array_equal(g.effective_radius(rc, th, checked=False), g.effective_radius(rc, th))
    assert np.array_equal(g.reduced_modulus(rc, 0.3, th, 0.5, checked=False), g.reduced_modulus(rc, 0.3, th, 0.5))
    beta = np.array([1e-4, 0.3, 1.0])
    assert np.array_equal(g.skew_angle(beta, checked=False), g.skew_angle(beta))

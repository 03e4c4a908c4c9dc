"""Circular double-Hertz (Greenwood & Johnson 1998): closed form, limits, elliptical core at beta0 = 1."""
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import integrate

from dhfield.models import dh_circular, jkr

#: the closed-form parametrisation is exact; residuals of Eqs. (24), (31) are rounding
#: (amplified ~1e4 by the cancellation in (c - a) at large mu)
TOL_EXACT = 1e-11
#: adaptive quadrature of the work-of-adhesion integral (quad epsrel 1e-12)
TOL_QUAD = 1e-10
#: issue 3: circular DH vs the elliptical DH core at beta0 = 1 on whole load curves
TOL_CORE = 1e-9
#: JKR limit at mu = 1000: the DH pull-off approaches -3/4 as O(mu^-2) (measured 1.0e-5 at
#: mu = 100, 1.0e-7 at mu = 1000)
TOL_JKR_LIMIT = 1e-6

R, E, DG = 1e-6, 1e9, 0.05


def _hertz_gap_slope(r, a):
    """dh/dr of the Hertz gap outside a circle of radius a (R = E* = 1)."""
    return 2.0 / np.pi * (r * np.arccos(a / r) + a * np.sqrt(r * r - a * a) / r)


def test_work_of_adhesion_closed_form_vs_quadrature(rng):
    for _ in range(5):
        a = rng.uniform(0.0, 3.0)
        c = a + rng.uniform(0.01, 2.0)
        v = rng.uniform(0.01, 5.0)

        def integrand(r):  # sigma(r) * d[(1+v) h_H]/dr, Eq. (31) at beta = 1
            return v * 2.0 / np.pi * np.sqrt(c * c - r * r) * (1 + v) * _hertz_gap_slope(r, a)

        ref = integrate.quad(integrand, a, c, epsabs=0, epsrel=1e-12, limit=200)[0]
        assert_allclose(dh_circular.work_of_adhesion(a, c, v, 1.0, 1.0), ref, rtol=TOL_QUAD)


@pytest.mark.parametrize("mu", [0.05, 0.5, 1.0, 5.0, 50.0])
def test_curve_satisfies_eqs_24_31(mu):
    a = np.concatenate([[0.0], np.geomspace(1e-3, 5.0, 40)])
    st = dh_circular.load_curve_nondimensional(a, mu)
    c, v = st["c_star"], st["v"]
    assert_allclose(2 * v / np.pi * np.sqrt(c * c - a * a), mu, rtol=TOL_EXACT)  # Eq. (24)
    assert_allclose(dh_circular.work_of_adhesion(a, c, v, 1.0, 1.0), 1.0, rtol=TOL_EXACT)  # Eq. (31)
    # absolute: v (c^3 - a^3) cancels near W* = 0 and the solve returns a to ~1e-15 relative
    assert_allclose(st["W_star"], 2 / (3 * np.pi) * (a**3 - v * (c**3 - a**3)), rtol=TOL_EXACT, atol=1e-10)
    v0 = dh_circular._v_zero_contact(mu)
    assert_allclose(st["W_star"][0], -1.0 / (1.0 + v0), rtol=TOL_EXACT)  # -2/(1+v) pi R dgamma at a = 0


def test_jkr_and_dmt_limits():
    assert abs(dh_circular.pull_off_nondimensional(1.0, 1000.0)["W_star"] + 0.75) < TOL_JKR_LIMIT
    po = dh_circular.pull_off_nondimensional(1.0, 1e-3)
    assert abs(po["W_star"] + 1.0) < 1e-3  # DMT side: -1/(1+v), v = O(mu^1.5)
    # the curve approaches JKR at large mu
    a = np.linspace(0.5, 3.0, 6)
    assert_allclose(dh_circular.load_curve_nondimensional(a, 1000.0)["W_star"], jkr.load_curve_nondimensional(a)["W_star"], atol=5e-3)


@pytest.mark.parametrize("mu", [0.3, 1.0, 5.0])
def test_agrees_with_elliptical_core_at_circle(mu):
    model = pytest.importorskip("dhfield.models.dh_elliptic")
    a = np.linspace(*model.DEFAULT_A_STAR, 200)
    ref = model.load_curve(mu=mu, beta0=1.0, a_star=a)
    st = dh_circular.load_curve_nondimensional(a, mu)
    for key in ("W_star", "c_star", "v", "delta_star"):
        assert_allclose(st[key], getattr(ref, key), rtol=TOL_CORE, atol=TOL_CORE, err_msg=key)
    for control in ("load", "displacement"):
        po, pref = dh_circular.pull_off_nondimensional(1.0, mu, control=control), model.pull_off(mu=mu, beta0=1.0, control=control)
        assert_allclose([po["W_star"], po["a_star"], po["delta_star"]],
                        [pref.W_star, pref.a_star, pref.delta_star], atol=TOL_CORE)


def test_pull_off_is_first_minimum_on_unloading():
    mu = 1.0
    po = dh_circular.pull_off_nondimensional(1.0, mu)
    a = np.linspace(po["a_star"], 4.0, 2000)
    w = dh_circular.load_curve_nondimensional(a, mu)["W_star"]
    assert np.all(np.diff(w) > 0)  # the load rises monotonically above the pull-off point


def test_dimensional_wrapper():
    sigma0 = 2e8
    mu = sigma0 * np.cbrt(R / (E * E * DG))
    po = dh_circular.pull_off(R, E, DG, sigma0)
    assert_allclose(po.force, dh_circular.pull_off_nondimensional(1.0, mu)["W_star"] * 2 * np.pi * R * DG, rtol=1e-12)
    cr = np.cbrt(R * R * DG / E)
    c = dh_circular.load_curve(np.array([0.5, 1.0]) * cr, R, E, DG, sigma0)
    assert_allclose(c.force,
                    dh_circular.load_curve_nondimensional(np.array([0.5, 1.0]), mu)["W_star"] * 2 * np.pi * R * DG,
                    rtol=1e-12)


def test_bad_input():
    with pytest.raises(ValueError, match="max_adhesive_stress"):
        dh_circular.pull_off(R, E, DG, -1.0)
    with pytest.raises(ValueError, match="contact_radius"):
        dh_circular.load_curve(np.nan, R, E, DG, 1e8)
    with pytest.raises(ValueError, match="reduced_modulus"):
        dh_circular.load_curve(1e-8, R, 0.0, DG, 1e8)
    with pytest.raises(ValueError, match="control"):
        dh_circular.pull_off(R, E, DG, 1e8, control="grips")
    with pytest.raises(ValueError, match="adhesive_radius"):
        dh_circular.work_of_adhesion(2.0, 1.0, 1.0, 1.0, 1.0)


@pytest.mark.parametrize("mu", [1e6, 1e9, 1e12])
def test_issue9_large_mu_is_jkr_without_cancellation(mu):
    # Before: dh-circular at mu = 1e8 gave -1.50 and at 1e12 ~0 (c^3 - a^3 lost to rounding).
    # JKR: load control -3/4, fixed grips -5/12 (Maugis 2000); the departure is O(mu^-2).
    from dhfield.models import dh_circular as dc

    assert float(dc.pull_off_nondimensional(1.0, np.array(mu))["W_star"]) == pytest.approx(-0.75, rel=1e-11)
    assert float(dc.pull_off_nondimensional(1.0, np.array(mu), control="displacement")["W_star"]) == pytest.approx(-5 / 12, rel=1e-11)

"""Approximate elliptical JKR (Johnson & Greenwood 2005): integrals, contact condition,
Griffith conditions, the JKR and Hertz limits, mild ellipticity, bad input."""
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import integrate

from dhfield.models import hertz, jkr, jkr_elliptic as je
from dhfield.core.geometry import radius_ratio, sin_skew_angle
from verification._oracles import boussinesq_displacement

#: adaptive quadrature of the ellipsoidal-potential integrals (quad epsrel 1e-12)
TOL_QUAD = 1e-10
#: Boussinesq quadrature of the pressure (40 x 256 nodes after the edge substitution)
TOL_BOUSSINESQ = 1e-8
#: issue 3: circular JKR at beta0 = 1 on the load curve
TOL_CIRCLE = 1e-10
#: Hertz limit of the coefficients: the 2x2 solve in double precision
TOL_HERTZ = 1e-13
#: issue 3 target for |beta - beta0| at W* = 100; reached only for beta0 >~ 0.98 (see below)
TOL_HERTZ_BETA = 1e-3
#: consistency with the pull-off ratios quoted in the physics notes (their own reconstruction)
TOL_NOTES = 1e-3


def test_integrals_against_quadrature():
    for beta in (1.0, 0.999, 0.9, 0.75, 0.5, 0.2):
        b2 = beta * beta
        j0, j1, j2, j12 = je._integrals(beta, 1 - b2)

        def q(f):
            # s = t^2 removes the 1/sqrt(s) end point
            return integrate.quad(lambda t: 2 * f(t * t) / np.sqrt((1 + t * t) * (b2 + t * t)), 0, np.inf,
                                  epsabs=0, epsrel=1e-12, limit=200)[0]

        ref = [q(lambda s: 1.0), q(lambda s: 1 / (1 + s)), q(lambda s: 1 / (b2 + s)),
               q(lambda s: 1 / ((1 + s) * (b2 + s)))]
        assert_allclose([j0, j1, j2, j12], ref, rtol=TOL_QUAD, err_msg=f"beta={beta}")


def test_series_and_divided_difference_agree_at_switch():
    k2 = np.array([0.2499, 0.25, 0.2501])
    beta = np.sqrt(1 - k2)
    _, j1, j2, j12 = je._integrals(beta, k2)
    assert_allclose(j12, (j2 - j1) / k2, rtol=1e-13)


@pytest.mark.parametrize("beta0", [0.3, 0.8, 0.9, 0.99])
def test_hertz_limit_of_coefficients(beta0):
    rho_m1 = je._radius_ratio_m1(beta0)
    assert_allclose(1 + rho_m1, radius_ratio(beta0), rtol=1e-14)
    g1, g2, dg, *_ = je.shape_coefficients(beta0, 1 - beta0**2, rho_m1)
    kappa = hertz.max_pressure(1.0, beta0)  # Po/a of Eq. (8)
    assert_allclose([g1, g2], [-kappa, -kappa], rtol=TOL_HERTZ)
    assert abs(dg) < 1e-14


@pytest.mark.parametrize("beta0,u", [(0.8, 0.3), (0.6, 0.7), (0.95, 0.5)])
def test_contact_condition_and_griffith(beta0, u):
    """Independent check of the model: the pressure makes omega = delta - A x^2 - B y^2
    inside the ellipse (Boussinesq quadrature), and K_I = sqrt(2) at both axis ends."""
    _, rho_m1, sn = je.geometry_terms(beta0)
    st = je._state_u(u, beta0, rho_m1, sn)
    a, b, alpha = st["a_star"], st["b_star"], st["alpha"]
    r1 = np.sqrt(1 + rho_m1)
    for x0, y0 in [(0.0, 0.0), (0.3 * a, 0.0), (0.0, 0.5 * b), (0.4 * a, -0.3 * b)]:
        ref = st["delta_star"] - x0**2 / (2 * r1) - y0**2 * r1 / 2
        assert_allclose(boussinesq_displacement(x0, y0, a, b, alpha), ref, rtol=TOL_BOUSSINESQ, atol=TOL_BOUSSINESQ)
    al0, al1, al2 = alpha
    assert_allclose(-(al0 + al1) * np.sqrt(np.pi * a), np.sqrt(2), rtol=1e-12)
    assert_allclose(-(al0 + al2) * np.sqrt(np.pi * b), np.sqrt(2), rtol=1e-12)
    assert_allclose(st["W_star"], sn * a * b * (al0 + (al1 + al2) / 3), rtol=1e-12)


def test_circle_is_jkr():
    a = np.linspace(0.02, 4.0, 300)
    st, ref = je.load_curve_nondimensional(a, 1.0), jkr.load_curve_nondimensional(a)
    for key in ("W_star", "delta_star"):
        assert_allclose(st[key], ref[key], rtol=TOL_CIRCLE, atol=TOL_CIRCLE)
    assert np.all(st["beta"] == 1.0)
    for control in ("load", "displacement"):
        po, pj = je.pull_off_nondimensional(1.0, 1.0, control=control), jkr.pull_off_nondimensional(1.0, 1.0, control=control)
        assert_allclose([po["W_star"], po["a_star"]], [pj["W_star"], pj["a_star"]], rtol=TOL_CIRCLE)


def test_continuous_at_the_circle():
    """Near beta0 = 1 the curve leaves JKR linearly in 1 - beta0 (a is the x semi-axis)."""
    a = np.linspace(0.05, 3.0, 50)
    slopes = [np.max(np.abs(je.load_curve_nondimensional(a, 1 - e)["W_star"] - jkr.load_curve_nondimensional(a)["W_star"])) / e
              for e in (1e-4, 1e-7, 1e-10)]
    assert_allclose(slopes, slopes[0], rtol=1e-3)


def test_beta_tends_to_hertz_at_high_load():
    beta0 = np.array([0.5, 0.8, 0.9, 0.99])
    dev = je.ellipticity_at_load(100.0, beta0=beta0) - beta0
    assert np.all(dev > 0)  # rounder than Hertz
    assert dev[-1] <= TOL_HERTZ_BETA  # beta0 = 0.99: 2.6e-4
    # beta - beta0 = C W*^(-1/2) + ...: the adhesive correction decays like JKR's sqrt(8 pi a^3)/W;
    # measured C = 0.084, 0.046, 0.024, 0.0026 at W* = 100, so the 1e-3 target is met at
    # W* = 100 only for beta0 >~ 0.98 (it needs W* ~ 2600 at beta0 = 0.8)
    c4 = (je.ellipticity_at_load(1e4, beta0=beta0) - beta0) * 1e2
    c6 = (je.ellipticity_at_load(1e6, beta0=beta0) - beta0) * 1e3
    assert_allclose(c6, c4, rtol=0.02)
    assert np.all(dev * 10 <= 1.2 * c6)


def test_pull_off_mild_ellipticity():
    """Pull-off over -1.5 pi R dgamma: 1 - f = O((ln rho)^2) (even in ln rho by symmetry), and
    W* of Eq. (34) carries sin(theta_skew) = 1/cosh(ln(rho)/2) on top."""
    rho = np.array([1.02, 1.01, 1.005])
    f = je.pull_off_force_ratio(radius_ratio=rho)
    coef = (1 - f) / np.log(rho) ** 2
    assert np.all(f < 1)
    assert_allclose(coef, coef[-1], rtol=0.02)
    beta0 = je.check_geometry(rho, None)
    w = je.pull_off_nondimensional(beta0, 1.0)["W_star"]
    assert_allclose(w, -0.75 * f * sin_skew_angle(beta0), rtol=1e-12)
    # the notes' reconstruction (not literature): 0.985, 0.944, 0.861 at R'/R'' = 2, 4, 10
    assert_allclose(je.pull_off_force_ratio(radius_ratio=[2.0, 4.0, 10.0]), [0.985, 0.944, 0.861],
                    atol=TOL_NOTES)


def test_pull_off_shape():
    beta0 = np.array([0.8, 0.9, 0.99])
    bpo = je.pull_off_ellipticity(beta0=beta0)
    assert np.all((bpo > beta0) & (bpo < 1))
    po = je.pull_off_nondimensional(beta0, 1.0)
    for b0, w in zip(beta0, po["W_star"]):  # the pull-off is the minimum of a dense scan
        u = np.linspace(1e-4, 1 - 1e-4, 4000)
        _, rm, sn = je.geometry_terms(b0)
        assert w <= np.min(je._state_u(u, b0, rm, sn)["W_star"]) + 1e-12


def test_dimensional():
    r, e, dg = 1e-6, 1e9, 0.05
    po = je.pull_off(r, e, dg, beta0=0.9)
    assert_allclose(po.force, je.pull_off_nondimensional(0.9, 1.0)["W_star"] / sin_skew_angle(0.9) * 2 * np.pi * r * dg,
                    rtol=1e-12)
    assert_allclose(po.ellipticity, je.pull_off_ellipticity(beta0=0.9))
    rho = radius_ratio(0.9)
    assert_allclose(je.pull_off_force(r, e, dg, radius_ratio=rho), po.force, rtol=1e-9)
    c = je.load_curve(np.array([0.5, 2.0]) * np.cbrt(r * r * dg / e), r, e, dg, beta0=0.9)
    assert np.all(c.semi_minor < c.semi_major)


def test_bad_input():
    r, e, dg = 1e-6, 1e9, 0.05
    with pytest.raises(ValueError, match="beta0"):
        je.pull_off(r, e, dg, beta0=1.2)
    with pytest.raises(ValueError, match="radius_ratio"):
        je.pull_off(r, e, dg, radius_ratio=0.5)
    with pytest.raises(ValueError, match="exactly one"):
        je.pull_off(r, e, dg)
    with pytest.raises(ValueError, match="exactly one"):
        je.pull_off_ellipticity(radius_ratio=2.0, beta0=0.9)
    with pytest.raises(ValueError, match="semi_major"):
        je.load_curve(0.0, r, e, dg, beta0=0.9)
    with pytest.raises(ValueError, match="load_star"):
        je.ellipticity_at_load(-0.9, beta0=0.9)
    with pytest.raises(ValueError, match="control"):
        je.pull_off_ellipticity(beta0=0.9, control="both")
    with pytest.raises(ValueError, match="work_of_adhesion"):
        je.pull_off(r, e, -dg, beta0=0.9)


def test_state_at_ellipticity_is_the_curve_at_its_contact_size():
    """The closed-form state at a given beta lies on the load curve (root-finder route) at its a*."""
    st = je.state_at_ellipticity(np.array([0.7, 0.85, 0.95]), 0.6)
    curve = je.load_curve_nondimensional(st["a_star"], 0.6)
    np.testing.assert_allclose(curve["beta"], st["beta"], rtol=1e-10)
    np.testing.assert_allclose(curve["W_star"], st["W_star"], rtol=1e-10)
    for bad in (dict(beta=0.5, beta0=0.6), dict(beta=1.0, beta0=0.6), dict(beta=0.9, beta0=1.0)):
        with pytest.raises(ValueError, match="beta"):
            je.state_at_ellipticity(**bad)


def test_si_pull_off_is_the_one_si_record():
    """jkr_elliptic.pull_off returns the SI records.PullOff (issue 16): the principal radii satisfy
    R'R'' = R^2 and R'/R'' = the given ratio (Eq. 5), JKR has no sigma0 (NaN), and the nondimensional
    fields are the nondimensional core's."""
    r, e, dg = 1e-3, 1e6, 0.05
    po = je.pull_off(r, e, dg, radius_ratio=4.0)
    assert po.model == "jkr-elliptic" and po.geometry == "ellipse"
    assert_allclose([po.r_major / po.r_minor, np.sqrt(po.r_major * po.r_minor)], [4.0, r], rtol=1e-14)
    assert np.isnan(po.max_adhesive_stress)
    nd = je.pull_off_nondimensional(po.beta0, 1.0)
    assert po.W_star == nd.W_star and po.a_star == nd.a_star and po.ellipticity == nd.ellipticity

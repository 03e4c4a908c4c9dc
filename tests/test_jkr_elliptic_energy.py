"""Energy-minimising elliptical JKR (Giudici, Vella & Griffiths 2025): the circle, stationarity
of the total energy in both semi-axes (independent quadrature), the Hertz limit, JG 2005 near
the circle, literature, SI scaling, bad input and the accepted domain."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy import integrate

from dhfield.models import hertz, jkr, jkr_elliptic as je, jkr_elliptic_energy as ee
from dhfield.core.validation import as_circle
from dhfield.core.geometry import ellipticity_from_radius_ratio, radius_ratio, sin_skew_angle

#: JKR closed forms at the circle: the same double-precision arithmetic
TOL_CIRCLE = 1e-12
#: adaptive quadrature of the moments I_j (quad epsrel 1e-13)
TOL_QUAD = 1e-12
#: central differences of the energy, step 1e-4 a: truncation ~1e-8, quadrature noise ~1e-10
TOL_STATIONARY = 1e-6
#: GVG's shape at pull-off is reached where the grid bracket is refined to ~1e-15 in beta
TOL_LOAD_IDENTITY = 1e-9


# ---------------------------------------------------------------- independent energy oracle
def _j_integrals(a, b):
    """J0, J1, J2, J12 of the ellipsoidal potential by adaptive quadrature (s = t^2)."""
    def q(f):
        return integrate.quad(lambda t: 2 * f(t * t) / np.sqrt((a * a + t * t) * (b * b + t * t)), 0, np.inf,
                              epsabs=0, epsrel=1e-13, limit=400)[0]

    return (q(lambda s: 1.0), q(lambda s: 1 / (a * a + s)), q(lambda s: 1 / (b * b + s)),
            q(lambda s: 1 / ((a * a + s) * (b * b + s))))


def _energy(a, b, delta, beta0):
    """Total energy U_E - pi a b (R = E* = dgamma = 1) and the load, from the pressure
    (alpha0 + alpha1 X^2 + alpha2 Y^2)/sqrt(1 - X^2 - Y^2) matched to the gap (physics notes,
    Sec. 6) with U_E = (1/2) int p (delta - A x^2 - B y^2) dA.  The disk moments of
    1/sqrt(1 - r^2) used: int 1 = 2 pi, int X^2 = 2 pi/3, int X^4 = 2 pi/5, int X^2 Y^2 = 2 pi/15."""
    rho = radius_ratio(beta0)
    A, B = 0.5 / np.sqrt(rho), 0.5 * np.sqrt(rho)
    j0, j1, j2, j12 = _j_integrals(a, b)
    m = 0.5 * a * b * np.array([[b * b * j12 - 2 * j1, j1 - b * b * j12], [j2 - a * a * j12, a * a * j12 - 2 * j2]])
    al1, al2 = np.linalg.solve(m, [A, B])
    al0 = (delta / (0.5 * a * b) - al1 * b * b * j2 - al2 * a * a * j1) / (2 * j0)
    load = 2 * np.pi * a * b * (al0 + (al1 + al2) / 3)
    pz = a * b * (al0 * 2 * np.pi / 3 * (A * a * a + B * b * b)
                  + al1 * (2 * np.pi / 5 * A * a * a + 2 * np.pi / 15 * B * b * b)
                  + al2 * (2 * np.pi / 15 * A * a * a + 2 * np.pi / 5 * B * b * b))
    return 0.5 * (delta * load - pz) - np.pi * a * b, load


def _gradient(a, b, delta, beta0):
    h = 1e-4 * a
    da = (_energy(a + h, b, delta, beta0)[0] - _energy(a - h, b, delta, beta0)[0]) / (2 * h)
    db = (_energy(a, b + h, delta, beta0)[0] - _energy(a, b - h, delta, beta0)[0]) / (2 * h)
    return da / (np.pi * b), db / (np.pi * a)  # in units of the surface-energy terms


# ---------------------------------------------------------------- the circle
def test_circle_is_jkr_exactly():
    po = ee.pull_off_nondimensional(1.0, 1.0)
    assert_allclose(po["W_star"], -0.75, rtol=TOL_CIRCLE)  # JKR: -(3/2) pi R dgamma
    assert_allclose(po["a_star"] ** 3, 9 * np.pi / 8, rtol=TOL_CIRCLE)
    pd = ee.pull_off_nondimensional(1.0, 1.0, control="displacement")
    assert_allclose(pd["W_star"], -5 / 12, rtol=TOL_CIRCLE)  # JKR fixed grips: -(5/6) pi R dgamma
    assert_allclose(ee.pull_off_force_ratio(beta0=1.0), 1.0, rtol=TOL_CIRCLE)
    assert_allclose(ee.pull_off_force_ratio(beta0=1.0, control="displacement"), 5 / 9, rtol=TOL_CIRCLE)
    a = np.array([0.1, 1.0, 3.0])
    c = ee.load_curve_nondimensional(a, 1.0)
    ref = jkr.load_curve_nondimensional(a)
    assert_allclose(c["W_star"], ref["W_star"], rtol=TOL_CIRCLE)
    assert_allclose(c["delta_star"], ref["delta_star"], rtol=TOL_CIRCLE)
    assert_allclose(c["beta"], 1.0)


def test_near_circle_is_continuous():
    # pull-off is even in ln(R'/R'') (swap the axes), so 1 - ratio = O(ln(rho)^2) ~ 1e-12 here
    assert_allclose(ee.pull_off_force_ratio(beta0=1 - 1e-6), 1.0, atol=1e-9)
    assert_allclose(ee.pull_off_force_ratio(beta0=1 - 1e-6, control="displacement"), 5 / 9, atol=1e-9)
    # one ulp below the circle (90 deg crossing through geometry.ellipticity_from_skew_angle)
    assert_allclose(ee.pull_off_force_ratio(beta0=np.nextafter(1.0, 0.0)), 1.0, atol=1e-12)


# ---------------------------------------------------------------- both semi-axes free
@pytest.mark.parametrize("beta0,beta", [(0.5, 0.6), (0.5, 0.9), (0.2, 0.35), (0.9, 0.95)])
def test_energy_stationary_in_both_semi_axes(beta0, beta):
    """GVG: dPi/da = dPi/db = 0 at fixed delta, checked on an independent quadrature of Pi."""
    s = ee.state_at_ellipticity(beta, beta0)
    a, b, d = float(s["a_star"]), float(s["b_star"]), float(s["delta_star"])
    ga, gb = _gradient(a, b, d, beta0)
    assert abs(ga) < TOL_STATIONARY and abs(gb) < TOL_STATIONARY, (ga, gb)
    # the load is dU_E/d(delta) at fixed a, b: the same pressure's resultant
    load = _energy(a, b, d, beta0)[1]
    assert_allclose(float(s["W_star"]) / sin_skew_angle(beta0) * 2 * np.pi, load, rtol=1e-10)


def test_jg_state_is_not_stationary_in_both():
    """JG impose one condition: at their states the energy still moves with the shape."""
    s = je.state_at_ellipticity(0.7, 0.5)
    ga, gb = _gradient(float(s["a_star"]), float(s["b_star"]), float(s["delta_star"]), 0.5)
    assert max(abs(ga), abs(gb)) > 1e-2


@pytest.mark.parametrize("m", [1e-3, 0.2, 0.2499, 0.25, 0.2501, 0.5, 0.9, 0.9975])
def test_edge_moments_against_quadrature(m):
    i = [integrate.quad(lambda t: np.sin(t) ** (2 * j) / np.sqrt(1 - m * np.sin(t) ** 2), 0, np.pi / 2,
                        epsabs=0, epsrel=1e-13, limit=200)[0] for j in range(4)]
    ref = [i[1], i[2], i[3], 2 * i[1] - i[0], 2 * i[2] - i[1], 2 * i[3] - i[2]]
    # the differences A_j cancel to ~m of their terms at small m: scale the tolerance by 1/m there
    got = ee._edge_moments(np.array(m))
    assert_allclose(got[:3], ref[:3], rtol=TOL_QUAD)
    assert_allclose(got[3:], ref[3:], rtol=TOL_QUAD / min(m, 1.0) * 10)


def test_edge_moments_series_at_the_circle():
    # A2 = 2 I1 - I0 = (pi/2) sum c_n^2 n/(n+1) m^n: leading term (pi/16) m; A1 = A0 = pi/8 at m = 0
    m = 1e-9
    a2, a1, a0 = ee._edge_moments(np.array(m))[3:]
    assert_allclose(a2, np.pi / 16 * m, rtol=1e-8)
    assert_allclose([a1, a0], [np.pi / 8, np.pi / 8], rtol=1e-8)


def test_griffith_on_average_not_pointwise():
    """Eq. (G2): K_I^2/(2E*) averaged with weights cos^2 and sin^2 equals dgamma; it is not equal
    to dgamma at the two axis ends (JG's condition: there it is ~1 % above, measured 1.4 % and 1.0 %)."""
    s = ee.state_at_ellipticity(0.7, 0.4)
    a, b = float(s["a_star"]), float(s["b_star"])
    al0, al1, al2 = (float(x) for x in s["alpha"])

    def g(phi):
        h = np.sqrt(np.cos(phi) ** 2 / a**2 + np.sin(phi) ** 2 / b**2)
        f = al0 + al1 * np.cos(phi) ** 2 + al2 * np.sin(phi) ** 2
        return np.pi * f * f / (2 * h)  # G = K_I^2/(2E*), K_I = f sqrt(pi/h)

    ga = integrate.quad(lambda p: g(p) * np.cos(p) ** 2, 0, 2 * np.pi, epsabs=0, epsrel=1e-12)[0]
    gb = integrate.quad(lambda p: g(p) * np.sin(p) ** 2, 0, 2 * np.pi, epsabs=0, epsrel=1e-12)[0]
    assert_allclose([ga, gb], [np.pi, np.pi], rtol=1e-10)
    assert g(0.0) - 1 > 5e-3 and g(np.pi / 2) - 1 > 5e-3  # JG's condition G = dgamma there is not met
    # K_I of one sign (tensile: f < 0) all round the edge
    phi = np.linspace(0, 2 * np.pi, 721)
    assert np.all(al0 + al1 * np.cos(phi) ** 2 + al2 * np.sin(phi) ** 2 < 0)


# ---------------------------------------------------------------- Hertz limit
@pytest.mark.parametrize("beta0", [0.2, 0.5, 0.9])
def test_hertz_limit_at_high_load(beta0):
    a = 1e4
    s = ee.load_curve_nondimensional(a, beta0)
    assert abs(float(s["beta"]) - beta0) < 1e-3
    w_hertz = hertz.load(a, beta0) * sin_skew_angle(beta0) / (2 * np.pi)  # Eq. (34)
    # adhesion lowers the load by ~ a^(3/2) against a^3: relative 1e-6 at a* = 1e4
    assert_allclose(float(s["W_star"]), w_hertz, rtol=1e-4)


# ---------------------------------------------------------------- JG 2005 and literature
def test_agrees_with_jg_near_the_circle_to_second_order():
    """Both pull-offs are even in ln(R'/R'') and 1 at the circle; they differ at O(ln(rho)^2)."""
    r1, r2 = 1.01, 1.1
    d1 = ee.pull_off_force_ratio(radius_ratio=r1) / je.pull_off_force_ratio(radius_ratio=r1) - 1
    d2 = ee.pull_off_force_ratio(radius_ratio=r2) / je.pull_off_force_ratio(radius_ratio=r2) - 1
    assert abs(d1) < 0.05 * np.log(r1) ** 2
    assert abs(d2) < 0.05 * np.log(r2) ** 2
    assert_allclose(d2 / d1, (np.log(r2) / np.log(r1)) ** 2, rtol=0.15)  # the order, to O(ln rho)


def test_stronger_than_jg_increasingly_with_slenderness():
    """GVG (abstract): JG under-predict the pull-off, the more so the more eccentric the contact."""
    rho = np.array([1.5, 3.0, 10.0, 30.0, 100.0])
    gap = ee.pull_off_force_ratio(radius_ratio=rho) / je.pull_off_force_ratio(radius_ratio=rho)
    assert np.all(gap > 1) and np.all(np.diff(gap) > 0)


#: Li & Popov (J. Phys. D 2020) BEM fit of JKR ellipsoids, load-control pull-off F/(pi R dgamma)
#: as transcribed in a third-party code (kmnam/biofilm-ABMs jkr.hpp) and quoted in the project's
#: notes (adhesive-solver.md); divided by its own sphere value 1.487 (0.9 % below the exact 1.5).
LI_POPOV = {3.0: 1.468, 5.0: 1.458, 10.0: 1.442, 20.0: 1.422, 50.0: 1.387}


@pytest.mark.parametrize("rho,f", sorted(LI_POPOV.items()))
def test_against_li_popov_fit(rho, f):
    # GVG state agreement with such simulations over all eccentricities (abstract)
    tol = 0.005 if rho <= 5 else 0.02  # the fit is 0.9 % off at the sphere; normalised, ~0.5 %
    assert_allclose(ee.pull_off_force_ratio(radius_ratio=rho), f / 1.487, rtol=tol)


# ---------------------------------------------------------------- SI wrappers
def test_si_scaling_and_invariance():
    r, e, w = 2e-3, 3e6, 0.05
    f = ee.pull_off_force(r, e, w, radius_ratio=4.0)
    # the pull-off force is (ratio) x 1.5 pi R dgamma: independent of E*, linear in R dgamma
    assert_allclose(f, -1.5 * np.pi * r * w * ee.pull_off_force_ratio(radius_ratio=4.0), rtol=1e-13)
    assert_allclose(ee.pull_off_force(r, 7 * e, w, radius_ratio=4.0), f, rtol=1e-13)
    assert_allclose(ee.pull_off_force(3 * r, e, 5 * w, radius_ratio=4.0), 15 * f, rtol=1e-13)
    p1 = ee.pull_off(r, e, w, beta0=ellipticity_from_radius_ratio(4.0), control="displacement")
    p2 = ee.pull_off(8 * r, 8 * e, 8 * w, beta0=ellipticity_from_radius_ratio(4.0), control="displacement")
    # R, E*, dgamma all x8: c_r = (R^2 dgamma/E*)^(1/3) x 4, c_r^2/R x 2, load (R dgamma) x 64
    assert_allclose(p2.semi_major, 4 * p1.semi_major, rtol=1e-12)
    assert_allclose(p2.approach, 2 * p1.approach, rtol=1e-12)
    assert_allclose(p2.force, 64 * p1.force, rtol=1e-12)
    c = ee.load_curve(p1.semi_major, r, e, w, radius_ratio=4.0)
    assert_allclose([c.force, c.approach, c.ellipticity], [p1.force, p1.approach, p1.ellipticity], rtol=1e-9)


def test_broadcasting():
    c = ee.load_curve_nondimensional(np.array([[0.5], [2.0]]), np.array([0.3, 0.6, 1.0]))
    assert c["W_star"].shape == (2, 3)
    p = ee.pull_off_nondimensional(np.array([[0.3, 1.0], [0.6, 0.9]]), 1.0)
    assert p["W_star"].shape == (2, 2)


@pytest.mark.parametrize("kwargs,match", [
    (dict(beta0=0.0), "beta0"), (dict(beta0=1.2), "beta0"), (dict(radius_ratio=0.5), "radius_ratio"),
    (dict(), "exactly one"), (dict(beta0=0.5, radius_ratio=2.0), "exactly one"),
    (dict(beta0=0.5, control="force"), "control"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ee.pull_off(1e-3, 1e6, 0.05, **kwargs)


def test_bad_input_curve_and_state():
    with pytest.raises(ValueError, match="semi_major"):
        ee.load_curve(-1e-6, 1e-3, 1e6, 0.05, beta0=0.5)
    with pytest.raises(ValueError, match="work_of_adhesion"):
        ee.load_curve(1e-6, 1e-3, 1e6, 0.0, beta0=0.5)
    with pytest.raises(ValueError, match="beta must lie"):
        ee.state_at_ellipticity(0.4, 0.5)
    with pytest.raises(ValueError, match="beta0"):
        ee.state_at_ellipticity(0.9, 1.0)


# ---------------------------------------------------------------- accepted domain
@settings(max_examples=40, deadline=None)
@given(beta0=st.floats(0.04, 1.0), log_a=st.floats(-2.0, 3.0))
def test_domain_properties(beta0, log_a):
    """Crossing angles down to ~10 deg (beta0 ~ 0.05): finite states, beta in [beta0, 1],
    the round trip a* -> state -> a*, and the ordering of the pull-offs."""
    po = ee.pull_off_nondimensional(beta0, 1.0)
    pd = ee.pull_off_nondimensional(beta0, 1.0, control="displacement")
    assert np.isfinite(po["W_star"]) and np.isfinite(pd["W_star"])
    assert beta0 <= po.ellipticity <= 1.0 and beta0 <= pd.ellipticity <= 1.0
    assert po["W_star"] <= pd["W_star"] < 0  # load control pulls harder than fixed grips
    ratio = ee.pull_off_force_ratio(beta0=beta0)
    assert 0.8 < ratio <= 1.0 + 1e-12
    assert ratio >= je.pull_off_force_ratio(beta0=beta0) - 1e-12
    a = 10.0**log_a
    c = ee.load_curve_nondimensional(a, beta0)
    assert_allclose(c["a_star"], a)
    if as_circle(beta0) < 1.0:  # closer to 1 than sqrt(eps) is the circle (dhfield.core.validation.as_circle)
        beta = float(c["beta"])
        s = ee.state_at_ellipticity(beta, beta0)
        # the round trip passes beta, rounded to ~eps, through a* = a*(beta): a relative error of up to
        # |d ln a*/d beta| * eps, large near the circle (beta in (beta0, 1), 1 - beta0 small); 8 eps of margin
        h = 1e-3 * min(beta - beta0, 1.0 - beta)  # wide enough that the difference is not itself rounding
        kappa = abs(np.log(ee.state_at_ellipticity(beta + h, beta0)["a_star"])
                    - np.log(ee.state_at_ellipticity(beta - h, beta0)["a_star"])) / (2 * h)
        rtol_a = 1e-9 + 8 * np.finfo(float).eps * kappa
        assert_allclose(s["a_star"], a, rtol=rtol_a)
        # the same round-trip error carried into W*: |dW*/d ln a*| times the relative error of a*
        # (near W* = 0 a fixed relative tolerance on W* would ask more than a* is known to)
        slope = abs(float(ee.load_curve_nondimensional(a * (1 + 1e-6), beta0)["W_star"])
                    - float(ee.load_curve_nondimensional(a * (1 - 1e-6), beta0)["W_star"])) / 2e-6
        assert_allclose(s["W_star"], c["W_star"], rtol=1e-8, atol=1e-12 + 2 * slope * rtol_a)
    # no point of the curve lies below the load-control pull-off
    assert c["W_star"] >= po["W_star"] - TOL_LOAD_IDENTITY


@pytest.mark.parametrize("beta0", [0.2, 0.5])
def test_minimum_in_both_semi_axes_until_fixed_grips_pull_off(beta0):
    """At fixed delta the energy is a minimum in (a, b) (Hessian positive definite) on the branch
    before the displacement-control pull-off, and a saddle after it (one eigenvalue < 0)."""
    b_po = float(ee.pull_off_nondimensional(beta0, 1.0, control="displacement").ellipticity)
    signs = []
    for beta in (beta0 + 0.5 * (b_po - beta0), b_po + 0.5 * (1 - b_po)):
        s = ee.state_at_ellipticity(beta, beta0)
        a, b, d = float(s["a_star"]), float(s["b_star"]), float(s["delta_star"])
        h = 1e-3 * b

        def e(x, y):
            return _energy(x, y, d, beta0)[0]

        haa = (e(a + h, b) - 2 * e(a, b) + e(a - h, b)) / h**2
        hbb = (e(a, b + h) - 2 * e(a, b) + e(a, b - h)) / h**2
        hab = (e(a + h, b + h) - e(a + h, b - h) - e(a - h, b + h) + e(a - h, b - h)) / (4 * h * h)
        signs.append(np.linalg.eigvalsh([[haa, hab], [hab, hbb]]))
    assert np.all(signs[0] > 0.1)  # measured eigenvalues O(1) against FD noise ~1e-4
    assert signs[1][0] < -0.1 < 0.1 < signs[1][1]

"""Nondimensional elliptical DH model: solve, load curves, pull-off (Eqs. 31-36)."""
import numpy as np
import pytest

import dhfield
from dhfield.models import dh_elliptic_fields as dh
from dhfield.models import dh_elliptic as model
from dhfield.models.dh_elliptic_adhesion import work_of_adhesion
from dhfield.core.geometry import sin_skew_angle

#: Delta gamma = 1 is solved to 1e-14 in log; the independent Eq. (31) evaluation agrees to rounding.
DGAMMA_RTOL = 1e-10
#: Issue 2: pull-off -> JKR (-0.75) within 0.5 % at mu = 20, -> DMT (-1) within 2 % at mu = 0.05.
JKR_RTOL, DMT_RTOL = 5e-3, 2e-2
#: Issue 2: pull-off contact size refined to 1e-8 in a*.
A_STAR_ATOL = 1e-8

CASES = [(0.5, 0.8), (1.0, 0.9), (5.0, 0.99), (2.0, 1.0), (0.1, 0.5)]


@pytest.mark.parametrize("mu, beta0", CASES)
def test_load_curve_satisfies_eqs_24_and_31(mu, beta0):
    c = model.load_curve(mu=mu, beta0=beta0, a_star=np.linspace(0.05, 2.5, 25))
    np.testing.assert_allclose(work_of_adhesion(c.a_star, c.c_star, beta0, c.v), 1.0, rtol=DGAMMA_RTOL)
    np.testing.assert_allclose(dh.max_adhesive_stress(c.a_star, c.c_star, beta0, c.v), mu, rtol=1e-12)
    # Eq. (36) is Eq. (25) in the units of Eqs. (32)-(34).
    w = dh.load(c.a_star, c.c_star, beta0, c.v) * sin_skew_angle(beta0) / (2 * np.pi)
    np.testing.assert_allclose(c.W_star, w, rtol=1e-12)
    np.testing.assert_allclose(c.delta_star, dh.approach(c.a_star, c.c_star, beta0, c.v), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(c.b_star, beta0 * c.a_star)


def test_circle_matches_greenwood_johnson_closed_forms():
    c = model.load_curve(mu=1.0, beta0=1.0, a_star=np.linspace(0.05, 2.5, 20))
    a, cc, v = c.a_star, c.c_star, c.v
    np.testing.assert_allclose(v * (1 + v) * 2 / (3 * np.pi) * (cc - a) ** 2 * (cc + 2 * a), 1.0, rtol=1e-12)
    np.testing.assert_allclose(c.W_star, (2 / (3 * np.pi)) * (a**3 - v * (cc**3 - a**3)), rtol=1e-12)


def test_jkr_and_dmt_limits_of_pull_off():
    # JKR: -3/2 pi R dgamma -> W* = -0.75; DMT/Bradley: -2 pi R dgamma -> W* = -1.
    assert model.pull_off(mu=20.0, beta0=1.0).W_star == pytest.approx(-0.75, rel=JKR_RTOL)
    assert model.pull_off(mu=0.05, beta0=1.0).W_star == pytest.approx(-1.0, rel=DMT_RTOL)
    # JKR fixed-grips pull-off: -(5/6) pi R dgamma -> W* = -5/12 (Maugis 2000, Sec. 4.5).
    assert model.pull_off(mu=20.0, beta0=1.0, control="displacement").W_star == pytest.approx(-5 / 12, rel=JKR_RTOL)


def test_jkr_limit_contact_radius():
    # JKR pull-off under load control: a^3 = 9 pi R^2 dgamma/(8 E*).
    assert model.pull_off(mu=100.0, beta0=1.0).a_star == pytest.approx((9 * np.pi / 8) ** (1 / 3), rel=5e-3)


@pytest.mark.parametrize("control, key", [("load", "W_star"), ("displacement", "delta_star")])
@pytest.mark.parametrize("mu, beta0", [(1.0, 0.9), (5.0, 0.8), (2.0, 1.0)])
def test_pull_off_is_stationary_to_1e8(control, key, mu, beta0):
    p = model.pull_off(mu=mu, beta0=beta0, control=control)
    a0 = float(p.a_star)
    assert a0 > 0
    h = 1e-3  # fourth-order stencils: truncation ~h^4 = 1e-12, rounding ~1e-16/h = 1e-13
    f = getattr(model.load_curve(mu=mu, beta0=beta0, a_star=a0 + h * np.arange(-2, 3)), key)
    d1 = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)
    d2 = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h**2)
    assert d2 > 0  # a minimum
    assert abs(d1 / d2) < A_STAR_ATOL  # Newton distance to the stationary point
    assert getattr(p, key) == pytest.approx(f[2], rel=1e-13)


def test_pull_off_continuous_and_monotone_in_beta0():
    beta0 = np.linspace(0.8, 1.0, 41)
    w = np.asarray(model.pull_off(mu=1.0, beta0=beta0).W_star)
    d = np.diff(w)
    assert np.all(d < 0)  # magnitude grows monotonically towards the circle
    assert np.max(np.abs(np.diff(d))) < 0.1 * np.max(np.abs(d))  # no kinks or jumps
    near = model.pull_off(mu=1.0, beta0=[1 - 1e-9, 1.0]).W_star
    assert near[0] == pytest.approx(near[1], abs=1e-7)


def test_zero_contact_limit_matches_small_contact_solve():
    shape = model._shape(np.array(0.8))
    z = model._zero_contact_state(np.array(0.3), shape)
    c = model.load_curve(mu=0.3, beta0=0.8, a_star=[1e-6])
    assert c.c_star[0] == pytest.approx(float(z["c"]), rel=1e-5)
    assert c.W_star[0] == pytest.approx(float(z["W"]), rel=1e-5)


def test_displacement_control_at_zero_contact_on_dmt_side():
    p = model.pull_off(mu=0.5, beta0=0.9, control="displacement")
    assert bool(p.at_zero_contact) and float(p.a_star) == 0.0
    c = model.load_curve(mu=0.5, beta0=0.9, a_star=np.geomspace(1e-3, 3, 200))
    assert float(p.delta_star) <= c.delta_star.min() + 1e-12


def test_vectorised_equals_scalar():
    mu = np.array([0.3, 1.0, 7.0])
    beta0 = np.array([0.85, 0.95])
    grid = model.pull_off(mu=mu[:, None], beta0=beta0[None, :])
    for i, m in enumerate(mu):
        for j, b in enumerate(beta0):
            assert grid.W_star[i, j] == pytest.approx(float(model.pull_off(mu=m, beta0=b).W_star), rel=1e-12)


def test_ellipticity_override_only_changes_shapes():
    # Circle shapes with the normalisation of beta0 = 0.8 (Eq. 34): W* scales by sin(theta_skew).
    p = model.pull_off(mu=2.0, beta0=0.8, ellipticity=1.0)
    assert float(p.W_star) == pytest.approx(float(model.pull_off(mu=2.0, beta0=1.0).W_star) * sin_skew_angle(0.8), rel=1e-12)
    q = model.pull_off(mu=2.0, beta0=0.8, ellipticity=0.8)
    assert float(q.W_star) == pytest.approx(float(model.pull_off(mu=2.0, beta0=0.8).W_star), rel=1e-15)


def test_scalar_and_array_inputs_agree():
    c0, v0 = model.solve_adhesive_axis(1.0, mu=1.0, beta0=0.8)
    assert np.ndim(c0) == 0 and np.ndim(v0) == 0
    c1, v1 = model.solve_adhesive_axis([1.0, 2.0], mu=1.0, beta0=0.8)
    assert c1[0] == pytest.approx(float(c0), rel=1e-15) and v1[0] == pytest.approx(float(v0), rel=1e-15)


def test_top_level_api_fields():
    p = dhfield.pull_off(mu=1.0, beta0=0.9)
    for k in ("beta0", "mu", "W_star", "a_star", "c_star", "v", "delta_star"):
        assert k in p.as_dict()
    c = dhfield.load_curve(mu=1.0, beta0=0.9)
    assert len(c.a_star) == 200


@pytest.mark.parametrize("kw, name", [
    (dict(mu=1.0, beta0=1.5), "beta0"), (dict(mu=1.0, beta0=0.0), "beta0"),
    (dict(mu=0.0, beta0=0.9), "mu"), (dict(mu=-2.0, beta0=0.9), "mu"),
    (dict(mu=np.nan, beta0=0.9), "mu"), (dict(mu=np.inf, beta0=0.9), "mu"),
    (dict(mu=1.0, beta0=0.9, ellipticity=2.0), "ellipticity"),
])
def test_bad_input(kw, name):
    with pytest.raises(ValueError, match=name):
        model.pull_off(**kw)
    with pytest.raises(ValueError, match=name):
        model.load_curve(**kw)


def test_bad_a_star_and_control():
    with pytest.raises(ValueError, match="a_star"):
        model.load_curve(mu=1.0, beta0=0.9, a_star=[0.5, -0.1])
    with pytest.raises(ValueError, match="a_star"):
        model.solve_adhesive_axis(0.0, mu=1.0, beta0=0.9)
    with pytest.raises(ValueError, match="control"):
        model.pull_off(mu=1.0, beta0=0.9, control="force")


# --------------------------------------------------------------------------- issue 9 regressions
#: The large-mu states are formed without cancellation: the JKR limit to rounding (~1e-14 observed).
LIMIT_RTOL = 1e-12


@pytest.mark.parametrize("beta0", [1.0, 0.5, 0.05])
@pytest.mark.parametrize("mu", [1e8, 1e9, 1e12])
def test_issue9_item1_large_mu_is_the_derived_jkr_limit(mu, beta0):
    # Before: mu = 1e8 gave W* = +1.698 at beta0 = 1, 1e9 gave 0, 3e6-1e10 raised RuntimeError.
    for control in ("load", "displacement"):
        p = model.pull_off(mu=mu, beta0=beta0, control=control)
        w_inf, a_inf = model.jkr_limit_pull_off(beta0, control=control)
        assert float(p.W_star) == pytest.approx(float(w_inf), rel=LIMIT_RTOL)
        assert float(p.a_star) == pytest.approx(float(a_inf), rel=1e-10)


def test_jkr_limit_is_jkr_at_the_circle():
    # JKR (Maugis 2000): load control -3/4 at a^3 = 9 pi/8; fixed grips -5/12 at a^3 = 9 pi/8 / 9.
    w, a = model.jkr_limit_pull_off(1.0)
    assert w == pytest.approx(-0.75, rel=1e-14) and a**3 == pytest.approx(9 * np.pi / 8, rel=1e-14)
    w, a = model.jkr_limit_pull_off(1.0, control="displacement")
    assert w == pytest.approx(-5 / 12, rel=1e-14) and a**3 == pytest.approx(np.pi / 8, rel=1e-14)


def test_finite_mu_approaches_the_jkr_limit_as_mu_squared():
    # The annulus width ~ mu^-2 (Eqs. 24, 31): the departure falls 100x per decade of mu.
    w_inf = float(model.jkr_limit_pull_off(0.7)[0])
    d = [float(model.pull_off(mu=mu, beta0=0.7).W_star) / w_inf - 1.0 for mu in (100.0, 1000.0)]
    assert 80.0 < d[0] / d[1] < 120.0


def test_issue9_item2_small_beta0_finds_the_stable_branch_end():
    # Before: beta0 = 0.001, mu = 100 reported the zero-contact limit W* = -7.6e-8 while the
    # curve's minimum is W* = -3.94e-5 near a* = 4.4 (the fixed scan stopped at a* = 4).
    p = model.pull_off(mu=100.0, beta0=0.001)
    c = model.load_curve(mu=100.0, beta0=0.001, a_star=np.linspace(3.0, 6.0, 601))
    assert not bool(p.at_zero_contact)
    assert float(p.W_star) <= c.W_star.min()  # the refined minimum is below every sample
    assert float(p.W_star) == pytest.approx(c.W_star.min(), rel=1e-5)  # grid step 5e-3: O(h^2)
    disp = model.pull_off(mu=100.0, beta0=0.001, control="displacement")
    assert abs(float(p.W_star)) >= abs(float(disp.W_star))


def test_pull_off_at_a_pull_off_contact_six_times_the_jkr_limit():
    # beta0 = 1e-4, mu = 10 pulls off at a* ~ 21 (JKR limit: 3.8): the scan must extend.
    p = model.pull_off(mu=10.0, beta0=1e-4)
    assert float(p.a_star) > 15.0
    c = model.load_curve(mu=10.0, beta0=1e-4, a_star=float(p.a_star) * np.array([0.98, 1.0, 1.02]))
    assert c.W_star[1] <= c.W_star[0] and c.W_star[1] <= c.W_star[2]


def test_issue9_item7_chunked_search_equals_one_chunk(monkeypatch):
    from dhfield.core import pull_off_search

    mu = np.geomspace(0.05, 50.0, 7)[:, None]
    beta0 = np.array([0.4, 0.8, 1.0])[None, :]
    whole = model.pull_off(mu=mu, beta0=beta0)
    monkeypatch.setattr(pull_off_search, "DEFAULT_CHUNK_BYTES", 1)  # one problem per chunk
    monkeypatch.setattr(model, "CHUNK_POINTS", 5)
    parts = model.pull_off(mu=mu, beta0=beta0)
    # Each problem has its own quadrature panels, scan and root (issue 11): chunking changes nothing.
    np.testing.assert_array_equal(whole.W_star, parts.W_star)
    assert whole.W_star.shape == (7, 3)


def test_issue9_item7_huge_curve_is_refused_by_name():
    # Before: curve --n 10000000 was OOM-killed.
    with pytest.raises(ValueError, match=r"n must be an integer in \[2, 1000000\]"):
        model.load_curve(mu=1.0, beta0=0.8, n=10_000_000)


@pytest.mark.parametrize("name", ["mu", "beta0", "a_star"])
@pytest.mark.parametrize("value", [1e-308, 1e308, np.inf, np.nan, -1.0, 0.0])
def test_issue9_item8_extreme_inputs_name_the_parameter(name, value):
    # Before: screens of RuntimeWarnings, then "cannot convert float NaN to integer".
    kw = {"mu": 1.0, "beta0": 0.8, "a_star": [1.0]}
    kw[name] = value if name != "a_star" else [value]
    with pytest.raises(ValueError, match=rf"^{name} must be"):
        model.load_curve(mu=kw["mu"], beta0=kw["beta0"], a_star=kw["a_star"])
    if name != "a_star":
        with pytest.raises(ValueError, match=rf"^{name} must be"):
            model.pull_off(mu=kw["mu"], beta0=kw["beta0"])


def test_issue9_tiny_mu_is_rejected_by_name():
    # Before: pulloff --beta0 0.9 --mu 1e-30 gave a traceback.
    with pytest.raises(ValueError, match=r"^mu must be in \[1e-06, 1e\+12\]"):
        model.pull_off(mu=1e-30, beta0=0.9)


@pytest.mark.parametrize("n", [2.5, "10", True, 1])
def test_issue9_item9_non_integer_n_is_rejected(n):
    with pytest.raises(ValueError, match=r"^n must be an integer"):
        model.load_curve(mu=1.0, beta0=0.8, n=n)


def test_issue9_item9_masked_arrays_are_rejected_and_empty_arrays_give_empty_results():
    masked = np.ma.masked_array([0.5, 1.0], mask=[False, True])
    with pytest.raises(ValueError, match="^a_star must not be a masked array"):
        model.load_curve(mu=1.0, beta0=0.8, a_star=masked)
    with pytest.raises(ValueError, match="^mu must not be a masked array"):
        model.pull_off(mu=np.ma.masked_array([1.0]), beta0=0.8)
    c = model.load_curve(mu=1.0, beta0=0.8, a_star=np.array([]))
    assert c.W_star.shape == (0,) and c.c_star.shape == (0,)
    p = model.pull_off(mu=np.zeros((0, 3)) + 1.0, beta0=0.8)
    assert np.shape(p.W_star) == (0, 3)


# --- issue 11: the pull-off search runs in the ratio x = a/S (one quadrature a state) --------------

#: Brute-force reference (below): two nested grids; the fine step is ~1e-5 a*, so W*(a*) of the
#: grid minimum is within W'' h^2 ~ 1e-10 |W*| of the true minimum, and a* within ~2 fine steps.
BRUTE_W_RTOL, BRUTE_A_RTOL = 1e-9, 5e-5
#: A state at ratio x satisfies Eqs. (24), (31) to the quadrature's accuracy (~1e-12).
RATIO_STATE_RTOL = 1e-10
#: Central differences of W*(a*) with h = 1e-5 a*: truncation ~h^2, rounding ~1e-16/h.
FD_RTOL = 1e-7


def _brute_force_minimum(mu, beta0, key):
    """Minimum of W*(a*) or delta*(a*) from load curves on nested grids (Newton solve at each a*)."""
    a = np.geomspace(1e-3, 40.0, 1500)
    f = getattr(model.load_curve(mu=mu, beta0=beta0, a_star=a), key)
    i = int(np.argmin(f))
    fine = np.linspace(a[max(i - 1, 0)], a[min(i + 1, a.size - 1)], 2001)
    c = model.load_curve(mu=mu, beta0=beta0, a_star=fine)
    j = int(np.argmin(getattr(c, key)))
    assert 0 < j < fine.size - 1  # an interior minimum
    return c, j


@pytest.mark.parametrize("control, key", [("load", "W_star"), ("displacement", "delta_star")])
@pytest.mark.parametrize("mu, beta0", [(1.0, 0.8), (5.0, 0.3), (2.0, 1.0), (300.0, 0.05), (30.0, 0.6)])
def test_issue11_pull_off_equals_brute_force_minimum_of_the_load_curve(control, key, mu, beta0):
    # Independent of the search: the load curve solves S at each a* by Newton (no ratio, no scan,
    # no root finder); its grid minimum is the pull-off where that minimum is the global one.
    p = model.pull_off(mu=mu, beta0=beta0, control=control)
    c, j = _brute_force_minimum(mu, beta0, key)
    assert not bool(p.at_zero_contact)
    assert float(getattr(p, key)) <= getattr(c, key)[j] * (1 - 1e-15)  # below every sample (negative)
    assert float(getattr(p, key)) == pytest.approx(getattr(c, key)[j], rel=BRUTE_W_RTOL)
    assert float(p.a_star) == pytest.approx(c.a_star[j], rel=BRUTE_A_RTOL)


@pytest.mark.parametrize("mu, beta0", [(1e-5, 0.3), (0.3, 0.8), (1.0, 1.0), (1e4, 0.01), (1e10, 0.9)])
def test_issue11_state_at_ratio_satisfies_eqs_24_31_and_its_derivative(mu, beta0):
    shape = model._shape(np.array(beta0), sin_skew_angle(beta0))
    x = np.geomspace(1e-2, 1e2, 7) * max(1.0, mu)  # a ~ (x/mu)^2 at large mu: a* ~ 1e-4 to 1e4
    st = model._state_at_ratio(x, mu, shape, derivatives=True)
    a, c, v = st["a"], st["c"], st["v"]
    np.testing.assert_allclose(a / st["s"], x, rtol=1e-14)
    if mu <= 100.0:  # the direct Eq. (31) loses c - a ~ mu^-2 to rounding beyond
        np.testing.assert_allclose(work_of_adhesion(a, c, beta0, v), 1.0, rtol=RATIO_STATE_RTOL)  # Eq. (31)
        np.testing.assert_allclose(dh.max_adhesive_stress(a, c, beta0, v), mu, rtol=RATIO_STATE_RTOL)  # Eq. (24)
    # The Newton solve in S at the same a* (load_curve) gives the same state.
    curve = model.load_curve(mu=mu, beta0=beta0, a_star=a)
    np.testing.assert_allclose(v, curve.v, rtol=RATIO_STATE_RTOL)
    np.testing.assert_allclose(st["W"], curve.W_star, rtol=RATIO_STATE_RTOL)
    for key, d in (("W_star", "dW"), ("delta_star", "ddelta")):
        h = 1e-5 * a
        fd = (getattr(model.load_curve(mu=mu, beta0=beta0, a_star=a + h), key) - getattr(model.load_curve(mu=mu, beta0=beta0, a_star=a - h), key)) / (2 * h)
        scale = np.abs(getattr(model.load_curve(mu=mu, beta0=beta0, a_star=a), key)) / a  # |f|/a: the derivative's natural size
        np.testing.assert_allclose(st[d], fd, rtol=0, atol=FD_RTOL * np.max(scale))


def test_issue11_pull_off_does_not_depend_on_the_batch():
    # Every problem gets its own quadrature panels and its own scan and root: a point alone gives
    # bit-identical results to the same point in any batch (the sweep's blocks may be cut anyhow).
    rng = np.random.default_rng(3)
    mu = 10.0 ** rng.uniform(-2, 3, 12)
    beta0 = rng.uniform(0.05, 1.0, 12)
    for control in ("load", "displacement"):
        batch = model.pull_off(mu=mu, beta0=beta0, control=control)
        for i in (0, 5, 11):
            one = model.pull_off(mu=mu[i], beta0=beta0[i], control=control)
            assert float(one.W_star) == batch.W_star[i] and float(one.a_star) == batch.a_star[i]


#: Central difference of W*(a*) with step h = 1e-4 a* (a* <= 1.5): truncation h^2 f'''/6 ~ 1e-8,
#: rounding ~1e-11; absolute, since dW*/da* vanishes near the pull-off (a* = 1.5 at mu = 5).
ATOL_SLOPE_FD = 1e-7


def test_load_curve_nondimensional_slopes_are_the_derivative_of_the_curve():
    """dW*/da* and d delta*/da* (implicit differentiation) against a central difference, broadcast over mu, beta0."""
    a = np.array([0.3, 0.8, 1.5])
    mu, beta0 = np.array([0.5, 1.0, 5.0]), np.array([0.6, 0.9, 1.0])
    st = model.load_curve_nondimensional(a, mu=mu, beta0=beta0, derivatives=True)
    h = 1e-4 * a
    up, dn = (model.load_curve_nondimensional(a + s * h, mu=mu, beta0=beta0) for s in (1.0, -1.0))
    np.testing.assert_allclose(st["dW_star"], (up["W_star"] - dn["W_star"]) / (2 * h), rtol=0,
                               atol=ATOL_SLOPE_FD)
    np.testing.assert_allclose(st["ddelta_star"], (up["delta_star"] - dn["delta_star"]) / (2 * h),
                               rtol=0, atol=ATOL_SLOPE_FD)
    with pytest.raises(ValueError, match="a_star"):
        model.load_curve_nondimensional(-1.0, mu=1.0, beta0=0.8)


@pytest.mark.parametrize("call", [lambda: model.pull_off(1.0, 0.9), lambda: model.load_curve(1.0, 0.9),
                                  lambda: model.solve_adhesive_axis(1.0, 1.0, 0.9),
                                  lambda: model.load_curve_nondimensional(1.0, 1.0, 0.9)])
def test_beta0_and_mu_are_keyword_only(call):
    """(beta0, mu) is GRID_DIMS' order, (mu, beta0) was the old one: a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_unchecked_load_curve_is_the_checked_curve():
    """checked=False (compare.load_curve, inputs validated once) skips the checks, not a digit."""
    a = np.array([0.05, 0.5, 1.0, 3.0])
    got = model.load_curve(beta0=0.6, mu=1.3, a_star=a, checked=False)
    ref = model.load_curve(beta0=0.6, mu=1.3, a_star=a)
    for k in ("a_star", "b_star", "c_star", "d_star", "v", "W_star", "delta_star"):
        assert np.array_equal(getattr(got, k), getattr(ref, k)), k

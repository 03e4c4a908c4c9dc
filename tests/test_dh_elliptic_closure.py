"""Tests of dhfield.models.dh_elliptic_closure: the equal-beta test and the alternative closures."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.models import (dh_elliptic_closure as closure, hertz, dh_elliptic as model, dh_elliptic_periphery
                            as periphery)
from dhfield.core.geometry import radius_ratio

#: The closure solves stop at |log Delta gamma| < 1e-12; states agree to ~1e-11.
SOLVE_RTOL = 1e-10
#: Pull-off minima are located to 1e-8 in a*; W* is flat there (error ~1e-14), but
#: the paper baseline comes from dhfield.models.dh_elliptic's own (different) root finder.
PULL_OFF_RTOL = 1e-9
#: The contact condition is linear algebra on closed forms: rounding only.
CONTACT_ATOL = 1e-12


def test_paper_closure_equals_model_pull_off():
    mu, beta0 = np.array([0.5, 2.0]), 0.8
    got = closure.pull_off_closure(beta0=beta0, mu=mu, closure="paper")
    ref = model.pull_off(mu=mu, beta0=beta0)
    assert got.model == "dh-elliptic" and got.control == "load"
    assert_allclose(got.W_star, ref.W_star, rtol=PULL_OFF_RTOL)
    assert_allclose(got.a_star, ref.a_star, rtol=1e-6)  # a* of a flat minimum: sqrt(tolerance)
    state = closure.state_at_pull_off(beta0=beta0, mu=mu, closure="paper")  # the closure's own state at that point
    assert np.array_equal(state.a_star, got.a_star) and np.array_equal(state.W_star, got.W_star)
    assert_allclose(state.work_major, 1.0, rtol=1e-12)


@pytest.mark.parametrize("solver", [closure.solve_ray_average, closure.solve_two_axis])
def test_alternative_closures_reduce_to_paper_at_circle(solver):
    a = np.array([0.05, 0.7, 1.5, 2.5])
    got = solver(a, beta0=1.0, mu=1.3)
    c, v = model.solve_adhesive_axis(a, mu=1.3, beta0=1.0)
    assert_allclose(got.c_star, c, rtol=SOLVE_RTOL)
    assert_allclose(got.d_star, c, rtol=SOLVE_RTOL)
    assert_allclose(got.b_star, a, rtol=SOLVE_RTOL)
    assert_allclose(got.adhesive_amplitude, v * hertz.max_pressure(c, 1.0), rtol=SOLVE_RTOL)
    lc = model.load_curve(mu=1.3, beta0=1.0, a_star=a)
    assert_allclose(got.W_star, lc.W_star, rtol=SOLVE_RTOL)
    assert_allclose(got.delta_star, lc.delta_star, rtol=SOLVE_RTOL, atol=1e-12)


@pytest.mark.parametrize("name", ["ray_average", "two_axis"])
def test_alternative_pull_off_reduces_to_paper_at_circle(name):
    got = closure.pull_off_closure(beta0=1.0, mu=1.0, closure=name)
    ref = model.pull_off(mu=1.0, beta0=1.0)
    assert_allclose(got.W_star, ref.W_star, rtol=PULL_OFF_RTOL)


def test_two_axis_constraints_and_contact_condition():
    mu, beta0 = 2.0, 0.8
    st = closure.solve_two_axis(np.array([0.4, 1.2, 2.0]), beta0=beta0, mu=mu)
    assert_allclose(st.work_major, 1.0, rtol=1e-11)  # Eq. (31) on theta_p = 0
    assert_allclose(st.work_minor, 1.0, rtol=1e-11)  # ... and on theta_p = pi/2
    assert_allclose(st.sigma0_major, mu, rtol=1e-12)  # Eq. (24) with Eq. (35)
    # Contact condition by explicit superposition of the two Hertz displacements (Eq. 13).
    r1, r2 = np.sqrt(radius_ratio(beta0)), 1 / np.sqrt(radius_ratio(beta0))
    for k in range(3):
        a, b, c, d = st.a_star[k], st.b_star[k], st.c_star[k], st.d_star[k]
        amp_a, amp_b = st.contact_amplitude[k], st.adhesive_amplitude[k]
        t = np.linspace(0, 2 * np.pi, 13)
        rho = np.array([0.0, 0.3, 0.7, 0.999])[:, None]
        x, y = rho * a * np.cos(t), rho * b * np.sin(t)

        def omega(xx, yy):
            return (hertz.surface_displacement(xx, yy, a, b, amp_a)
                    - hertz.surface_displacement(xx, yy, c, d, amp_b))

        delta = omega(0.0, 0.0)
        h = x**2 / (2 * r1) + y**2 / (2 * r2) + omega(x, y) - delta  # Eq. (27)
        assert np.max(np.abs(h)) < CONTACT_ATOL
        assert_allclose(delta, st.delta_star[k], rtol=1e-12)
        # annulus gap: (A/E*) g of dhfield.models.dh_elliptic_periphery, on the axes at mid-zone
        xm = 0.5 * (a + c)
        h_mid = xm**2 / (2 * r1) + omega(xm, 0.0) - delta
        assert_allclose(h_mid, amp_a * periphery._gap_shape(xm, 0.0, a, b), rtol=1e-10)
        # load: (2 pi/3)(A ab - B cd), Eq. (25), with Eq. (34)'s sin(theta_skew)
        w = 2 * np.pi / 3 * (amp_a * a * b - amp_b * c * d)
        sn = 2 * np.sqrt(radius_ratio(beta0)) / (1 + radius_ratio(beta0))
        assert_allclose(st.W_star[k], w * sn / (2 * np.pi), rtol=1e-12)


def test_two_axis_ellipticities_same_side_of_beta0():
    # Derived in the module docstring: A ab I2_ab [rho(beta_ab) - rho0] = B cd I2_cd [rho(beta_cd) - rho0]
    # with A ab I2_ab > B cd I2_cd > 0: same side, adhesive ellipse further from beta0.
    st = closure.solve_two_axis(np.array([0.3, 1.0, 1.8]), beta0=0.8, mu=np.array([[0.5], [5.0]]))
    assert np.all(st.beta_contact > 0.8)
    assert np.all(st.beta_adhesive > st.beta_contact)


def test_ray_average_constraints():
    a, mu, beta0 = np.array([0.3, 1.0, 2.0]), 1.0, 0.8
    st = closure.solve_ray_average(a, beta0=beta0, mu=mu)
    th = np.linspace(0, np.pi / 2, 41)
    v = st.adhesive_amplitude / hertz.max_pressure(st.c_star, beta0)
    prof = periphery.periphery(a[:, None], st.c_star[:, None], beta0, v[:, None], th)
    mean = periphery.ray_average(prof.work_of_adhesion, th, prof.contact_radius)
    assert_allclose(mean, 1.0, rtol=1e-11)
    assert_allclose(prof.max_adhesive_stress, mu, rtol=1e-12)
    assert np.all(prof.work_of_adhesion[..., 0] > 1.0)
    assert np.all(prof.work_of_adhesion[..., -1] < 1.0)
    angle = closure.solve_ray_average(a, beta0=beta0, mu=mu, weight="angle")
    assert not np.allclose(angle.c_star, st.c_star, rtol=1e-6)


def test_equal_beta_spread():
    mu = np.array([0.5, 1.0, 5.0])
    s = closure.equal_beta_spread(beta0=np.array([[0.8], [0.9], [1.0]]), mu=mu)
    # circle: one cohesive law on every ray
    for q in (s.work_spread[2], s.law_spread[2], s.law_sup_spread[2]):
        assert np.all(np.abs(q) < 1e-10)
    assert_allclose(s.work_ratio[2], 1.0, rtol=1e-12)
    # more elliptical -> further from one law; at pull-off Delta gamma(0) = 1
    assert np.all(s.work_ratio[0] < s.work_ratio[1])
    assert np.all(s.law_spread[0] > s.law_spread[1])
    po = model.pull_off(mu=mu, beta0=0.8)
    w90 = periphery.periphery(po.a_star, po.c_star, 0.8, po.v, [np.pi / 2]).work_of_adhesion[..., 0]
    assert_allclose(s.work_ratio[0], w90, rtol=1e-12)
    assert_allclose(s.width_ratio[:2], np.array([[0.8], [0.9]]) * np.ones(3), rtol=1e-12)  # r_cd - r_ab scales as beta


def test_law_spread_identity():
    law = periphery.cohesive_law(1.3, 2.0, 1.0, 1.1, theta=[0.0, 0.5, 1.0])
    assert closure.law_spread(law) < 1e-12


@pytest.mark.parametrize("call, match", [
    (lambda: closure.pull_off_closure(beta0=0.8, mu=1.0, closure="bogus"), "closure"),
    (lambda: closure.pull_off_closure(beta0=0.8, mu=1.0, control="force"), "control"),
    (lambda: closure.solve_two_axis(-1.0, beta0=0.8, mu=1.0), "a_star"),
    (lambda: closure.solve_ray_average(1.0, beta0=0.8, mu=0.0), "mu"),
    (lambda: closure.solve_ray_average(1.0, beta0=0.8, mu=1.0, weight="x"), "weight"),
    (lambda: closure.equal_beta_spread(beta0=1.5, mu=1.0), "beta0"),
    (lambda: closure.law_spread(periphery.cohesive_law(1.3, 2.0, 0.8, 1.1, theta=[0.0, 1.0]), "l2"), "norm"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.mark.parametrize("call", [lambda: closure.equal_beta_spread(1.0, 0.9),
                                  lambda: closure.solve_ray_average(1.0, 1.0, 0.9),
                                  lambda: closure.solve_two_axis(1.0, 1.0, 0.9),
                                  lambda: closure.pull_off_closure(1.0, 0.9),
                                  lambda: closure.state_at_pull_off(1.0, 0.9)])
def test_beta0_and_mu_are_keyword_only(call):
    """(beta0, mu) is GRID_DIMS' order, (mu, beta0) was the old one: a positional call would swap them silently.
    (``pull_off_two_axis``/``pull_off_ray_average`` are the registry's ``f(beta0, mu, *, control)`` cores.)"""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_displacement_control_and_zero_contact():
    # mu = 0.5: displacement-controlled pull-off at zero contact (DMT side); mu = 5: interior minimum.
    for mu in (0.5, 5.0):
        got = closure.pull_off_closure(beta0=0.8, mu=mu, closure="paper", control="displacement")
        ref = model.pull_off(mu=mu, beta0=0.8, control="displacement")
        assert_allclose(got.delta_star, ref.delta_star, rtol=1e-9)
        assert_allclose(got.W_star, ref.W_star, rtol=1e-6)
        assert bool(got.at_zero_contact) == bool(ref.at_zero_contact)
    two = closure.pull_off_closure(beta0=1.0, mu=0.5, closure="two_axis", control="displacement")
    assert_allclose(two.delta_star, model.pull_off(mu=0.5, beta0=1.0, control="displacement").delta_star, rtol=1e-9)


@pytest.mark.parametrize("theta", [0.0, 0.6, np.pi / 2])
def test_two_axis_ray_work_against_quad(theta):
    # Independent oracle for the general (beta_cd != beta_ab) field: quad of sigma dh/dr with the
    # gap gradient built from both Hertz displacement gradients (Eq. 13) and the geometry (Eq. 2).
    from scipy import integrate

    st = closure.solve_two_axis(1.0, beta0=0.8, mu=2.0)
    a, b, c, d = (float(q) for q in (st.a_star, st.b_star, st.c_star, st.d_star))
    amp_a, amp_b = float(st.contact_amplitude), float(st.adhesive_amplitude)
    rho = radius_ratio(0.8)
    r1, r2 = np.sqrt(rho), 1 / np.sqrt(rho)
    r_ab = a * b / np.hypot(b * np.cos(theta), a * np.sin(theta))
    r_cd = c * d / np.hypot(d * np.cos(theta), c * np.sin(theta))

    def f(t):
        r = r_ab + (r_cd - r_ab) * np.sin(t) ** 2
        x, y = r * np.cos(theta), r * np.sin(theta)
        ga = hertz.surface_displacement_gradient(x, y, a, b, amp_a)
        gc = hertz.surface_displacement_gradient(x, y, c, d, amp_b)
        hx, hy = x / r1 + ga[0] - gc[0], y / r2 + ga[1] - gc[1]
        sigma = hertz.pressure(x, y, c, d, amp_b)
        return sigma * (hx * np.cos(theta) + hy * np.sin(theta)) * 2 * (r_cd - r_ab) * np.sin(t) * np.cos(t)

    ref, _ = integrate.quad(f, 0, np.pi / 2, epsabs=0, epsrel=1e-12, limit=200)
    got = periphery.periphery_two_ellipses(a, b, c, d, amp_a, amp_b, np.array([theta])).work_of_adhesion[0]
    assert_allclose(got, ref, rtol=1e-9)
    if theta in (0.0, np.pi / 2):
        assert_allclose(ref, 1.0, rtol=1e-9)


@pytest.mark.parametrize("mu, beta0, name", [(50.0, 0.8, "mu"), (1e12, 0.9, "mu"), (1.0, 0.1, "beta0")])
def test_issue9_closures_reject_outside_their_domain_by_name(mu, beta0, name):
    # Before: the two-axis solve raised RuntimeError from mu ~ 100 and rays_for(1e-4) ran out of memory.
    from dhfield.models import dh_elliptic_closure as cl

    for f in (cl.pull_off_two_axis, cl.pull_off_ray_average):
        with pytest.raises(ValueError, match=rf"^{name} must be in"):
            f(beta0, mu)


@pytest.mark.parametrize("gap", [1e-7, 5e-8, 2e-8, 1e-9, 3e-15])
@pytest.mark.parametrize("control", ["load", "displacement"])
def test_issue18_item12_two_axis_converges_next_to_the_circle(gap, control):
    """beta0 = 1 - gap: before, RuntimeError 'did not converge' from about 1 - 1e-7 to 1 - 3e-15 (the
    finite-difference step crossed d = c).  The pull-off tends to the circle's: W* departs by O(gap) plus
    the closure's own search tolerance (find_minimum xatol 1e-8 on a*: W* to ~1e-7 relative at worst on
    the flat displacement-control minimum), hence 1e-6."""
    got = closure.pull_off_two_axis(1.0 - gap, 1.0, control=control)
    ref = closure.pull_off_two_axis(1.0, 1.0, control=control)
    assert np.isfinite(got.W_star)
    assert_allclose(got.W_star, ref.W_star, rtol=1e-6)

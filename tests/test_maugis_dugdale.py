"""Maugis-Dugdale: the three equations, the DMT and JKR limits, speed, bad input.

Limits (issue 3): pull-off within 0.1 % of DMT at lambda = 0.01 and of JKR at
lambda = 100.  Whole load curves: the approach to the limits is not uniform in A
and its rate is set by the physics, so the curves are checked against the
asymptotic rates below (measured values in the comments); "within 1e-4 in Maugis
units" is reached for the load at lambda = 1000 (JKR side) and lambda = 0.001 (DMT
side), not at lambda = 100 and 0.01 (see the module-level constants).
"""
import time

import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.models import maugis_dugdale as md
from dhfield.core.transition import maugis_parameter

#: issue 3: pull-off within 0.1 % of the limits (measured 0.086 % at 0.01, 0.0011 % at 100)
TOL_PULL_OFF = 1e-3
#: issue 3 target for whole curves in Maugis units (met at lambda = 1000 / 0.001)
TOL_CURVE = 1e-4
#: lambda = 100 vs JKR: the load deviates by O(lambda^-2) A-dependent terms; measured
#: 3.1e-4 max of |dP|/max(1, |P|) on A in [0, 10] (at A ~ 2), so 1e-4 is not reachable there
TOL_CURVE_JKR_100 = 4e-4
#: lambda = 0.01 vs DMT on A <= 0.3: O(lambda^1.5) load deviation, measured 1.7e-3 at A = 0
TOL_CURVE_DMT_001 = 2e-3
#: the DMT-side approach offset -(8/3) sqrt(lambda/pi) holds to O(sqrt(lambda)) relative
TOL_DMT_OFFSET = 0.05
#: residuals of the MD equations re-evaluated from the returned m: M = sqrt(m^2 - 1)
#: recomputed from m loses ~eps/(m - 1) ~ 1e-12 (m - 1 ~ 1e-4 at lambda = 100)
TOL_RESIDUAL = 1e-9


def jkr_maugis(a):
    return a**3 - np.sqrt(6 * a**3), a**2 - 2 / 3 * np.sqrt(6 * a)


def test_first_equation_residual():
    a = np.geomspace(1e-3, 20, 60)
    for lam in np.geomspace(0.01, 100, 15):  # every lambda of the stated range, A over 4 decades
        p, d, m = md.load_curve_maugis_units(a, lam)
        assert np.all(np.isfinite(p) & np.isfinite(d) & (m > 1))
        mm = np.sqrt(m * m - 1)
        lhs = (lam * a**2 / 2 * (mm + (m * m - 2) * np.arctan(mm))
               + 4 * lam**2 * a / 3 * (mm * np.arctan(mm) - m + 1))  # Maugis (1992), first MD equation
        assert_allclose(lhs, 1.0, rtol=TOL_RESIDUAL)  # direct form here, series inside at small M
        assert_allclose(p, a**3 - lam * a**2 * (mm + m * m * np.arctan(mm)), rtol=TOL_RESIDUAL, atol=1e-12)
        assert_allclose(d, a**2 - 4 / 3 * a * lam * mm, rtol=TOL_RESIDUAL, atol=1e-12)


def test_series_branch_matches_direct_form():
    mm = np.array([0.099, 0.0999, 0.1, 0.1001])
    direct = mm + (mm * mm - 1) * np.arctan(mm)
    assert_allclose(md._bracket_adhesion(mm), direct, rtol=1e-12)


@pytest.mark.parametrize("control,jkr_value", [("load", -1.5), ("displacement", -5 / 6)])
def test_pull_off_limits(control, jkr_value):
    _, p_dmt, _, _ = md._pull_off_maugis_units(0.01, control)
    _, p_jkr, _, _ = md._pull_off_maugis_units(100.0, control)
    assert abs(p_dmt / -2.0 - 1) <= TOL_PULL_OFF
    assert abs(p_jkr / jkr_value - 1) <= TOL_PULL_OFF


def test_pull_off_monotone_in_lambda():
    lam = np.geomspace(0.01, 100, 41)
    _, p, _, _ = md._pull_off_maugis_units(lam)
    assert np.all(np.diff(p) > 0)  # from -2 (DMT) up to -1.5 (JKR)


def test_load_curves_jkr_side():
    a = np.concatenate([[0.0], np.geomspace(1e-4, 10, 400)])
    pj, dj = jkr_maugis(a)
    p, d, _ = md.load_curve_maugis_units(a, 100.0)
    assert np.max(np.abs(p - pj) / np.maximum(1, np.abs(pj))) <= TOL_CURVE_JKR_100
    p, d, _ = md.load_curve_maugis_units(a, 1000.0)
    assert np.max(np.abs(p - pj) / np.maximum(1, np.abs(pj))) <= TOL_CURVE
    big = a >= 0.3  # the approach converges non-uniformly: D(A = 0) = -(4/3) lambda x = O(1/lambda)
    assert np.max(np.abs(d - dj)[big] / np.maximum(1, np.abs(dj[big]))) <= TOL_CURVE


def test_load_curves_dmt_side():
    a = np.concatenate([[0.0], np.geomspace(1e-4, 0.3, 200)])
    p, d, _ = md.load_curve_maugis_units(a, 0.01)
    assert np.max(np.abs(p - (a**3 - 2))) <= TOL_CURVE_DMT_001
    offset = -8 / 3 * np.sqrt(0.01 / np.pi)  # D - A^2 -> -(4/3) lambda (A m), A m -> 2/sqrt(pi lambda)
    assert_allclose(d - a**2, offset, rtol=TOL_DMT_OFFSET)
    small = a <= 0.1
    p, _, _ = md.load_curve_maugis_units(a, 0.001)
    assert np.max(np.abs(p - (a**3 - 2))[small]) <= TOL_CURVE


def test_zero_contact_end_point():
    for lam in (0.05, 1.0, 20.0):
        p0, d0 = md._zero_contact(lam)
        p, d, _ = md.load_curve_maugis_units(np.array([1e-9]), lam)
        assert_allclose([p[0], d[0]], [p0, d0], rtol=1e-6)
        c = md.load_curve_nondimensional(np.array([0.0, 1e-9]), lam / 1.1272516517868267)["c_star"]
        assert_allclose(c[0], c[1], rtol=1e-6)  # the zone radius is continuous at a = 0


def test_paper_units_and_mapping():
    mu = np.array([0.5, 1.0, 5.0])
    st = md.pull_off_nondimensional(1.0, mu)
    _, p, _, _ = md._pull_off_maugis_units(maugis_parameter(mu))
    assert_allclose(st["W_star"], p / 2, rtol=1e-14)


def test_vectorised_and_fast():
    lam = np.geomspace(0.01, 100, 25)
    a, p, d, m = md._pull_off_maugis_units(lam)
    for i in (0, 12, 24):
        assert_allclose(md._pull_off_maugis_units(lam[i])[1], p[i], rtol=1e-12)
    t0 = time.perf_counter()
    md.pull_off_nondimensional(1.0, 1.0)
    assert time.perf_counter() - t0 < 0.2  # loose here; verification/bench_models.py measures <= 20 ms


def test_dimensional():
    r, e, dg, s0 = 1e-6, 1e9, 0.05, 3e8
    mu = s0 * np.cbrt(r / (e * e * dg))
    assert_allclose(md.pull_off_force(r, e, dg, s0), md.pull_off_nondimensional(1.0, mu)["W_star"] * 2 * np.pi * r * dg,
                    rtol=1e-12)
    c = md.load_curve(np.array([1e-8, 3e-8]), r, e, dg, s0)
    assert c.force.shape == (2,) and np.all(np.isfinite(c.approach))


def test_bad_input():
    r, e, dg, s0 = 1e-6, 1e9, 0.05, 3e8
    with pytest.raises(ValueError, match="max_adhesive_stress"):
        md.pull_off(r, e, dg, 0.0)
    with pytest.raises(ValueError, match="contact_radius"):
        md.load_curve(-1e-9, r, e, dg, s0)
    with pytest.raises(ValueError, match="effective_radius"):
        md.load_curve(1e-9, np.nan, e, dg, s0)
    with pytest.raises(ValueError, match="control"):
        md.pull_off(r, e, dg, s0, control="x")
    with pytest.raises(ValueError, match="mu"):
        maugis_parameter(-1.0)


@pytest.mark.parametrize("call, name", [
    (lambda: md.load_curve_nondimensional(-1.0, 1.0), "a_star"),
    (lambda: md.load_curve_nondimensional(1.0, 0.0), "mu"),
    (lambda: md.load_curve_nondimensional(1.0, np.inf), "mu"),
    (lambda: md.load_curve_maugis_units(-1.0, 1.0), "a_maugis"),
    (lambda: md.load_curve_maugis_units(1.0, -1.0), "lam"),
])
def test_public_functions_still_validate(call, name):
    """The internal callers skip the checks (checked=False); a user's call to the public function does not."""
    with pytest.raises(ValueError, match=rf"^{name} must be"):
        call()


def test_unchecked_curve_is_the_checked_curve():
    a = np.array([0.0, 0.3, 1.0, 2.5])
    got, ref = md.load_curve_nondimensional(a, 1.7, checked=False), md.load_curve_nondimensional(a, 1.7)
    assert all(np.array_equal(got[k], ref[k]) for k in ref)

"""Compliant loading and the loading-unloading cycle (dhfield.analysis.spring).

References, all independent of dhfield's curve and search code:

* JKR sphere (Johnson, Kendall & Roberts 1971; paper units, t = sqrt(a*), c = sqrt(2 pi)):
  W* = (4/3 t^6 - 2c t^3)/(2 pi), delta* = t^4 - c t.
  - jump out under a spring K*: dW*/da + K* d(delta*)/da = 0, i.e. the quintic
    4 t^5 + 4 pi K* t^3 - 3c t^2 - pi K* c = 0 (derived here; one positive root);
  - jump in from delta* = 0 at the same machine position: W* + K* delta* = 0, i.e.
    2/(3 pi) t^5 + K* t^3 - (c/pi) t^2 - K* c = 0 (largest positive root);
  - limits: a*^3 = 9 pi/8, W* = -3/4 (load control) and a*^3 = pi/8, W* = -5/12
    (displacement control) for the jump out; a*^3 = 9 pi/2, W* = 0 and a*^3 = 2 pi,
    W* = -2/3 for the jump in;
  - energy lost: -int W* d(delta*) is the polynomial
    (8/15 t^10 - 4/3 c t^7 + c^2/2 t^4)/(2 pi) between the jumps, plus (W_o^2 - W_i^2)/(2K*).
* Maugis-Dugdale (Maugis 1992, the three equations in the physics notes, Sec. 5),
  re-implemented here in Maugis' units with m = c/a as parameter, and the separated
  branch in the same units (derived in test_maugis_dugdale_separated); the jumps by scipy's
  bounded scalar minimiser and brentq, the energy by quad with complex-step derivatives.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, optimize

from dhfield.analysis import spring as compliance
from dhfield.analysis import dimensional as dim
from dhfield.core.transition import maugis_parameter

#: JKR: polynomial roots and the minimum search both to ~1e-12; the issue asks for 1e-6
TOL_JKR = 1e-6
#: MD against the independent parametric solution; the issue asks for 1e-4
TOL_MD = 1e-4
C = math.sqrt(2.0 * math.pi)


# --------------------------------------------------------------------------- JKR closed forms
def _jkr(t):
    return (4.0 / 3.0 * t**6 - 2.0 * C * t**3) / (2.0 * np.pi), t**4 - C * t


def _jkr_energy_prim(t):
    return (8.0 / 15.0 * t**10 - 4.0 / 3.0 * C * t**7 + C**2 / 2.0 * t**4) / (2.0 * np.pi)


def _positive_roots(coef):
    r = np.roots(coef)
    return np.sort(r[(np.abs(r.imag) < 1e-9) & (r.real > 0)].real)


def _jkr_spring(k):
    t_out = _positive_roots([4.0, 0.0, 4.0 * np.pi * k, -3.0 * C, 0.0, -np.pi * k * C])[-1]
    t_in = _positive_roots([2.0 / (3.0 * np.pi), 0.0, k, -C / np.pi, 0.0, -k * C])[-1]
    (w_o, d_o), (w_i, d_i) = _jkr(t_out), _jkr(t_in)
    return {"t_out": t_out, "t_in": t_in, "w_o": w_o, "d_o": d_o, "w_i": w_i, "d_i": d_i,
            "energy": -(_jkr_energy_prim(t_in) - _jkr_energy_prim(t_out)) + (w_o**2 - w_i**2) / (2 * k)}


@pytest.mark.parametrize("k", [1e-3, 0.05, 0.3, 1.0, 3.0, 30.0, 1e3])
def test_jkr_spring_pull_off_matches_the_quintic(k):
    ref = _jkr_spring(k)
    po = compliance.pull_off_under_spring("jkr", mu=10.0, beta0=1.0, machine_stiffness=k)
    assert abs(po["a_star"] - ref["t_out"] ** 2) < TOL_JKR
    assert abs(po["W_star"] - ref["w_o"]) < TOL_JKR
    assert abs(po["delta_star"] - ref["d_o"]) < TOL_JKR
    assert abs(po["separation_delta_star"] - (ref["d_o"] + ref["w_o"] / k)) < TOL_JKR * max(1.0, 1.0 / k)


def test_jkr_spring_pull_off_tends_to_load_and_displacement_control():
    po = compliance.pull_off_under_spring("jkr", mu=10.0, beta0=1.0, machine_stiffness=[0.0, 1e-9, 1e9])
    assert po["W_star"][0] == pytest.approx(-0.75, abs=1e-12)  # K = 0 is load control exactly
    assert po["W_star"][1] == pytest.approx(-0.75, abs=TOL_JKR)  # dW/d(delta) ~ K a*/pi near a_W
    assert po["W_star"][2] == pytest.approx(-5.0 / 12.0, abs=TOL_JKR)  # displacement control
    assert po["a_star"][2] ** 3 == pytest.approx(np.pi / 8.0, abs=TOL_JKR)


@pytest.mark.parametrize("k", [0.05, 0.3, 1.0, 3.0, 30.0])
def test_jkr_cycle_matches_closed_forms(k):
    ref = _jkr_spring(k)
    cyc = compliance.loading_cycle("jkr", mu=10.0, beta0=1.0, machine_stiffness=k)
    assert cyc["jump_in_start_delta_star"] == 0.0
    assert abs(cyc["jump_in_a_star"] - ref["t_in"] ** 2) < TOL_JKR
    assert abs(cyc["jump_in_W_star"] - ref["w_i"]) < TOL_JKR
    assert abs(cyc["jump_in_delta_star"] - ref["d_i"]) < TOL_JKR
    assert abs(cyc["jump_out_W_star"] - ref["w_o"]) < TOL_JKR
    assert abs(cyc["energy_lost_star"] - ref["energy"]) < TOL_JKR
    assert cyc["energy_lost_error_star"] < 1e-9


def test_jkr_cycle_rigid_machine():
    cyc = compliance.loading_cycle("jkr", mu=10.0, beta0=1.0, machine_stiffness=None)
    t_out, t_in = (np.pi / 8.0) ** (1.0 / 6.0), (2.0 * np.pi) ** (1.0 / 6.0)
    assert cyc["machine_stiffness_star"] == math.inf
    assert abs(cyc["jump_out_W_star"] + 5.0 / 12.0) < TOL_JKR
    assert abs(cyc["jump_in_W_star"] + 2.0 / 3.0) < TOL_JKR
    assert abs(cyc["jump_in_delta_star"]) < TOL_JKR
    assert abs(cyc["jump_in_a_star"] ** 3 - 2.0 * np.pi) < TOL_JKR
    assert abs(cyc["separation_delta_star"] - _jkr(t_out)[1]) < TOL_JKR
    assert abs(cyc["max_tension_W_star"] + 0.75) < TOL_JKR
    energy = -(_jkr_energy_prim(t_in) - _jkr_energy_prim(t_out))
    assert abs(cyc["energy_lost_star"] - energy) < TOL_JKR


def test_jkr_cycle_load_control():
    cyc = compliance.loading_cycle("jkr", mu=10.0, beta0=1.0, machine_stiffness=0.0)
    assert abs(cyc["jump_out_W_star"] + 0.75) < TOL_JKR
    assert abs(cyc["jump_in_W_star"]) < TOL_JKR
    assert abs(cyc["jump_in_a_star"] ** 3 - 4.5 * np.pi) < TOL_JKR
    assert cyc["energy_lost_star"] == math.inf  # the spring of zero stiffness releases W^2/(2K)


@settings(max_examples=20, deadline=None)
@given(st.floats(min_value=0.0, max_value=1e4, allow_nan=False, allow_infinity=False))
def test_jkr_spring_invariants(k):
    # over the accepted domain: the jump lies between the two controls, the curve's stiffness is -K
    # there, the landing shares the machine position of the start (Delta = 0), energy >= 0
    cyc = compliance.loading_cycle("jkr", mu=10.0, beta0=1.0, machine_stiffness=k)
    a = cyc["jump_out_a_star"]
    assert (np.pi / 8.0) ** (1 / 3) - 1e-9 <= a <= (9.0 * np.pi / 8.0) ** (1 / 3) + 1e-9
    assert -0.75 - 1e-12 <= cyc["jump_out_W_star"] <= -5.0 / 12.0 + 1e-9
    t = math.sqrt(a)
    dw = (4.0 * a * a - 3.0 * C * t) / (2.0 * np.pi)
    dd = 2.0 * a - 0.5 * C / t
    assert abs(dw + k * dd) < 1e-6 * (1.0 + k)
    assert abs(cyc["jump_in_W_star"] + k * cyc["jump_in_delta_star"]) < 1e-9 * (1.0 + k)
    assert cyc["energy_lost_star"] > 0


# --------------------------------------------------------------------------- MD, independent reference
_D_UNIT = (9.0 * np.pi**2 / 16.0) ** (1.0 / 3.0)  # delta* per Maugis D
_A_UNIT = (3.0 * np.pi / 4.0) ** (1.0 / 3.0)  # a* per Maugis A


def _md_contact(log_mm, lam):
    """W*, delta*, a* of the MD equations (Maugis 1992) at M = sqrt(m^2 - 1) = exp(log_mm)."""
    mm = np.exp(log_mm)
    m2 = 1.0 + mm * mm
    q2 = 0.5 * lam * (mm + (m2 - 2.0) * np.arctan(mm))  # first equation: q2 A^2 + q1 A = 1
    q1 = 4.0 / 3.0 * lam**2 * (mm * np.arctan(mm) - np.sqrt(m2) + 1.0)
    a = 2.0 / (q1 + np.sqrt(q1 * q1 + 4.0 * q2))
    p = a**3 - lam * a * a * (mm + m2 * np.arctan(mm))
    d = a * a - 4.0 / 3.0 * a * lam * mm
    return 0.5 * p, d * _D_UNIT, a * _A_UNIT


def _md_separated(x, lam):
    """W*, delta* of the separated sphere, x = Dugdale-zone radius in Maugis units."""
    return -lam * np.pi * x**2 / 4.0, (x**2 / 2.0 - 8.0 * lam * x / (3.0 * np.pi) - 2.0 / (np.pi * lam)) * _D_UNIT


class _MDReference:
    """One curve parameter u: u < 0 the separated branch (x = x_end + u), u >= 0 the contact branch
    with ln M = U_MAX - u (high load at large u)."""

    U_MAX = 12.0

    def __init__(self, mu):
        self.mu, self.lam = mu, maugis_parameter(mu)
        qa, qb = self.lam * np.pi / 4.0, 4.0 / 3.0 * self.lam**2 * (np.pi / 2.0 - 1.0)
        self.x_end = (-qb + math.sqrt(qb * qb + 4.0 * qa)) / (2.0 * qa)

    def state(self, u):
        if u < 0:
            return _md_separated(self.x_end + u, self.lam)
        w, d, _ = _md_contact(self.U_MAX - u, self.lam)
        return w, d

    def deriv(self, u, h=1e-30):
        # complex step on each branch (both analytic there)
        if u < 0:
            w, d = _md_separated(self.x_end + u + 1j * h, self.lam)
        else:
            w, d, _ = _md_contact(self.U_MAX - (u + 1j * h), self.lam)
        return w.imag / h, d.imag / h

    def cycle(self, k):
        s = 1.0 if k is None else k / (1.0 + k)

        def f(u):
            w, d = self.state(u)
            return s * d + (1.0 - s) * w

        # first minimum from high load: scan u downwards, then bounded minimisation around it
        grid = np.concatenate([np.linspace(self.U_MAX + 8.0, 0.0, 2001)[:-1], np.linspace(0.0, -self.x_end, 400)])
        vals = np.array([f(u) for u in grid])
        i = next(j for j in range(1, grid.size) if vals[j] > vals[j - 1]) - 1 if np.any(np.diff(vals) > 0) \
            else grid.size - 1
        lo, hi = grid[min(i + 1, grid.size - 1)], grid[max(i - 1, 0)]
        if i == grid.size - 1:
            u_out = grid[-1]
        else:
            u_out = optimize.minimize_scalar(f, bounds=(lo, hi), method="bounded",
                                             options=dict(xatol=1e-13)).x
        f_start = s * (-1.0 / self.mu)
        if f(u_out) >= f_start:
            u_in = u_out
        else:
            top = u_out + 1.0
            while f(top) < f_start:
                top += 1.0
            u_in = optimize.brentq(lambda u: f(u) - f_start, u_out, top, xtol=1e-14)
        w_o, d_o = self.state(u_out)
        w_i, d_i = self.state(u_in)

        def integrand(u):
            w, _ = self.state(u)
            return w * self.deriv(u)[1]

        pts = [p for p in (0.0,) if u_out < p < u_in]
        integral = integrate.quad(integrand, u_out, u_in, points=pts or None, epsabs=1e-13, epsrel=1e-12,
                                  limit=200)[0]
        spring = 0.0 if k is None else (w_o**2 - w_i**2) / (2.0 * k)
        return {"w_o": w_o, "d_o": d_o, "w_i": w_i, "d_i": d_i, "energy": -integral + spring}


@pytest.mark.parametrize("mu", [0.3, 1.0, 3.0])
@pytest.mark.parametrize("k", [None, 0.3, 3.0])
def test_md_cycle_matches_maugis(mu, k):
    ref = _MDReference(mu).cycle(k)
    cyc = compliance.loading_cycle("md", mu=mu, beta0=1.0, machine_stiffness=k)
    assert abs(cyc["jump_out_W_star"] - ref["w_o"]) < TOL_MD
    assert abs(cyc["jump_out_delta_star"] - ref["d_o"]) < TOL_MD
    assert abs(cyc["jump_in_W_star"] - ref["w_i"]) < TOL_MD
    assert abs(cyc["jump_in_delta_star"] - ref["d_i"]) < TOL_MD
    assert abs(cyc["energy_lost_star"] - ref["energy"]) < TOL_MD
    assert cyc["jump_in_start_delta_star"] == pytest.approx(-1.0 / mu, rel=1e-15)


def test_md_stiff_machine_small_lambda_jumps_on_the_separated_branch():
    # lambda = 0.34: the minimum of delta lies out of contact, at c* = 4 mu/pi (d(delta*)/dc = 0)
    mu = 0.3
    po = compliance.pull_off_under_spring("md", mu=mu, beta0=1.0, machine_stiffness=1e9)
    assert po["on_separated_branch"] and po["at_zero_contact"]
    c = 4.0 * mu / np.pi
    assert po["c_star"] == pytest.approx(c, abs=1e-6)
    assert po["W_star"] == pytest.approx(-mu * c * c / 2.0, abs=1e-6)


# --------------------------------------------------------------------------- other models, SI, validation
@pytest.mark.parametrize("model, beta0", [("dh-circular", 1.0), ("jkr-elliptic", 0.8), ("dh-elliptic", 0.9),
                                          ("dmt", 1.0)])
def test_other_models_between_the_two_controls(model, beta0):
    from dhfield.analysis import compare

    mu = 2.0
    w_load = float(compare.pull_off(model, mu=mu, beta0=beta0, control="load", check_closure=False)["W_star"])
    w_disp = float(compare.pull_off(model, mu=mu, beta0=beta0, control="displacement", check_closure=False)["W_star"])
    po = compliance.pull_off_under_spring(model, mu=mu, beta0=beta0, machine_stiffness=[0.0, 0.1, 1.0, 1e9])
    w = po["W_star"]
    assert w[0] == pytest.approx(w_load, abs=1e-9)
    assert w[-1] == pytest.approx(w_disp, abs=1e-5)
    assert np.all(np.diff(w) >= -1e-9)  # a stiffer machine holds on to a less tensile load
    cyc = compliance.loading_cycle(model, mu=mu, beta0=beta0, machine_stiffness=1.0)
    assert cyc["energy_lost_star"] >= 0 and cyc["energy_lost_error_star"] < 1e-8
    if model in ("dh-circular", "dh-elliptic", "dmt"):
        assert "no force out of contact" in cyc["warning"]


def test_si_wrappers_scale_back():
    params = dim.contact_parameters(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, np.radians(90.0), 0.05, 3e5)
    k_si = 200.0
    k_star = compliance.stiffness_star(k_si, params.effective_radius, params.reduced_modulus,
                                       params.work_of_adhesion)
    # K* = K (c_r^2/R)/(2 pi R dgamma), Eqs. (33)-(34)
    assert k_star == pytest.approx(k_si * params.approach_unit / (2 * np.pi * params.effective_radius * 0.05),
                                   rel=1e-14)
    rec = compliance.pull_off_force_under_spring(params, k_si, model="jkr")
    nd = compliance.pull_off_under_spring("jkr", mu=params.mu, beta0=params.beta0, machine_stiffness=k_star)
    assert rec["control"] == "spring"
    assert rec["force"] == pytest.approx(nd["W_star"] * 2 * np.pi * params.effective_radius * 0.05, rel=1e-12)
    cyc = compliance.loading_cycle_si(params, k_si, model="jkr")
    unit = 2 * np.pi * params.effective_radius * 0.05 * params.approach_unit
    assert cyc["energy_lost"] == pytest.approx(cyc["energy_lost_star"] * unit, rel=1e-12)
    assert cyc["machine_stiffness"] == k_si


@pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf, "stiff"])
def test_bad_stiffness_is_named(bad):
    with pytest.raises(ValueError, match="machine_stiffness"):
        compliance.pull_off_under_spring("jkr", mu=1.0, beta0=1.0, machine_stiffness=bad)
    with pytest.raises(ValueError, match="machine_stiffness"):
        compliance.loading_cycle("jkr", mu=1.0, beta0=1.0, machine_stiffness=bad)


def test_model_without_a_curve_is_refused():
    with pytest.raises(ValueError, match="load curve"):
        compliance.loading_cycle("dh-elliptic-jkr-beta", mu=1.0, beta0=0.9, machine_stiffness=1.0)


def test_machine_displacement_of_a_vanishing_stiffness_is_a_named_error():
    """Hostile run (issue 18): K = 1e-308 gave W/K = inf in the curve's machine_displacement."""
    curve = {"W_star": np.array([-5.0, 5.0]), "delta_star": np.array([0.1, 0.2])}  # 5/1e-308 > max float
    with pytest.raises(ValueError, match="machine_stiffness.*too small"):
        compliance.add_machine_displacement(curve, 1e-308)
    assert np.all(np.isfinite(compliance.add_machine_displacement(curve, 1e-3)["machine_displacement"]))


@pytest.mark.parametrize("call", [lambda: compliance.pull_off_under_spring("md", 1.0, 1.0, 1.0),
                                  lambda: compliance.spring_pull_off_record("md", 1.0, 1.0, 1.0),
                                  lambda: compliance.loading_cycle("md", 1.0, 1.0),
                                  lambda: compliance.cycle_path("md", 1.0, 1.0)])
def test_beta0_and_mu_are_keyword_only(call):
    """(beta0, mu) is GRID_DIMS' order, (mu, beta0) was the old one: a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_spring_records_are_typed_with_the_old_keys():
    """pull_off_under_spring -> the one records.PullOff with its spring group (issue 16), and
    spring_pull_off_record -> records.PullOff (control 'spring') with the nondimensional keys only,
    so the CLI's JSON is unchanged."""
    from dhfield.core.records import PullOff
    from dhfield.core.schema import PULL_OFF_KEYS, PULL_OFF_SPRING_KEYS

    po = compliance.pull_off_under_spring("jkr", beta0=1.0, mu=10.0, machine_stiffness=[0.0, 1.0])
    assert type(po) is PullOff and tuple(po) == PULL_OFF_KEYS + PULL_OFF_SPRING_KEYS and "_t" not in po
    assert po.groups == ("spring",) and po.control == "spring" and po.model == "jkr"
    assert po.W_star is po["W_star"] and np.shape(po.W_star) == (2,) and np.shape(po.beta0) == (2,)
    rec = compliance.spring_pull_off_record("jkr", beta0=1.0, mu=10.0, machine_stiffness=1.0)
    assert type(rec) is PullOff and tuple(rec) == PULL_OFF_KEYS and rec.control == "spring"
    assert rec.W_star == float(po.W_star[1]) and not rec.at_zero_contact

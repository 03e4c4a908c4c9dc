"""The semismooth Newton adhesive solve (dhfield.bem.newton): its Jacobian, its merit, and the sphere against MD."""
import math

import numpy as np
import pytest

from dhfield.models import maugis_dugdale
from dhfield.analysis.bem_start import predicted_problem
from dhfield.bem import newton


@pytest.fixture(scope="module")
def sphere():
    """The paper's sphere (beta0 = 1) at mu = 1 on 128^2 cells, with its analytic start."""
    P = predicted_problem(beta0=1.0, mu=1.0, n=128)
    prob = P.adhesive_problem(threads=1)
    q0 = newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)
    return P, prob, q0


def test_jacobian_matches_finite_differences(sphere):
    # the Newton rows are the exact derivative of F = min(c h, p) away from its kinks: a central
    # difference with step 1e-6 agrees to ~1e-6 relative (F is piecewise linear in q there)
    P, prob, q0 = sphere
    law = newton._Law(prob.law, prob.min_spread)
    c = law.sigma0 / law.h0
    h, p = newton._state(prob, law, P.pull_off_approach, q0)
    contact = c * h < p
    slope = law.slope(h)
    v = np.random.default_rng(0).standard_normal(q0.shape)
    eps = 1e-6
    hp, pp = newton._state(prob, law, P.pull_off_approach, q0 + eps * v)
    hm, pm = newton._state(prob, law, P.pull_off_approach, q0 - eps * v)
    fd = (newton._residual(hp, pp, c) - newton._residual(hm, pm, c)) / (2 * eps)
    kv = prob.op(v)
    exact = np.where(contact, c * kv, v - slope * kv)
    # cells within eps of a kink (c h = p, or the ramp's ends) take the other branch: few
    off = np.abs(fd - exact) > 1e-4 * (1.0 + np.abs(exact))
    assert off.sum() <= 0.001 * off.size


def test_state_converges_with_decreasing_merit(sphere):
    P, prob, q0 = sphere
    st = newton.solve_state(prob, P.pull_off_approach, q0)
    assert st.converged and st.reason == newton.CONVERGED
    assert st.residual <= newton.SolverOptions().tol
    # every accepted step decreased the merit ||F|| (the line search's guarantee)
    assert all(b < a for a, b in zip(st.merit_history, st.merit_history[1:]))
    # the state satisfies the complementarity system: no overlap, no tensile contact pressure
    assert st.gap.min() >= -1e-8 * prob.law.range


def test_sphere_pull_off_within_grid_error_of_maugis_dugdale(sphere):
    # MD's load-control pull-off is exact for the Dugdale sphere; at 128^2 cells the ramped edge and
    # the lattice leave ~0.1 %, so 0.5 % bounds it with margin while still failing a wrong law or scale
    P, prob, q0 = sphere
    res = newton.load_minimum(prob, P.pull_off_approach, q0, half_window=0.5 * P.approach_step, method="smoothed")
    assert res.converged
    w_star = res.load * P.sin_skew / (2 * math.pi)          # Eq. (34)
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 1.0, control="load").W_star)
    assert abs(w_star / md - 1) < 5e-3


def test_load_slope_matches_neighbouring_states(sphere):
    # dW/d delta from the Jacobian against a central difference of two solved states; W(delta) is
    # piecewise smooth (its kinks are cells entering or leaving the law's ramp or the contact), so the
    # step is kept far below the kinks' spacing (~1e-3 here): agreement to the difference's O(eps^2)
    P, prob, q0 = sphere
    d = P.pull_off_approach + 0.3
    st = newton.solve_state(prob, d, q0)
    slope, _ = newton.load_slope(prob, st)
    eps = 1e-6
    up = newton.solve_state(prob, d + eps, st.traction)
    dn = newton.solve_state(prob, d - eps, st.traction)
    assert slope == pytest.approx((up.load - dn.load) / (2 * eps), rel=1e-3)


def test_smoothed_solve_converges_on_a_slender_contact_from_the_analytic_start():
    # 20 degrees (beta0 = 0.108) at mu = 1: the plain active-set iteration stalls from the analytic
    # start (its line search fails); the smoothing Newton follows the smoothed systems to the exact one
    from dhfield.analysis.bem_start import nondimensional_problem

    P = nondimensional_problem(beta0=0.108, mu=1.0, n=256, ny=64)
    prob = P.adhesive_problem(threads=1)
    q0 = newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)
    st = newton.solve_state_smoothed(prob, P.pull_off_approach, q0)
    assert st.converged and st.residual <= newton.SolverOptions().tol
    assert st.gap.min() >= -1e-8 * prob.law.range


def test_ramp_potential_is_the_integral_of_the_law():
    # phi' = sigma_w (the law is the potential's derivative) and phi(0) = -sigma0 h0 (the work of
    # adhesion is kept by the symmetric ramp), checked by central differences on both sides of every kink
    from dhfield.bem.energy import RampPotential
    from dhfield.bem.laws import DugdaleLaw

    law = DugdaleLaw(max_stress=3.0, range=0.5)
    pot = RampPotential(law, 0.4, penalty_stiffness=50.0)
    h = np.linspace(-0.2, 1.2, 1401) + 1e-4
    eps = 1e-6
    fd = (pot.phi(h + eps) - pot.phi(h - eps)) / (2 * eps)
    grad = pot.gradient(np.zeros_like(h), h)            # q = 0: phi'(h)
    assert np.allclose(fd, grad, atol=1e-6)
    assert float(pot.phi(np.array(0.0))) == pytest.approx(-3.0 * 0.5, rel=1e-12)
    assert float(pot.phi(np.array(1.0))) == 0.0


def test_energy_solve_decreases_the_energy_and_matches_the_active_set_state(sphere):
    # the energy phase decreases Pi at every step; with the polish the state is the semismooth Newton's
    # exact state (same complementarity system, tolerance 1e-8): loads agree to ~1e-8 relative
    from dhfield.bem import energy

    P, prob, q0 = sphere
    a = energy.solve_state_energy(prob, P.pull_off_approach, q0, stages=1)
    assert a.reason == "stage_converged"
    assert all(b <= e for e, b in zip(a.merit_history, a.merit_history[1:]))
    st = energy.solve_state_hybrid(prob, P.pull_off_approach, q0)
    ref = newton.solve_state(prob, P.pull_off_approach, q0)
    assert st.converged and ref.converged
    assert st.load == pytest.approx(ref.load, rel=1e-6)


def test_slope_zero_search_on_the_sphere_against_maugis_dugdale(sphere):
    # MD's load-control pull-off is exact for the Dugdale sphere; at 128^2 cells the ramped edge and the
    # lattice leave ~0.1 % (the Newton test above), so 0.5 % bounds it while failing a wrong law or scale
    from dhfield.bem import energy

    P, prob, q0 = sphere
    res = energy.pull_off_search(prob, P.pull_off_approach, q0, step=0.5 * P.approach_step)
    assert res.converged
    assert np.all(np.isfinite(res.slopes))
    w_star = res.load * P.sin_skew / (2 * math.pi)
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 1.0, control="load").W_star)
    assert abs(w_star / md - 1) < 5e-3


def test_nested_solve_reaches_the_single_grid_state():
    # the sphere at mu = 1 on 64^2 cells solved on 16^2 and 32^2 first (same domain, the traction prolonged):
    # the finest level starts near its state and needs only a few Newton steps, and it lands on the same
    # discrete state as the single-grid solve from the analytic start (loads within the tolerance's reach)
    P = predicted_problem(beta0=1.0, mu=1.0, n=64)
    ladder = newton.grid_ladder(P, 3, threads=1)
    assert [p.grid.shape for p in ladder] == [(16, 16), (32, 32), (64, 64)]
    nested = newton.solve_state_nested(ladder, P.pull_off_approach,
                                       newton.cold_start(ladder[0], P.pull_off_approach, P.pull_off_zone))
    single = newton.solve_state(ladder[-1], P.pull_off_approach,
                                newton.cold_start(ladder[-1], P.pull_off_approach, P.pull_off_zone))
    assert nested.converged and single.converged
    assert [r.shape for r in nested.levels] == [(16, 16), (32, 32), (64, 64)]
    assert nested.levels[-1].newton_iterations <= 8
    assert nested.state.load == pytest.approx(single.load, rel=1e-7)
    assert np.array_equal(nested.state.contact, single.contact)


def test_prolongation_keeps_linear_fields_and_the_mean():
    # cell-centred bilinear prolongation (weights 3/4, 1/4): a linear field stays linear inside the domain,
    # and every coarse cell's four children average to the coarse value away from the outer edge
    x = np.arange(6.0)[:, None] + 0.5
    y = 2.0 * np.arange(4.0)[None, :] + 1.0
    f = newton.prolong(x + y)
    xf = (np.arange(12.0)[:, None] + 0.5) / 2.0
    yf = 2.0 * (np.arange(8.0)[None, :] + 0.5) / 2.0
    assert np.allclose(f[1:-1, 1:-1], (xf + yf)[1:-1, 1:-1])
    c = f.reshape(6, 2, 4, 2).mean(axis=(1, 3))
    assert np.allclose(c[1:-1, 1:-1], (x + y)[1:-1, 1:-1])


def test_fgmres_with_a_fixed_preconditioner_solves_the_system():
    # flexible GMRES with a fixed preconditioner is right-preconditioned GMRES, restarts included
    rng = np.random.default_rng(3)
    A = np.eye(60) * 4.0 + rng.standard_normal((60, 60)) * 0.3
    b = rng.standard_normal(60)
    d = 1.0 / np.diag(A)
    hist = []
    x, its, info = newton.fgmres(lambda v: A @ v, lambda v: d * v, b, 1e-10, 500, restart=7, history=hist)
    assert info == 0 and its == len(hist)
    assert np.linalg.norm(A @ x - b) <= 1e-9 * np.linalg.norm(b)


def test_inner_cg_contact_preconditioner_reaches_the_same_state(sphere):
    # SolverOptions.contact_inner (CG on K_AA inside a flexible GMRES) changes the path, not the state
    P, prob, q0 = sphere
    ref = newton.solve_state(prob, P.pull_off_approach, q0)
    st = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(contact_inner=3))
    assert ref.converged and st.converged
    assert np.array_equal(st.contact, ref.contact)
    assert st.load == pytest.approx(ref.load, rel=1e-7)


def test_floored_symbol_reaches_the_same_state(sphere):
    # SolverOptions.symbol_floor changes the contact rows' preconditioner, not the state
    P, prob, q0 = sphere
    ref = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(symbol_floor=False))
    st = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(symbol_floor=True))
    assert ref.converged and st.converged
    assert np.array_equal(st.contact, ref.contact)
    assert st.load == pytest.approx(ref.load, rel=1e-7)


def test_floored_symbol_is_positive_on_oblong_cells():
    # on cells that are not square the truncated kernel's spectrum dips below zero; the floored
    # inverse symbol is then bounded (a field of the zero-x-frequency line is not amplified ~1e12)
    P = predicted_problem(beta0=0.4826, mu=10.0, n=320)
    prob = P.adhesive_problem(threads=1)
    assert prob.grid.dx != pytest.approx(prob.grid.dy, rel=0.1)
    v = np.zeros(prob.z.shape)
    v[0, :] = np.cos(np.pi * (np.arange(v.shape[1]) + 0.5) * 0.95)     # high frequency along y only
    plain = newton.symbol_preconditioner(prob.grid, prob.symmetric, floor=False)(v)
    floored = newton.symbol_preconditioner(prob.grid, prob.symmetric, floor=True)(v)
    assert np.abs(floored).max() < 1e-3 * np.abs(plain).max()


def _slender_start(beta0, mu, n, ny):
    from dhfield.analysis.bem_start import nondimensional_problem

    P = nondimensional_problem(beta0=beta0, mu=mu, n=n, ny=ny)
    prob = P.adhesive_problem(threads=1)
    return P, prob, newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)


def test_watchdog_reaches_the_monotone_iterations_state():
    # beta0 = 0.3, mu = 5 on 400 x 180 from the analytic start: the merit rises on two steps of the
    # non-monotone iteration; with the watchdog the same state (load, contact cells)
    P = predicted_problem(beta0=0.3, mu=5.0, n=400, ny=180)
    prob = P.adhesive_problem(threads=1)
    q0 = newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)
    plain = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(nonmonotone=4))
    wd = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(nonmonotone=4, watchdog=4))
    assert plain.converged and wd.converged
    assert wd.load == pytest.approx(plain.load, rel=1e-9)
    assert np.array_equal(wd.contact, plain.contact)


@pytest.mark.parametrize("watchdog", [2, 4])
def test_watchdog_best_merit_falls_in_every_window(watchdog):
    # 20 deg (beta0 = 0.108), mu = 1, one 256 x 64 grid from the analytic start: the full steps raise the
    # merit on most iterations, yet the best merit so far falls at least once in every watchdog + 1
    # accepted steps (else the iteration returns to the best iterate and takes a merit-decreasing step)
    P, prob, q0 = _slender_start(0.108, 1.0, 256, 64)
    wd = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(watchdog=watchdog, max_newton=40))
    h = np.asarray(wd.merit_history)
    assert np.count_nonzero(np.diff(h) > 0) >= 5           # the watchdog's full steps were taken
    best = np.minimum.accumulate(h)
    for k in range(len(best) - watchdog - 1):
        assert best[k + watchdog + 1] < best[k]
    # an unconverged state is returned at its best iterate
    assert wd.converged or float(np.linalg.norm(newton._residual(wd.gap, wd.traction + newton._Law(
        prob.law, prob.min_spread).stress(wd.gap), prob.law.max_stress / prob.law.range))) == pytest.approx(
        best[-1], rel=1e-9)


def test_watchdog_off_is_the_monotone_iteration():
    P = predicted_problem(beta0=1.0, mu=1.0, n=64)
    prob = P.adhesive_problem(threads=1)
    q0 = newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)
    a = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions())
    b = newton.solve_state(prob, P.pull_off_approach, q0, newton.SolverOptions(watchdog=0))
    assert a.merit_history == b.merit_history and a.load == b.load

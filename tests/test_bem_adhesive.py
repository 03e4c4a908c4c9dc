"""End-to-end tests of the adhesive BEM (dhfield.bem and dhfield.analysis.bem_start, the public names): limits and identities.

The parts are tested in tests/test_bem_solver.py (one state), tests/test_bem_path.py
(paths, the displacement-control fold) and tests/test_bem_pull_off.py (the paper's
problem, the located search).

Reference values are closed forms (Hertz, :mod:`dhfield.models.hertz`), the Maugis-Dugdale
sphere (:mod:`dhfield.models.maugis_dugdale`, Maugis 1992, with lambda = 1.1272 mu of
:mod:`dhfield.core.transition`), the DMT force 2 pi dgamma sqrt(R'R'') and elliptical JKR
(:mod:`dhfield.models.jkr_elliptic`, Johnson & Greenwood 2005).  Grids are small (N <= 96)
to keep the module fast; the accuracy at N = 256-1024 is printed by
verification/convergence_adhesive.py.
"""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.models import hertz, jkr_elliptic, maugis_dugdale
from dhfield.core import transition
from dhfield.analysis.bem_start import AdhesiveOptions
from dhfield.bem import Grid, adhesive_pull_off, solve_adhesive
from dhfield.bem import nondimensional_problem, richardson_extrapolation
from dhfield.core.geometry import radius_ratio, sin_skew_angle

#: Hertz on 64^2 cells over 1.25 a: semi-axes from the second moments of the pixel
#: contact are O(h) (h = a/25.6: 4 % of a would be 1 cell); measured 0.3-0.8 %.
RTOL_HERTZ_AXES_64 = 0.015
#: Peak pressure and load at 64^2: cell-averaged field, O(h^2) (measured < 3e-4).
RTOL_HERTZ_PRESSURE_64 = 2e-3
#: BEM sphere pull-off vs MD at N = 64, lambda = 1: the sub-cell edge keeps the error
#: well below the 1 % required at N = 256 (measured 0.1 % at N = 128).
RTOL_MD_64 = 0.01
#: DMT limit at mu = 0.08 (lambda = 0.09): MD itself is 2.5 % above DMT there
#: (P = -1.95 pi R dgamma at lambda = 0.1), so 5 % bounds the BEM against DMT.
RTOL_DMT = 0.05
#: JKR limit at mu = 2.5 (lambda = 2.8): MD is ~1.2 % from JKR there (P = -1.517 vs -1.5
#: pi R dgamma at lambda = 3, Johnson & Greenwood 1997); the BEM at N = 96-128 is within
#: 0.2-0.7 % of MD at lambda = 3 (verification/convergence_adhesive.py): 3 % bounds both.
RTOL_JKR = 0.03


def _hertz_problem(beta, n):
    rho = float(radius_ratio(beta))
    r1, r2 = np.sqrt(rho), 1.0 / np.sqrt(rho)
    a = 1.0
    grid = Grid.centered(n, 1.25 * a, half_width_y=1.25 * beta * a)
    x, y = grid.mesh()
    z = x * x / (2 * r1) + y * y / (2 * r2)
    return grid, z, float(hertz.approach(a, beta))


@pytest.mark.parametrize("beta", [1.0, 0.6])
def test_no_adhesion_is_elliptical_hertz(beta):
    grid, z, delta = _hertz_problem(beta, 64)
    st = solve_adhesive(z, grid, delta, None, tol=1e-10)
    assert st.converged
    a, b = st.contact_semi_axes()
    assert a == pytest.approx(1.0, rel=RTOL_HERTZ_AXES_64)
    assert b == pytest.approx(beta, rel=RTOL_HERTZ_AXES_64)
    assert st.peak_pressure == pytest.approx(float(hertz.max_pressure(1.0, beta)), rel=RTOL_HERTZ_PRESSURE_64)
    assert st.load == pytest.approx(float(hertz.load(1.0, beta)), rel=RTOL_HERTZ_PRESSURE_64)
    assert np.all(st.gap >= -1e-9 * delta)
    assert np.all(st.cohesive == 0.0)


def test_dugdale_sphere_pull_off_matches_maugis_dugdale():
    lam = 1.0
    mu = float(transition.tabor_from_maugis(lam))
    res = adhesive_pull_off(mu=mu, beta0=1.0, n=64, progress=False)
    ref = maugis_dugdale.pull_off_nondimensional(1.0, mu)  # Maugis (1992) in the paper's units
    assert res.converged
    assert res.W_star == pytest.approx(float(ref["W_star"]), rel=RTOL_MD_64)
    assert res.ellipticity == pytest.approx(1.0, abs=1e-12)   # the symmetric sphere stays round
    assert res.c_star > res.a_star > 0


def test_small_mu_tends_to_dmt_force():
    beta0 = 0.8
    res = adhesive_pull_off(mu=0.08, beta0=beta0, n=48, progress=False)
    # DMT: W = -2 pi dgamma sqrt(R'R'') = -2 pi (R = 1): W* = -sin(theta_skew), Eq. (34)
    assert res.W_star == pytest.approx(-float(sin_skew_angle(beta0)), rel=RTOL_DMT)
    assert res.converged


def test_large_mu_tends_to_elliptical_jkr():
    beta0 = 0.8
    ref = float(jkr_elliptic.pull_off_nondimensional(np.asarray(beta0), 1.0)["W_star"])
    near = adhesive_pull_off(mu=2.5, beta0=beta0, n=96, progress=False)
    far = adhesive_pull_off(mu=1.0, beta0=beta0, n=64, progress=False)
    assert near.resolved and near.converged
    assert near.W_star == pytest.approx(ref, rel=RTOL_JKR)
    # the approach to JKR: much closer at mu = 2.5 than at mu = 1
    assert abs(near.W_star - ref) < 0.5 * abs(far.W_star - ref)


def test_under_resolved_grid_is_flagged():
    res = nondimensional_problem(mu=6.0, beta0=1.0, n=32)
    flagged = adhesive_pull_off(mu=6.0, beta0=1.0, n=32, progress=False, options=AdhesiveOptions(n_steps=4, refine_levels=0, max_iter=50))
    assert res.grid.nx == 32
    assert not flagged.resolved
    assert not flagged.converged and len(flagged.failures) > 0   # flagged, not dropped


def test_bad_input_names_the_parameter():
    grid = Grid.centered(16, 1.0)
    z = np.zeros(grid.shape)
    with pytest.raises(ValueError, match="initial_gap"):
        solve_adhesive(np.zeros((4, 4)), grid, 0.1, None)
    with pytest.raises(ValueError, match="law"):
        solve_adhesive(z, grid, 0.1, "dugdale")
    with pytest.raises(ValueError, match="approach"):
        solve_adhesive(z, grid, float("nan"), None)
    with pytest.raises(ValueError, match="beta0"):
        nondimensional_problem(mu=1.0, beta0=1.5, n=64)
    with pytest.raises(ValueError, match="n must be an even integer"):
        nondimensional_problem(mu=1.0, beta0=0.5, n=63)
    with pytest.raises(ValueError, match="control"):
        adhesive_pull_off(mu=1.0, beta0=1.0, n=16, control="force")


def test_richardson_extrapolation_recovers_power_law():
    n = [64, 128, 256]
    f = [2.0 + 3.0 * k ** -1.5 for k in n]
    val, order = richardson_extrapolation(n, f)
    assert val == pytest.approx(2.0, rel=1e-12)
    assert order == pytest.approx(1.5, rel=1e-12)


# ============================================================================ coarse to fine
#: States solved at the same approach by the full path and by the coarse-to-fine window are
#: the same discrete equilibrium: they agree to the solver tolerance (1e-6 on the zone
#: fraction and on the gap relative to h0; measured 1e-7 relative at N = 256).
RTOL_SAME_STATE = 1e-5
#: When the window of the coarse-to-fine route holds the full marching path's three finest
#: samples (lambda = 1, 64 -> 128: it does), both take the parabola through the same states.
RTOL_REFINE_VS_FULL = 1e-5


def test_coarse_to_fine_equals_the_full_path():
    from dhfield.bem import refine_pull_off

    mu = float(transition.tabor_from_maugis(1.0))
    coarse = adhesive_pull_off(mu=mu, beta0=1.0, n=64, progress=False, search="march")
    fine = refine_pull_off(coarse, 128)
    full = adhesive_pull_off(mu=mu, beta0=1.0, n=128, progress=False, search="march")
    assert fine.converged and full.converged
    assert fine.n == 128 and fine.n_steps < full.n_steps / 2          # only the window is solved
    assert fine.W_star == pytest.approx(full.W_star, rel=RTOL_REFINE_VS_FULL)
    loads = {round(d, 9): w for d, w in zip(full.path.approach, full.path.load)}
    common = [(w, loads[round(d, 9)]) for d, w in zip(fine.path.approach, fine.path.load) if round(d, 9) in loads]
    assert len(common) >= 2                                           # the same approach lattice
    for w_fine, w_full in common:
        assert w_fine == pytest.approx(w_full, rel=RTOL_SAME_STATE)


def test_refine_pull_off_rejects_bad_input():
    from dhfield.bem import refine_pull_off

    coarse = adhesive_pull_off(mu=1.0, beta0=1.0, n=16, progress=False, options=AdhesiveOptions(n_steps=4, refine_levels=0))
    with pytest.raises(ValueError, match="n must be an integer > coarse.n"):
        refine_pull_off(coarse, 16)
    with pytest.raises(ValueError, match="coarse must be a BEM pull-off"):
        refine_pull_off(coarse.path, 32)
    with pytest.raises(ValueError, match="window"):
        refine_pull_off(coarse, 32, window=0)


# ============================================================================ bracket search, nested warm starts
#: The discrete load W(delta) of a path is jagged at N <= 64 (contact cells switch one by one):
#: up to ~7e-4 relative between neighbouring samples (measured, lambda = 3, N = 48; with the
#: Newton solve's ramped Dugdale edge the two routes below differ by 9e-4 and 1.2e-3).  The
#: bracket search and the marching path take the parabola around their lowest samples, which
#: are different samples: they agree to about twice that jaggedness.
RTOL_BRACKET_VS_MARCH = 2e-3
#: The same discrete equilibrium reached by a cold start and by warm starts along the path
#: agrees to the solver tolerance (1e-6 on the zone fraction and on the gap / h0).
RTOL_COLD_VS_WARM = 1e-5


@pytest.mark.parametrize("mu, beta0, n", [(float(transition.tabor_from_maugis(1.0)), 1.0, 64), (1.0, 0.5, 48)])
def test_bracket_search_equals_the_marching_path_with_a_fifth_of_the_states(mu, beta0, n):
    new = adhesive_pull_off(mu=mu, beta0=beta0, n=n, progress=False, search="bracket")
    old = adhesive_pull_off(mu=mu, beta0=beta0, n=n, progress=False, search="march")
    assert new.converged and old.converged
    assert (new.search, old.search) == ("bracket", "march")
    assert new.W_star == pytest.approx(old.W_star, rel=RTOL_BRACKET_VS_MARCH)
    assert new.n_steps <= old.n_steps / 5
    assert set(new.path.phase) <= {"unloading", "refine"}      # no loading, nothing past the bracket
    # the reported minimum is interior: samples on both sides of it
    assert new.path.approach.min() < new.delta_star < new.path.approach.max()


def test_bracket_search_rejects_bad_input():
    from dhfield.bem import unloading_path

    prob = nondimensional_problem(mu=1.0, beta0=1.0, n=16)
    args = (prob.initial_gap, prob.grid, prob.law, prob.approach_max, prob.approach_step)
    with pytest.raises(ValueError, match="approach_guess"):
        unloading_path(*args, approach_guess=float("nan"))
    with pytest.raises(ValueError, match="start_stress"):
        unloading_path(*args, approach_guess=-0.5, start_stress=np.zeros((4, 4)))
    with pytest.raises(ValueError, match="search"):
        adhesive_pull_off(mu=1.0, beta0=1.0, n=16, search="gauss")


def test_nested_warm_starts_reach_the_same_states():
    mu = float(transition.tabor_from_maugis(3.0))
    plain = adhesive_pull_off(mu=mu, beta0=1.0, n=128, progress=False, search="bracket", options=AdhesiveOptions(nested=False))
    nested = adhesive_pull_off(mu=mu, beta0=1.0, n=128, progress=False, search="bracket", options=AdhesiveOptions(nested=True))
    assert plain.converged and nested.converged
    assert nested.path.coarse_states >= nested.n_steps and plain.path.coarse_states == 0
    # the bracket: the same approaches, hence the same discrete states, found from other warm starts
    # (the vertex states then sit at approaches that move with the loads' last digits)
    np.testing.assert_array_equal(nested.path.approach[:3], plain.path.approach[:3])
    np.testing.assert_allclose(nested.path.load[:3], plain.path.load[:3], rtol=RTOL_COLD_VS_WARM)
    assert nested.W_star == pytest.approx(plain.W_star, rel=RTOL_COLD_VS_WARM)
    # fewer outer (zone) iterations per fine state from the coarse state at the same approach
    assert nested.path.outer_iterations.sum() < plain.path.outer_iterations.sum()


def test_nested_cold_start_solves_the_same_hertz_problem(monkeypatch):
    from dhfield.bem import solver as adhesive_solver

    grid, z, delta = _hertz_problem(0.7, 128)
    nested = solve_adhesive(z, grid, delta, None)
    monkeypatch.setattr(adhesive_solver, "NESTED_COLD_MIN_N", 10**9)        # no coarser grid
    plain = solve_adhesive(z, grid, delta, None)
    assert nested.converged and plain.converged
    assert nested.load == pytest.approx(plain.load, rel=RTOL_COLD_VS_WARM)
    assert nested.peak_pressure == pytest.approx(plain.peak_pressure, rel=RTOL_COLD_VS_WARM)
    np.testing.assert_array_equal(nested.contact, plain.contact)

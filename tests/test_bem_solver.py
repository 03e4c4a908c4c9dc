"""Tests of dhfield.bem.solver (one state): the cropped contact CG, symmetry mode, flags, direct sums.

The cropped contact CG (the box of cells that can touch):

Without an adhesive stress the Polonsky-Keer CG runs on the box of cells whose rigid
gap is negative (every influence coefficient is positive, so no other cell can touch).
The references are the uncropped solve of the same discrete problem (an independent
route: other grids, other transforms, another iteration sequence) and the Hertz closed
form (:mod:`dhfield.models.hertz`).
"""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.models import hertz
from dhfield.bem import DugdaleLaw, ExponentialLaw, Grid, solve_adhesive
from dhfield.bem import solver as bem_solver
from dhfield.core.geometry import radius_ratio

#: Cropped and uncropped solves are the same discrete problem solved to the solver
#: tolerance (1e-6 of delta in complementarity): loads agree far below 1e-5.
RTOL_CROP = 1e-5
#: Hertz at N = 128 over 4 a (a = 16 cells): cell-averaged load, O(h^2) plus the
#: pixelated edge, measured 0.2 %; 1 % bounds it (N = 512: 0.002 %, bench_adhesive).
RTOL_HERTZ_LOAD_16_CELLS = 0.01
#: The gap outside the contact is >= 0 to the solver tolerance (relative to delta).
GAP_TOL = 1e-6


def _hertz(beta, n, half_width, x0=0.0):
    rho = float(radius_ratio(beta))
    r1, r2 = np.sqrt(rho), 1.0 / np.sqrt(rho)
    grid = Grid.centered(n, half_width, half_width_y=half_width * beta)
    x, y = grid.mesh()
    z = (x - x0) ** 2 / (2 * r1) + y * y / (2 * r2)  # Eq. (2)
    return grid, z, float(hertz.approach(1.0, beta))


@pytest.mark.parametrize("beta, x0", [(0.7, 0.0), (1.0, 0.6)])   # quadrant mode; full grid, off centre
def test_cropped_solve_is_the_full_grid_solve(beta, x0, monkeypatch):
    grid, z, delta = _hertz(beta, 128, 4.0, x0)
    op = bem_solver.get_operator(grid, symmetric=x0 == 0.0)
    box = bem_solver._contact_box(op, bem_solver.quadrant(z - delta) if x0 == 0.0 else z - delta)
    assert box is not None                                           # the crop is exercised
    cropped = solve_adhesive(z, grid, delta, None)
    monkeypatch.setattr(bem_solver, "CROP_MAX_FRACTION", 0.0)       # never crop
    full = solve_adhesive(z, grid, delta, None)
    assert cropped.converged and full.converged
    assert cropped.load == pytest.approx(full.load, rel=RTOL_CROP)
    assert cropped.peak_pressure == pytest.approx(full.peak_pressure, rel=RTOL_CROP)
    np.testing.assert_array_equal(cropped.contact, full.contact)
    # the gap is completed on the whole grid: no overlap anywhere, zero on the contact
    assert np.min(cropped.gap) >= -GAP_TOL * delta
    assert np.max(np.abs(cropped.gap[cropped.contact])) <= GAP_TOL * delta
    assert cropped.load == pytest.approx(float(hertz.load(1.0, beta)), rel=RTOL_HERTZ_LOAD_16_CELLS)


def test_crop_sizes_are_fft_friendly_and_cover_the_box():
    for cells in (1, 7, 23, 91, 97, 250):
        k = bem_solver._crop_size(cells, 10**6)
        assert k >= cells and k % 2 == 0
        m = k
        for f in (2, 3, 5):
            while m % f == 0:
                m //= f
        assert m == 1                                                # 5-smooth
    assert bem_solver._crop_size(250, 200) == 200                    # never beyond the grid


def test_no_crop_when_the_box_is_most_of_the_grid():
    grid, z, delta = _hertz(1.0, 64, 1.25)                           # contact fills the grid
    op = bem_solver.get_operator(grid, symmetric=True)
    assert bem_solver._contact_box(op, bem_solver.quadrant(z - delta)) is None
    assert bem_solver._contact_box(op, np.ones(op.input_shape)) is None   # no contact at all


# ============================================================================ the solver: symmetry, flags, direct sums
#: Symmetric (quadrant) mode and full grid solve the same discrete problem to the
#: solver tolerance (1e-9 here), through different iteration sequences.
RTOL_SYMMETRY = 1e-6


@pytest.mark.parametrize("law", [DugdaleLaw(1.0, 1.0), ExponentialLaw(1.0, 1.0)])
def test_symmetric_mode_equals_full_grid(law):
    grid = Grid.centered(32, 2.6)
    x, y = grid.mesh()
    z = x * x / 2.0 + y * y / 1.4
    kw = dict(tol=1e-9)
    sym = solve_adhesive(z, grid, 0.3, law, symmetric=True, **kw)
    full = solve_adhesive(z, grid, 0.3, law, symmetric=False, **kw)
    assert sym.converged and full.converged
    scale = law.max_stress
    np.testing.assert_allclose(sym.pressure, full.pressure, rtol=0, atol=RTOL_SYMMETRY * 10 * scale)
    assert sym.load == pytest.approx(full.load, rel=RTOL_SYMMETRY * 10)
    np.testing.assert_array_equal(sym.contact, full.contact)


def test_unconverged_state_is_flagged_not_raised():
    grid = Grid.centered(32, 2.6)
    x, y = grid.mesh()
    # one GMRES iteration per linear solve: the Newton iteration cannot reach the tolerance
    st = solve_adhesive((x * x + y * y) / 2, grid, 0.5, DugdaleLaw(1.0, 1.0), max_iter=1)
    assert not st.converged
    assert st.residual > 1e-6


#: Direct summation of influence coefficients vs the FFT convolution: rounding only.
RTOL_DIRECT_SUM = 1e-12


@pytest.mark.parametrize("symmetric", [True, False])
def test_direct_gap_correction_equals_the_convolution(symmetric):
    from dhfield.bem import get_operator
    from dhfield.bem.solver import _add_point_loads

    grid = Grid.centered(24, 1.3, half_width_y=0.8)
    op = get_operator(grid, symmetric=symmetric)
    rng = np.random.default_rng(8)
    p = rng.random(op.input_shape)
    cells = (rng.integers(0, op.input_shape[0], 5), rng.integers(0, op.input_shape[1], 5))
    amounts = rng.random(5)
    h = op(p)
    _add_point_loads(op, h, cells, amounts)
    q = p.copy()
    np.add.at(q, cells, amounts)
    np.testing.assert_allclose(h, op(q), rtol=0, atol=RTOL_DIRECT_SUM * float(np.max(np.abs(h))))


# ============================================================================ the edge criterion (issue 20)
@pytest.mark.parametrize("n, dx, dy", [(64, 0.05, 0.05), (256, 0.02, 0.0116), (96, 0.01, 0.03)])
def test_edge_width_ratio_is_the_stability_criterion_written_out(n, dx, dy):
    import math

    grid = Grid(n, n, dx, dy)
    law = DugdaleLaw(7.0, 1.0 / 7.0)       # sigma0 = mu, h0 = 1/mu in the paper's units (mu = 7)
    kappa = bem_solver.EDGE_WIDTH_FACTOR * (1.0 + 2.0 / math.pi * math.log(n))
    want = kappa * 7.0 * math.sqrt(dx * dy)  # edge width wanted, E* = 1
    assert bem_solver.edge_width_ratio(grid, law) == pytest.approx(want / (2.0 / 7.0), rel=1e-12)
    smooth = ExponentialLaw(7.0, 1.0 / 7.0)  # steepest slope sigma0/rho times the edge compliance
    assert bem_solver.edge_width_ratio(grid, smooth) == pytest.approx(kappa * 49.0 * math.sqrt(dx * dy), rel=1e-12)
    z = np.zeros((n, n))
    prob = bem_solver.AdhesiveProblem(z, grid, law, None, None, 1.0)
    assert prob.edge_width_ratio == bem_solver.edge_width_ratio(grid, law)
    assert prob.resolved == (prob.edge_width_ratio <= 1.0)
    assert prob.min_spread == pytest.approx(min(want, 2.0 / 7.0), rel=1e-12)


# --- the stretch step (issue 20: the predicted route's trapped cold states at mu = 10) ---------------------------
def _sphere_state(n=128, mu=2.0, delta=0.3, symmetric=None):
    grid = Grid.centered(n, 2.0)
    x, y = grid.mesh()
    law = DugdaleLaw(mu, 1.0 / mu)
    prob = bem_solver.AdhesiveProblem(x * x / 2.0 + y * y / 2.0, grid, law, symmetric, 1, 1.0)
    return prob, bem_solver.solve_problem(prob, delta, None, 1e-8, 20000)



# ============================================================================ the one start protocol
def test_coarser_problem_is_the_same_domain_law_and_symmetry_with_block_averaged_gap():
    grid = Grid.centered(32, 2.0)
    x, y = grid.mesh()
    z = (x * x + y * y) / 2
    prob = bem_solver.AdhesiveProblem(z, grid, DugdaleLaw(1.0, 1.0), None, 1, 1.0)
    coarse = bem_solver.coarser_problem(prob, 4)
    assert coarse.grid.shape == (8, 8) and coarse.symmetric == prob.symmetric
    assert coarse.grid.nx * coarse.grid.dx == pytest.approx(grid.nx * grid.dx)       # the same domain
    # the mean of a quadratic over a k x k block is its centre value plus (k^2 - 1) dx^2 / 12 per axis
    xc, yc = coarse.grid.mesh()
    shift = 2 * (4 ** 2 - 1) * grid.dx ** 2 / 12 / 2
    np.testing.assert_allclose(coarse.z_full, (xc * xc + yc * yc) / 2 + shift, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="k must divide"):
        bem_solver.coarser_problem(prob, 3)


def _sphere_64():
    """The sphere at lambda ~ 1 on 64^2 cells: (grid, x, y, z, law)."""
    grid = Grid.centered(64, 2.6)
    x, y = grid.mesh()
    return grid, x, y, (x * x + y * y) / 2, DugdaleLaw(1.0, 1.0)


def _count_nested_solves(monkeypatch):
    """Wrap solver.nested_solve; the returned list gains one entry per call."""
    real, calls = bem_solver.nested_solve, []

    def counting(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(bem_solver, "nested_solve", counting)
    return calls


def test_a_failed_start_falls_back_on_nested_iteration_to_the_same_state(monkeypatch):
    # the sphere at lambda ~ 1, N = 64: Newton from a start that fails (here: its first solve reported
    # diverged) goes on by nested iteration from the coarsest grid, to the state a cold solve finds
    import dataclasses

    import dhfield.bem.newton as newton

    grid, x, y, z, law = _sphere_64()
    cold = solve_adhesive(z, grid, -0.5, law)
    start = solve_adhesive(z, grid, 0.5, law)                 # a state with a far larger contact
    real, calls = newton.solve_state, []

    def first_fails(*args, **kwargs):
        st = real(*args, **kwargs)
        calls.append(st.reason)
        return dataclasses.replace(st, reason=newton.DIVERGED_MAX_IT) if len(calls) == 1 else st

    monkeypatch.setattr(newton, "solve_state", first_fails)
    nested = _count_nested_solves(monkeypatch)
    warm = solve_adhesive(z, grid, -0.5, law, guess=start)
    assert nested == [1] and warm.converged and cold.converged
    # the same discrete state, to the solver tolerance (1e-6 of the law's range in complementarity)
    assert warm.load == pytest.approx(cold.load, rel=1e-6)
    assert np.array_equal(warm.contact, cold.contact)


def test_an_analytic_zone_start_is_solved_by_nested_iteration_at_once(monkeypatch):
    # a Prediction with a zone and no contact pressure is an analytic start, not a solved state: the
    # state is solved by nested iteration from it (sigma0 on its zone), with no Newton try from it first
    import dhfield.bem.newton as newton
    from dhfield.bem.solver import Prediction

    grid, x, y, z, law = _sphere_64()
    prob = bem_solver.AdhesiveProblem(z, grid, law, None, 1, 1.0)
    zone = prob.to_work(law.max_stress * (x * x + y * y < 1.7 ** 2))
    real, shapes = newton.solve_state, []

    def recording(problem, *args, **kwargs):
        shapes.append(problem.grid.shape)
        return real(problem, *args, **kwargs)

    monkeypatch.setattr(newton, "solve_state", recording)
    nested = _count_nested_solves(monkeypatch)
    st = bem_solver.solve_problem(prob, -0.8, Prediction(np.zeros_like(zone), zone), 1e-6, 2000)
    assert st.converged and nested == [1]
    assert shapes.count(grid.shape) == 1            # the full grid solved once: nested iteration's last level


@pytest.mark.parametrize("tol, max_iter, krylov", [(1e-7, 500, 500), (1e-6, 10**6, None)])
def test_state_options_are_the_nested_options_with_the_tolerance_and_a_capped_krylov(tol, max_iter, krylov):
    """Every adhesive state (solve_problem, and the continuation's bordered solve) takes these options:
    NESTED_OPTIONS with the tolerance asked for and at most NESTED_OPTIONS.max_krylov GMRES iterations."""
    from dataclasses import replace

    from dhfield.bem.newton import NESTED_OPTIONS

    got = bem_solver.state_options(tol, max_iter)
    want = replace(NESTED_OPTIONS, tol=tol, max_krylov=NESTED_OPTIONS.max_krylov if krylov is None else krylov)
    assert got == want

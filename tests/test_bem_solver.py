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


#: Box and whole-grid inner solves stop at different iterates within the inner tolerance
#: (1e-7 of the zone fraction): pull-offs agree to ~1e-8 relative (measured at N = 256:
#: 1.3e-8 at lambda = 3); 1e-6 bounds it.
RTOL_ACTIVE_BOX = 1e-6


@pytest.mark.parametrize("lam", [1.0, 3.0])
def test_adhesive_box_solve_is_the_whole_grid_solve(lam, monkeypatch):
    from dhfield.core import transition
    from dhfield.bem import adhesive_pull_off

    mu = float(transition.tabor_from_maugis(lam))
    boxes = []
    box = bem_solver._box

    def counting_box(op, mask, margin, max_fraction):
        out = box(op, mask, margin, max_fraction)
        boxes.append(out is not None and margin == bem_solver.ACTIVE_BOX_MARGIN)
        return out

    monkeypatch.setattr(bem_solver, "_box", counting_box)
    boxed = adhesive_pull_off(mu=mu, beta0=1.0, n=96, progress=False)
    assert sum(boxes) > 0                                            # the box is exercised
    monkeypatch.setattr(bem_solver, "ACTIVE_BOX_MAX_FRACTION", 0.0)   # never box
    whole = adhesive_pull_off(mu=mu, beta0=1.0, n=96, progress=False)
    assert boxed.converged and whole.converged
    assert boxed.W_star == pytest.approx(whole.W_star, rel=RTOL_ACTIVE_BOX)
    assert boxed.a_star == pytest.approx(whole.a_star, rel=RTOL_ACTIVE_BOX)


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
    st = solve_adhesive((x * x + y * y) / 2, grid, 0.5, DugdaleLaw(1.0, 1.0), max_iter=1)
    assert not st.converged
    assert st.residual > 0 and st.iterations <= 1 + 1


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


def test_relaxed_edge_is_as_wide_as_stability_wants_and_never_resolved():
    grid = Grid(64, 64, 0.05, 0.05)
    law = DugdaleLaw(7.0, 1.0 / 7.0)
    z = np.zeros((64, 64))
    capped = bem_solver.AdhesiveProblem(z, grid, law, None, None, 1.0)
    relaxed = bem_solver.AdhesiveProblem(z, grid, law, None, None, 1.0, relaxed_edge=True)
    assert capped.edge_width_ratio > 1.0 and capped.min_spread == pytest.approx(2.0 / 7.0)
    assert relaxed.min_spread == pytest.approx(capped.edge_width_ratio * 2.0 / 7.0, rel=1e-12)
    assert not relaxed.resolved and not capped.resolved


def test_widest_edge_spreads_the_dugdale_edge_over_its_cap_and_keeps_the_problem():
    # a grid fine enough that its own edge (0.58 h0 wanted) is narrower than the cap 2 h0
    grid = Grid.centered(128, 2.0)
    x, y = grid.mesh()
    law = DugdaleLaw(2.0, 0.5)
    prob = bem_solver.AdhesiveProblem(x * x / 2.0 + y * y / 2.0, grid, law, None, 1, 1.0)
    wide = prob.with_widest_edge()
    assert prob.min_spread < 2.0 * law.range and not prob.widest_edge
    assert wide.widest_edge and wide.min_spread == 2.0 * law.range       # the cap, exactly
    assert wide.grid is prob.grid and wide.law is prob.law and wide.symmetric == prob.symmetric
    np.testing.assert_array_equal(wide.z_full, prob.z_full)
    # its state is a start of the grid's own edge: the state reached from it is the grid's own
    # (both solved to 1e-8: loads equal to 1e-6, far below the 2 % the wide edge itself moves here)
    st_wide = bem_solver.solve_problem(wide, 0.3, None, 1e-8, 20000)
    st_own = bem_solver.solve_problem(prob, 0.3, None, 1e-8, 20000)
    again = bem_solver.solve_problem(prob, 0.3, st_wide, 1e-8, 20000)
    assert st_wide.converged and st_own.converged and again.converged
    assert again.load == pytest.approx(st_own.load, rel=1e-6)
    assert abs(st_wide.load / st_own.load - 1.0) > 1e-3                # a different law: not a no-op
    with pytest.raises(ValueError, match="Dugdale"):
        bem_solver.AdhesiveProblem(x * x / 2.0 + y * y / 2.0, grid, ExponentialLaw(2.0, 0.5), None, 1,
                                   1.0).with_widest_edge()


# --- the stretch step (issue 20: the predicted route's trapped cold states at mu = 10) ---------------------------
def _sphere_state(n=128, mu=2.0, delta=0.3, symmetric=None):
    grid = Grid.centered(n, 2.0)
    x, y = grid.mesh()
    law = DugdaleLaw(mu, 1.0 / mu)
    prob = bem_solver.AdhesiveProblem(x * x / 2.0 + y * y / 2.0, grid, law, symmetric, 1, 1.0)
    return prob, bem_solver.solve_problem(prob, delta, None, 1e-8, 20000)


@pytest.mark.parametrize("symmetric", [True, False])
def test_stretched_field_is_the_field_at_scaled_coordinates(symmetric):
    """Bilinear interpolation is exact for a linear field: f(x, y) -> f(x/sx, y/sy) inside the grid."""
    grid = Grid.centered(32, 2.0, ny=16, half_width_y=1.0)
    law = DugdaleLaw(2.0, 0.5)
    x, y = grid.mesh()
    prob = bem_solver.AdhesiveProblem(x * x + y * y, grid, law, symmetric, 1, 1.0)
    xw, yw = (prob.to_work(x), prob.to_work(y))
    f = 3.0 * xw - 2.0 * yw + 1.0
    assert np.array_equal(bem_solver._stretched(prob, f, 1.0, 1.0), f)
    sx, sy = 1.07, 0.95
    got = bem_solver._stretched(prob, f, sx, sy)
    inside = ((xw / sx >= xw.min()) & (xw / sx <= xw.max()) & (yw / sy >= yw.min()) & (yw / sy <= yw.max()))
    np.testing.assert_allclose(got[inside], (3.0 * xw / sx - 2.0 * yw / sy + 1.0)[inside], atol=1e-12)


def test_stretch_step_undoes_a_stretch_of_a_solved_state_to_within_a_cell():
    """A converged state stretched by (sx, sy) is stretched back: the product of the factors is 1
    within a cell of the contact radius (the second moments locate the edge to a cell, not better)."""
    prob, st = _sphere_state()
    assert st.converged
    p, s = prob.to_work(st.repulsive_pressure), prob.stress_of_state(st)
    a = st.summary()["a"]
    cell = prob.grid.dx / a
    sigma0 = prob.law.max_stress
    unchanged = bem_solver.stretch_step(prob, 0.3, p, s, 1e-6, 20000)
    assert unchanged.factors == (1.0, 1.0)                      # a solution asks for no stretch
    for sx, sy in [(1.03, 1.03), (1.02, 0.98)]:
        ps = bem_solver._stretched(prob, p, sx, sy)
        ss = np.clip(bem_solver._stretched(prob, s, sx, sy), 0.0, sigma0)
        step = bem_solver.stretch_step(prob, 0.3, ps, ss, 1e-6, 20000)
        assert abs(step.factors[0] * sx - 1.0) < cell and abs(step.factors[1] * sy - 1.0) < cell
        assert step.iterations > 0 and np.all((step.stress >= 0) & (step.stress <= sigma0))


def test_stretch_steps_leave_the_converged_state_unchanged():
    """With a stretch step every few outer iterations the solver converges to the same state."""
    prob, st = _sphere_state()
    p, s = prob.to_work(st.repulsive_pressure), prob.stress_of_state(st)
    ps = bem_solver._stretched(prob, p, 1.03, 1.03)
    ss = np.clip(bem_solver._stretched(prob, s, 1.03, 1.03), 0.0, prob.law.max_stress)
    for every in (None, 10):
        again = bem_solver.solve_problem(prob, 0.3, bem_solver.Prediction(ps, ss), 1e-8, 20000, stretch_every=every)
        assert again.converged
        # both within the tolerance 1e-8 of h0 in the gap: the load agrees to far better than 1e-6
        assert abs(again.load - st.load) < 1e-6 * abs(st.load)


def test_a_longer_anderson_memory_converges_to_the_same_state():
    """Memory 30 without restarts (the high-mu route's mixing) solves the same discrete problem."""
    prob, st = _sphere_state()
    p, s = prob.to_work(st.repulsive_pressure), prob.stress_of_state(st)
    ps = bem_solver._stretched(prob, p, 1.03, 1.03)
    ss = np.clip(bem_solver._stretched(prob, s, 1.03, 1.03), 0.0, prob.law.max_stress)
    again = bem_solver.solve_problem(prob, 0.3, bem_solver.Prediction(ps, ss), 1e-8, 20000,
                                     stretch_every=10, anderson_memory=bem_solver.STRETCH_ANDERSON_MEMORY)
    assert again.converged
    # both within the tolerance 1e-8 of h0 in the gap: the load agrees to far better than 1e-6
    assert abs(again.load - st.load) < 1e-6 * abs(st.load)


def test_give_up_stops_a_stalled_start_early_and_leaves_a_converging_one_alone():
    """give_up_after (a race's start): a converging state is solved as without it; one that cannot
    reach its tolerance (1e-16, below the round-off floor of the residual, ~2e-15 here) stops,
    flagged, on the first window whose second half brought no halving of the best residual, with its
    best iterate.  (This start creeps at residual ~0.13 for its first ~10 outer iterations: a window
    of 10 gives it up, one of 20 does not.)"""
    prob, st = _sphere_state()
    p, s = prob.to_work(st.repulsive_pressure), prob.stress_of_state(st)
    start = bem_solver.Prediction(bem_solver._stretched(prob, p, 1.03, 1.03),
                                  np.clip(bem_solver._stretched(prob, s, 1.03, 1.03), 0.0, prob.law.max_stress))
    plain = bem_solver.solve_problem(prob, 0.3, start, 1e-8, 20000)
    early = bem_solver.solve_problem(prob, 0.3, start, 1e-8, 20000, give_up_after=20)
    # both within the tolerance 1e-8 of h0 in the gap: the loads agree to far better than 1e-6
    assert plain.converged and early.converged and abs(early.load - plain.load) < 1e-6 * abs(plain.load)
    assert not bem_solver.solve_problem(prob, 0.3, start, 1e-8, 20000, give_up_after=10).converged
    stuck = bem_solver.solve_problem(prob, 0.3, start, 1e-16, 10 ** 6)
    given_up = bem_solver.solve_problem(prob, 0.3, start, 1e-16, 10 ** 6, give_up_after=20)
    assert not stuck.converged and not given_up.converged
    assert 20 <= given_up.outer_iterations < stuck.outer_iterations
    assert given_up.residual > 1e-16 and abs(given_up.load - st.load) < 1e-6 * abs(st.load)
    with pytest.raises(ValueError, match="give_up_after must be None or an integer >= 1"):
        bem_solver.solve_problem(prob, 0.3, st, 1e-6, 100, give_up_after=0)


@pytest.mark.parametrize("bad", [0, -3, 2.5, True, "30"])
def test_anderson_memory_is_a_positive_integer_or_none(bad):
    prob, st = _sphere_state()
    with pytest.raises(ValueError, match="anderson_memory must be None or an integer >= 1"):
        bem_solver.solve_problem(prob, 0.3, st, 1e-6, 100, anderson_memory=bad)


def test_stretch_is_taken_only_when_the_state_stalls():
    """A residual halving every few iterations is converging; one that stays put has stalled."""
    converging = [0.4 * 0.8 ** k for k in range(30)]                # 0.8^15 = 0.035 over half a window
    flat = [2e-2 * (1.0 + 0.1 * (-1) ** k) for k in range(30)]       # the mu = 10 trapped states
    slow = [2e-2 * 0.97 ** k for k in range(30)]                    # 0.97^15 = 0.63 > STALL_RATIO
    assert not bem_solver._stalled(converging, 30)
    assert bem_solver._stalled(flat, 30) and bem_solver._stalled(slow, 30)
    assert not bem_solver._stalled(flat[:29], 30)                     # not a whole window yet


def _anderson_reference(x0, fixed_point, memory, steps):
    """Type-II Anderson mixing written out from its definition (Walker & Ni 2011, Eq. 1.2 with
    beta = 1): the least-squares gamma of the last ``memory`` residual differences, by lstsq."""
    xs, fs = [x0], [fixed_point(x0) - x0]
    for _ in range(steps):
        x, f = xs[-1], fs[-1]
        n = min(len(xs) - 1, memory)
        if n:
            dX = np.array([xs[-i] - xs[-i - 1] for i in range(n, 0, -1)]).T
            dF = np.array([fs[-i] - fs[-i - 1] for i in range(n, 0, -1)]).T
            gamma = np.linalg.lstsq(dF, f, rcond=None)[0]
            new = x + f - (dX + dF) @ gamma
        else:
            new = x + f
        xs.append(new)
        fs.append(fixed_point(new) - new)
    return xs


def test_anderson_mixing_is_type_two_anderson_past_its_ring_buffer():
    """The ring buffer and the Gram matrix updated row by row give the textbook iterates, also after
    the history wraps (memory 3, 8 steps), on a contracting linear map."""
    rng = np.random.default_rng(1)
    a = 0.15 * rng.standard_normal((12, 12))          # spectral radius ~0.5: a contraction
    b = rng.standard_normal(12)

    def g(x):
        return a @ x + b

    ref = _anderson_reference(np.zeros(12), g, 3, 8)
    acc = bem_solver.AndersonMixing(memory=3)
    x = np.zeros(12)
    for k in range(8):
        x = acc.step(x, g(x) - x)
        # the Tikhonov term (1e-12 of the Gram trace) moves gamma by ~1e-12 relative
        np.testing.assert_allclose(x, ref[k + 1], rtol=1e-8, atol=1e-10)


def test_anderson_mixing_solves_a_linear_fixed_point_in_dimension_plus_one_steps():
    """With memory >= the dimension, type-II Anderson on x = A x + b is GMRES in disguise
    (Walker & Ni 2011, Thm 2.2): the fixed point is reached after dim + 1 steps."""
    rng = np.random.default_rng(2)
    dim = 6
    a = 0.9 * np.linalg.qr(rng.standard_normal((dim, dim)))[0]     # eigenvalues of modulus 0.9
    b = rng.standard_normal(dim)
    exact = np.linalg.solve(np.eye(dim) - a, b)
    acc = bem_solver.AndersonMixing(memory=dim)
    x = np.zeros(dim)
    for _ in range(dim + 1):
        x = acc.step(x, a @ x + b - x)
    # plain iteration would still be 0.9^7 ~ 0.48 of the way off; the residual is rounding only
    np.testing.assert_allclose(x, exact, rtol=1e-6)

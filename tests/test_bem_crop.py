"""Tests of the cropped contact CG of dhfield.bem.solver (the box of cells that can touch).

Without an adhesive stress the Polonsky-Keer CG runs on the box of cells whose rigid
gap is negative (every influence coefficient is positive, so no other cell can touch).
The references are the uncropped solve of the same discrete problem (an independent
route: other grids, other transforms, another iteration sequence) and the Hertz closed
form (:mod:`dhfield.hertz`).
"""
from __future__ import annotations

import numpy as np
import pytest

from dhfield import hertz
from dhfield.bem import Grid, solve_adhesive
from dhfield.bem import solver as bem_solver
from dhfield.geometry import radius_ratio

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
    from dhfield import transition
    from dhfield.bem import adhesive_pull_off

    mu = float(transition.tabor_from_maugis(lam))
    boxes = []
    box = bem_solver._box

    def counting_box(op, mask, margin, max_fraction):
        out = box(op, mask, margin, max_fraction)
        boxes.append(out is not None and margin == bem_solver.ACTIVE_BOX_MARGIN)
        return out

    monkeypatch.setattr(bem_solver, "_box", counting_box)
    boxed = adhesive_pull_off(mu, 1.0, 96, progress=False)
    assert sum(boxes) > 0                                            # the box is exercised
    monkeypatch.setattr(bem_solver, "ACTIVE_BOX_MAX_FRACTION", 0.0)   # never box
    whole = adhesive_pull_off(mu, 1.0, 96, progress=False)
    assert boxed.converged and whole.converged
    assert boxed.W_star == pytest.approx(whole.W_star, rel=RTOL_ACTIVE_BOX)
    assert boxed.a_star == pytest.approx(whole.a_star, rel=RTOL_ACTIVE_BOX)

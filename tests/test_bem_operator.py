"""The half-space operator and the contact solver on grids shaped to slender contacts (nx != ny, square cells).

Issue 20: the automatic grid of a slender contact (beta0 < 0.45) has about square cells,
nx along the major axis and ny < nx along the minor one.  Here the operator and the
solver on such grids are checked against the Hertz closed form (:mod:`dhfield.models.hertz`,
an independent reference) and against a direct double sum of Love's influence
coefficients (:func:`dhfield.bem.love_influence`).
"""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.models import hertz
from dhfield.bem import Grid, HalfSpaceOperator, love_influence, quadrant, solve_adhesive, unfold_quadrant
from dhfield.core.geometry import radius_ratio

#: DC-FFT against the direct sum of the same coefficients: round-off of the transforms only.
RTOL_DIRECT = 1e-12
#: Hertz load on 288 x 56 about square cells over 1.25 a x 1.25 b at beta = 0.18 (a = 115 cells,
#: b = 21): measured 2.9e-5 (128 x 128 stretched cells: 2.5e-5); 5e-4 leaves room for other
#: platforms' FFT round-off in the CG stopping point and still fails a mis-scaled cell area (~1e-2).
RTOL_HERTZ_LOAD = 5e-4


def test_operator_on_a_slender_square_cell_grid_is_the_direct_love_sum():
    grid = Grid.centered(40, 2.0, ny=12, half_width_y=0.6)          # dx = dy = 0.1, 40 x 12
    assert grid.dx == pytest.approx(grid.dy, rel=1e-12)
    rng = np.random.default_rng(3)
    q = rng.standard_normal((20, 6))
    p = unfold_quadrant(q)                                           # even in x and y
    x, y = grid.mesh()
    direct = np.zeros_like(p)
    for i in range(grid.nx):
        for j in range(grid.ny):
            direct[i, j] = np.sum(love_influence(x[i, j] - x, y[i, j] - y, grid.dx / 2, grid.dy / 2) * p)
    full = HalfSpaceOperator(grid)(p)
    sym = unfold_quadrant(HalfSpaceOperator(grid, symmetric=True)(quadrant(p)))
    scale = np.max(np.abs(direct))
    assert np.max(np.abs(full - direct)) <= RTOL_DIRECT * scale * 10
    assert np.max(np.abs(sym - direct)) <= RTOL_DIRECT * scale * 10


def test_slender_hertz_contact_on_square_cells_matches_the_closed_form():
    beta = 0.18                                                      # crossing ~30 deg
    rho = float(radius_ratio(beta))
    grid = Grid.centered(288, 1.25, ny=56, half_width_y=1.25 * beta)
    assert 0.9 < grid.dx / grid.dy < 1.1                             # about square
    x, y = grid.mesh()
    z = x * x / (2 * np.sqrt(rho)) + y * y * np.sqrt(rho) / 2        # Eq. (2), R'R'' = 1
    st = solve_adhesive(z, grid, float(hertz.approach(1.0, beta)), None)
    assert st.converged
    assert st.load == pytest.approx(float(hertz.load(1.0, beta)), rel=RTOL_HERTZ_LOAD)
    a, b = st.contact_semi_axes()                                    # second moments: within a cell
    assert abs(a - 1.0) <= grid.dx and abs(b - beta) <= grid.dy


def test_planner_effort_comes_from_the_environment(monkeypatch):
    """$DHFIELD_FFTW_PLANNER sets the default planner flag; a bad value is an error naming it."""
    from dhfield.bem import operator as op

    monkeypatch.delenv("DHFIELD_FFTW_PLANNER", raising=False)
    assert op.default_planner_effort() == "FFTW_MEASURE"
    monkeypatch.setenv("DHFIELD_FFTW_PLANNER", "FFTW_ESTIMATE")
    assert op.default_planner_effort() == "FFTW_ESTIMATE"
    assert op.HalfSpaceOperator(op.Grid.centered(16, 2.0)).planner_effort == "FFTW_ESTIMATE"
    monkeypatch.setenv("DHFIELD_FFTW_PLANNER", "fast")
    with pytest.raises(ValueError, match="DHFIELD_FFTW_PLANNER"):
        op.default_planner_effort()
    with pytest.raises(ValueError, match="planner_effort must be one of"):
        op.check_planner_effort("FFTW_FAST")

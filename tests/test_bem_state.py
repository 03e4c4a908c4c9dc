"""Tests of the BEM state (dhfield.bem.state): second-moment semi-axes and validation."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.bem import ContactState, DugdaleLaw, Grid, mask_semi_axes

#: Second moments of a uniform ellipse are exact: a^2/4, b^2/4 (rounding only).
RTOL_MOMENTS = 1e-12
#: A rasterised ellipse (cell in if its centre is) has semi-axes off by O(h); the
#: constant measured here is below 1 cell, so 1.5 cells is a bound that still fails on
#: an O(1) error (e.g. sqrt(<x^2>) without the factor 2).
CELLS_RASTER = 1.5


def _ellipse_mask(grid, a, b, angle=0.0):
    x, y = grid.mesh()
    c, s = np.cos(angle), np.sin(angle)
    u, v = c * x + s * y, -s * x + c * y
    return (u / a) ** 2 + (v / b) ** 2 <= 1.0


@pytest.mark.parametrize("n", [64, 256])
def test_rasterised_ellipse_semi_axes_order_h(n):
    a, b = 1.0, 0.55
    grid = Grid.centered(n, 1.3)
    ra, rb = mask_semi_axes(_ellipse_mask(grid, a, b), grid)
    assert abs(ra - a) <= CELLS_RASTER * grid.dx
    assert abs(rb - b) <= CELLS_RASTER * grid.dx


def test_semi_axes_converge_under_refinement():
    a, b = 1.0, 0.55
    errs = []
    for n in (64, 128, 256, 512):
        grid = Grid.centered(n, 1.3)
        ra, rb = mask_semi_axes(_ellipse_mask(grid, a, b, angle=0.3), grid)
        errs.append(abs(ra - a) + abs(rb - b))
    # O(h) or better on average over the refinements (single steps may be noisy)
    assert errs[-1] < errs[0] / 4.0


def test_rotated_ellipse_principal_axes():
    grid = Grid.centered(256, 1.3)
    ra, rb = mask_semi_axes(_ellipse_mask(grid, 1.0, 0.5, angle=0.7), grid)
    assert ra == pytest.approx(1.0, abs=CELLS_RASTER * grid.dx)
    assert rb == pytest.approx(0.5, abs=CELLS_RASTER * grid.dx)


def test_uniform_weights_give_exact_moments():
    # a uniform rectangle of cells: <x^2> is the discrete sum, compared with the closed form
    grid = Grid(8, 8, 1.0, 1.0)
    w = np.ones(grid.shape)
    ra, rb = mask_semi_axes(w, grid)
    mean_x2 = float(np.mean(grid.x ** 2))  # (n^2 - 1)/12 for unit cells
    assert mean_x2 == pytest.approx((64 - 1) / 12, rel=RTOL_MOMENTS)
    assert ra == pytest.approx(2 * np.sqrt(mean_x2), rel=RTOL_MOMENTS)
    assert rb == pytest.approx(ra, rel=RTOL_MOMENTS)
    assert mask_semi_axes(np.zeros(grid.shape), grid) == (0.0, 0.0)


def _state(grid, contact, cohesive):
    z = np.zeros(grid.shape)
    return ContactState(grid=grid, pressure=z, gap=z, approach=0.0, load=0.0, contact=contact,
                        cohesive=cohesive, law=DugdaleLaw(1.0, 1.0), converged=True, iterations=0,
                        residual=0.0)


def test_state_semi_axes_and_betas():
    grid = Grid.centered(128, 1.3)
    contact = _ellipse_mask(grid, 0.8, 0.4)
    zone = _ellipse_mask(grid, 1.0, 0.6) & ~contact
    st = _state(grid, contact, zone.astype(float))
    a, b = st.contact_semi_axes()
    c, d = st.cohesive_semi_axes()
    tol = CELLS_RASTER * grid.dx
    assert (a, b) == (pytest.approx(0.8, abs=tol), pytest.approx(0.4, abs=tol))
    assert (c, d) == (pytest.approx(1.0, abs=tol), pytest.approx(0.6, abs=tol))
    assert st.beta_ab == pytest.approx(b / a, rel=RTOL_MOMENTS)
    assert st.beta_cd == pytest.approx(d / c, rel=RTOL_MOMENTS)
    s = st.summary()
    assert s["a"] == a and s["d"] == d and s["converged"] is True


def test_state_without_contact_has_nan_beta():
    grid = Grid.centered(16, 1.0)
    st = _state(grid, np.zeros(grid.shape, bool), np.zeros(grid.shape))
    assert np.isnan(st.beta_ab) and np.isnan(st.beta_cd)
    assert not st.in_contact


def test_state_rejects_wrong_shapes():
    grid = Grid.centered(16, 1.0)
    with pytest.raises(ValueError, match="contact must have the grid shape"):
        _state(grid, np.zeros((8, 8), bool), np.zeros(grid.shape))

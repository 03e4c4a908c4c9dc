"""Polar resampling of grid fields (dhfield.analysis.polar)."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield import bem
from dhfield.analysis import polar

#: Cubic splines reproduce a quadratic exactly except for the boundary condition, whose
#: effect decays like 0.27^k at k cells from the domain edge: >= 16 cells here (~1e-10).
ATOL_POLAR_QUADRATIC = 1e-8


def test_polar_resampling_of_a_quadratic_field():
    grid = bem.Grid.centered(64, 2.0)
    x, y = grid.mesh()
    f = 3.0 * x**2 + 2.0 * y**2 - x * y
    r, th = polar.polar_grid(1.0, 31, 19, theta_max=2 * np.pi)
    fp = polar.to_polar(f, grid, r, th)
    ref = 3.0 * (r[:, None] * np.cos(th)) ** 2 + 2.0 * (r[:, None] * np.sin(th)) ** 2 \
        - r[:, None] ** 2 * np.cos(th) * np.sin(th)
    assert fp.shape == (31, 19)
    assert np.max(np.abs(fp - ref)) <= ATOL_POLAR_QUADRATIC
    assert np.isnan(polar.to_polar(f, grid, [5.0], [0.0])).all()
    with pytest.raises(ValueError, match="field"):
        polar.to_polar(f[:10], grid, r, th)
